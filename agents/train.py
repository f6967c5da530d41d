"""Train a fighter with Stable-Baselines3 PPO: a scripted curriculum or self-play.

    python -m agents.train [--config default] [--out runs/NAME] [--seed N] [--steps N] [--resume]
    python -m agents.train --config selfplay --init runs/default/final.zip  # then self-play

Config-driven (`configs/train/*.toml`). Checkpoints every `checkpoint_every` steps into
`OUT/checkpoints/`, and `OUT/latest.zip` + `OUT/train_state.json` always hold the newest one:
Ctrl-C or a crash saves them first, and `--resume` continues from them. Logs go to TensorBoard
when it is installed. The finished model is `OUT/final.zip`; `agents.evaluate` measures it.
"""

from __future__ import annotations

import argparse
import dataclasses
import importlib.util
import json
import shutil
import sys
import time
from pathlib import Path
from typing import Any

import torch
from stable_baselines3 import PPO
from stable_baselines3.common.callbacks import BaseCallback, CallbackList
from stable_baselines3.common.env_util import make_vec_env
from stable_baselines3.common.utils import set_random_seed
from stable_baselines3.common.vec_env import DummyVecEnv, VecEnv, VecNormalize

from vooga_env.config import ConfigError
from vooga_env.gym_env import FightEnv
from vooga_env.models import load_model

from .callbacks import (
    NORMALIZER_FILE,
    STATE_FILE,
    CurriculumCallback,
    SelfPlayCallback,
    StateCheckpointCallback,
    save_checkpoint,
)
from .train_config import TrainConfig, load_train_config


def make_envs(config: TrainConfig) -> VecEnv:
    """`n_envs` single-agent fights in one process; the learner's seat is drawn each episode."""
    envs = make_vec_env(
        FightEnv,
        n_envs=config.n_envs,
        seed=config.seed,
        vec_env_cls=DummyVecEnv,
        env_kwargs={"config": config.fight, "opponent": "idle", "seat": "random"},
    )
    if config.ppo.normalize_reward:
        return VecNormalize(envs, norm_obs=False, norm_reward=True, gamma=config.ppo.gamma)
    return envs


def build_model(config: TrainConfig, envs: VecEnv, folder: Path) -> PPO:
    ppo = config.ppo
    tensorboard = str(folder / "tb") if importlib.util.find_spec("tensorboard") else None
    return PPO(
        "MlpPolicy",
        envs,
        learning_rate=ppo.learning_rate,
        n_steps=ppo.n_steps,
        batch_size=ppo.batch_size,
        n_epochs=ppo.n_epochs,
        gamma=ppo.gamma,
        gae_lambda=ppo.gae_lambda,
        ent_coef=ppo.ent_coef,
        clip_range=ppo.clip_range,
        policy_kwargs={"net_arch": list(ppo.net_arch)},
        tensorboard_log=tensorboard,
        seed=config.seed,
        device="cpu",
        verbose=0,
    )


def start_from(model: PPO, path: str, config: TrainConfig) -> None:
    """Copy a saved model's weights into `model` (its own hyperparameters stay the config's)."""
    try:
        saved = load_model(path)
    except (FileNotFoundError, ValueError) as error:  # no file, or spaces that don't fit
        raise ConfigError(f"init = {path!r}: {error}") from error
    try:
        model.policy.load_state_dict(saved.policy.state_dict())
    except RuntimeError as error:
        raise ConfigError(
            f"init = {path!r}: its network does not fit net_arch = {list(config.ppo.net_arch)} "
            f"({str(error).splitlines()[0]})"
        ) from error


class StopAfter(BaseCallback):
    """Stops training once `minutes` of wall time have passed (the recipe's time budget)."""

    def __init__(self, minutes: float) -> None:
        super().__init__()
        self.deadline = time.monotonic() + 60.0 * minutes

    def _on_step(self) -> bool:
        return time.monotonic() < self.deadline


def train(
    config: TrainConfig,
    folder: Path,
    resume: bool = False,
    progress: bool = True,
    minutes: float | None = None,
    overwrite: bool = False,
) -> Path:
    """Run (or continue) one training for at most `minutes` (default: the config's budget).

    A fresh run refuses a folder that holds one already, unless `overwrite` (which empties it
    first): no run's checkpoints are lost, or mixed with another's. Returns the final model's path.
    """
    if not resume and (folder / "latest.zip").exists():
        if not overwrite:
            raise FileExistsError(
                f"{folder} holds a run already: --resume continues it, --overwrite starts over "
                "(deleting it), or pick another --out"
            )
        shutil.rmtree(folder)
    torch.set_num_threads(1)
    set_random_seed(config.seed)
    folder.mkdir(parents=True, exist_ok=True)
    envs = make_envs(config)
    state: dict[str, Any] = {}
    if resume:
        latest = folder / "latest.zip"
        if not latest.is_file():
            raise FileNotFoundError(f"--resume: no checkpoint at {latest}")
        state = json.loads((folder / STATE_FILE).read_text())
        if isinstance(envs, VecNormalize) and (folder / NORMALIZER_FILE).is_file():
            envs = VecNormalize.load(str(folder / NORMALIZER_FILE), envs.venv)
        model = PPO.load(latest, env=envs, device="cpu")
    else:
        (folder / "train_config.json").write_text(json.dumps(dataclasses.asdict(config), indent=2))
        model = build_model(config, envs, folder)
        if config.init:
            start_from(model, config.init, config)
    if config.mode == "selfplay":
        opponents: Any = SelfPlayCallback(config.selfplay, folder / "snapshots", config.seed, state)
        (folder / "snapshots").mkdir(exist_ok=True)
    else:
        opponents = CurriculumCallback(config.curriculum, config.seed, state.get("stage", 0))
    every = max(config.checkpoint_every // config.n_envs, 1)
    checkpoints = StateCheckpointCallback(every, folder, [opponents])
    minutes = minutes or config.minutes
    callbacks = [opponents, checkpoints] + ([StopAfter(minutes)] if minutes else [])
    remaining = config.total_timesteps - model.num_timesteps
    try:
        if remaining > 0:
            model.learn(
                remaining,
                callback=CallbackList(callbacks),
                reset_num_timesteps=not resume,
                progress_bar=progress,
            )
    except BaseException:
        save_checkpoint(model, folder, [opponents])
        raise
    save_checkpoint(model, folder, [opponents])
    final = folder / "final.zip"
    model.save(final)
    return final


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="vooga-train", description=__doc__.splitlines()[0])
    parser.add_argument("--config", default="default", help="a name in configs/train or a path")
    parser.add_argument("--out", type=Path, help="run folder (default runs/CONFIG)")
    parser.add_argument("--seed", type=int)
    parser.add_argument("--steps", type=int, help="total timesteps (overrides the config)")
    parser.add_argument("--init", help="start from this saved model's weights (overrides)")
    parser.add_argument("--resume", action="store_true", help="continue from OUT/latest.zip")
    parser.add_argument("--overwrite", action="store_true", help="start over in a used OUT")
    parser.add_argument("--minutes", type=float, help="stop after this much wall time")
    parser.add_argument("--no-progress", action="store_true", help="no progress bar")
    args = parser.parse_args(argv)
    try:
        config = load_train_config(
            args.config, seed=args.seed, total_timesteps=args.steps, init=args.init
        )
    except ConfigError as error:
        parser.error(str(error))
    folder = args.out or Path("runs") / config.name
    try:
        final = train(
            config,
            folder,
            resume=args.resume,
            progress=not args.no_progress,
            minutes=args.minutes,
            overwrite=args.overwrite,
        )
    except KeyboardInterrupt:
        print(
            f"\ninterrupted: the last checkpoint is {folder / 'latest.zip'}; "
            f"continue with --resume --out {folder}",
            file=sys.stderr,
        )
        return 130
    except (FileNotFoundError, FileExistsError, ConfigError) as error:
        parser.error(str(error))
    print(f"trained: {final}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
