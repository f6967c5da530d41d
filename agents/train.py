"""Train a fighter with Stable-Baselines3 PPO: a scripted curriculum or self-play.

    python -m agents.train [--config default] [--out runs/NAME] [--seed N] [--steps N] [--resume]
    python -m agents.train --config selfplay --init runs/default/final.zip  # then self-play

Config-driven (`configs/train/*.toml`), every key checked before any work starts. Checkpoints
every `checkpoint_every` steps (and at step 0, on Ctrl-C and on a crash) into
`OUT/checkpoints/`, each file written atomically; `OUT/train_state.json` commits the newest one
(it names it, with its SHA-256) and `OUT/latest.zip` links to it. `--resume` continues from the
committed checkpoint, whatever moment a kill came at. A model with NaN or inf weights is never
saved: the run stops, says what diverged, and keeps the last good checkpoint. One run at a time
uses OUT (a lock names the pid holding it). Logs go to TensorBoard when it is installed. The
finished model is `OUT/final.zip`; `agents.evaluate` measures it.
"""

from __future__ import annotations

import argparse
import importlib.util
import json
import sys
import time
from functools import partial
from pathlib import Path
from typing import Any, Protocol

import torch
from gymnasium.wrappers import ReshapeObservation
from stable_baselines3 import PPO
from stable_baselines3.common.callbacks import BaseCallback, CallbackList
from stable_baselines3.common.env_util import make_vec_env
from stable_baselines3.common.utils import set_random_seed
from stable_baselines3.common.vec_env import DummyVecEnv, VecEnv, VecFrameStack, VecNormalize

from vooga_env.envs.gym_env import FightEnv
from vooga_env.game.config import ConfigError
from vooga_env.policies.facing_policy import mlp_policy
from vooga_env.policies.models import load_model

from .callbacks import (
    CurriculumCallback,
    EntropySchedule,
    LearningRateSchedule,
    SelfPlayCallback,
    StateCheckpointCallback,
    StopWhenRequested,
)
from .checkpoints import (
    STATE_FILE,
    BrokenRun,
    Diverged,
    RunLock,
    RunLocked,
    atomic_write,
    check_finite,
    holds_run,
    resume_state,
    save_checkpoint,
    start_fresh,
)
from .common import _minutes, budget_minutes, quiet_logger, stop_on_signals
from .train_config import PPOConfig, TrainConfig, load_train_config


def make_envs(config: TrainConfig, opponent: str = "idle", seed: int | None = None) -> VecEnv:
    """`n_envs` single-agent fights in one process; the learner's seat is drawn each episode.
    With pixels, each image gets a channel axis (SB3's CnnPolicy takes (H, W, C)) and the last
    `frame_stack` images are stacked."""
    kwargs: dict[str, Any] = {"config": config.fight, "opponent": opponent, "seat": "random"}
    wrapper = None
    if config.obs_type == "pixels":
        kwargs.update(obs_type="pixels", pixel_size=tuple(config.pixel_size))
        shape = (*config.pixel_size, 1)
        wrapper = partial(ReshapeObservation, shape=shape)
    envs = make_vec_env(
        FightEnv,
        n_envs=config.n_envs,
        seed=config.seed if seed is None else seed,
        vec_env_cls=DummyVecEnv,
        env_kwargs=kwargs,
        wrapper_class=wrapper,
    )
    if config.frame_stack > 1:
        envs = VecFrameStack(envs, config.frame_stack)
    if config.ppo.normalize_reward:
        return VecNormalize(envs, norm_obs=False, norm_reward=True, gamma=config.ppo.gamma)
    return envs


def policy_class(ppo: PPOConfig, obs_type: str = "vector") -> Any:
    """SB3's policy for the config: CnnPolicy on pixels, else as `frame` says (mlp_policy)."""
    return "CnnPolicy" if obs_type == "pixels" else mlp_policy(ppo.frame)


def build_model(config: TrainConfig, envs: VecEnv, folder: Path) -> PPO:
    ppo = config.ppo
    tensorboard = str(folder / "tb") if importlib.util.find_spec("tensorboard") else None
    return PPO(
        policy_class(ppo, config.obs_type),
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


def load_init(config: TrainConfig) -> Any:
    """The model `init` names (None for a new network), or a ConfigError saying why not."""
    if not config.init:
        return None
    try:
        model = load_model(config.init)
        check_finite(model, model.num_timesteps)
    except (FileNotFoundError, ValueError, Diverged) as error:  # not a usable model
        raise ConfigError(f"init = {config.init!r}: {error}") from error
    extractor = model.policy.mlp_extractor
    expected = list(config.ppo.net_arch)
    for head, layers in (("policy", extractor.policy_net), ("value", extractor.value_net)):
        sizes = [layer.out_features for layer in layers if isinstance(layer, torch.nn.Linear)]
        if sizes != expected:
            raise ConfigError(
                f"init = {config.init!r}: its {head} network has layers {sizes}, which do not "
                f"fit net_arch = {expected}"
            )
    return model


def start_from(model: PPO, saved: Any) -> None:
    """Copy a saved model's weights into `model` (its own hyperparameters stay the config's)."""
    model.policy.load_state_dict(saved.policy.state_dict())


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

    The folder is locked for the run (RunLocked names the pid of a live run that holds it). A
    fresh run refuses a folder that holds one already, unless `overwrite` (which empties it
    first): no run's checkpoints are lost, or mixed with another's. Returns the final model's path.
    """
    budget = budget_minutes(minutes, config.minutes)
    if resume and not folder.is_dir():
        raise FileNotFoundError(f"--resume: no run folder at {folder}")
    # The model to start from is checked before anything is written.
    saved = None if resume and (folder / STATE_FILE).exists() else load_init(config)
    with RunLock(folder) as lock:
        if lock.stale_pid:
            print(f"{folder}: taking over the lock left by pid {lock.stale_pid}, which ended")
        state = _prepare(folder, resume, overwrite, config)
        return _run(config, folder, state, saved, progress, budget)


def _prepare(folder: Path, resume: bool, overwrite: bool, config: TrainConfig) -> dict[str, Any]:
    """The committed state to resume from ({} for a fresh run, in an emptied folder if asked)."""
    if resume and holds_run(folder):
        return resume_state(folder)
    if resume:
        print(f"--resume: {folder} holds no checkpoint yet; starting from step 0")
    start_fresh(folder, overwrite, config, "train_config.json")
    return {}


def _run(
    config: TrainConfig,
    folder: Path,
    state: dict[str, Any],
    saved: Any,
    progress: bool,
    minutes: float,
) -> Path:
    torch.set_num_threads(1)
    set_random_seed(config.seed)
    envs = make_envs(config)
    if state:
        if isinstance(envs, VecNormalize) and "normalizer" in state:
            envs = VecNormalize.load(str(folder / state["normalizer"]), envs.venv)
        model = PPO.load(folder / state["checkpoint"], env=envs, device="cpu")
    else:
        model = build_model(config, envs, folder)
        if saved is not None:
            start_from(model, saved)
    quiet_logger(model)
    if config.mode == "selfplay":
        opponents: Any = SelfPlayCallback(config.selfplay, folder / "snapshots", config.seed, state)
        (folder / "snapshots").mkdir(exist_ok=True)
    else:
        opponents = CurriculumCallback(
            config.curriculum, config.seed, state.get("stage", 0), state.get("results", ())
        )
    every = max(config.checkpoint_every // config.n_envs, 1)
    return learn_and_save(model, folder, opponents, every, config, not state, progress, minutes)


class RunLength(Protocol):
    """What `learn_and_save` reads from a training run's or a league run's config."""

    @property
    def total_timesteps(self) -> int: ...

    @property
    def ppo(self) -> PPOConfig: ...


def learn_and_save(
    model: PPO,
    folder: Path,
    opponents: BaseCallback,
    every: int,
    config: RunLength,
    fresh: bool,
    progress: bool,
    minutes: float,
) -> Path:
    """`model.learn` up to `config.total_timesteps` against `opponents` (a callback whose state
    is checkpointed with the model): a committed checkpoint at step 0 of a fresh run, every
    `every` calls, at the end and on the way out; the finished model as `folder/final.zip`. The
    entropy coefficient and the learning rate follow `config.ppo`'s schedules, if it has them."""
    if fresh:
        save_checkpoint(model, folder, [opponents])  # step 0: from here on, --resume works
    checkpoints = StateCheckpointCallback(every, folder, [opponents])
    callbacks = [opponents, checkpoints, StopWhenRequested()]
    callbacks += [StopAfter(minutes)] if minutes else []
    ppo = config.ppo
    if ppo.ent_decay_steps:
        callbacks.append(EntropySchedule(ppo.ent_coef, ppo.ent_coef_final, ppo.ent_decay_steps))
    if ppo.lr_decay_steps:
        callbacks.append(
            LearningRateSchedule(ppo.learning_rate, ppo.learning_rate_final, ppo.lr_decay_steps)
        )
    remaining = config.total_timesteps - model.num_timesteps
    try:
        if remaining > 0:
            model.learn(
                remaining,
                callback=CallbackList(callbacks),
                reset_num_timesteps=fresh,
                progress_bar=progress,
            )
    except BaseException as error:
        _save_on_the_way_out(model, folder, [opponents], error)
        raise
    save_checkpoint(model, folder, [opponents])
    return atomic_write(folder / "final.zip", model.save)


def _save_on_the_way_out(model: PPO, folder: Path, parts: list[Any], error: BaseException) -> None:
    """The crash handler: save the model, unless it diverged (then keep the last good one)."""
    try:
        save_checkpoint(model, folder, parts)
    except Diverged as diverged:
        if not isinstance(error, Diverged):
            raise diverged from error


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="vooga-train", description=__doc__.splitlines()[0])
    parser.add_argument("--config", default="default", help="a name in configs/train or a path")
    parser.add_argument("--out", type=Path, help="run folder (default runs/CONFIG)")
    parser.add_argument("--seed", type=int, help="overrides the config's seed")
    parser.add_argument("--steps", type=int, help="total timesteps (overrides the config)")
    parser.add_argument("--init", help="start from this saved model's weights (overrides)")
    parser.add_argument("--resume", action="store_true", help="continue from OUT/latest.zip")
    parser.add_argument("--overwrite", action="store_true", help="start over in a used OUT")
    parser.add_argument(
        "--minutes", type=_minutes, help="stop after this much wall time (0: no budget)"
    )
    parser.add_argument("--no-progress", action="store_true", help="no progress bar")
    args = parser.parse_args(argv)
    if args.resume and args.overwrite:
        parser.error("--resume continues a run, --overwrite deletes it: give one of them")
    if args.out is not None and args.out.exists() and not args.out.is_dir():
        parser.error(f"--out {args.out} is a file; give a folder for the run")
    try:
        config = load_train_config(
            args.config, seed=args.seed, total_timesteps=args.steps, init=args.init
        )
    except ConfigError as error:
        parser.error(str(error))
    folder = args.out or Path("runs") / config.name
    stop_on_signals()  # `kill` and job schedulers stop it as Ctrl-C does: checkpointed
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
    except Diverged as error:
        good = json.loads((folder / STATE_FILE).read_text())["checkpoint"]
        print(f"error: {error}; kept the last good checkpoint, {folder / good}", file=sys.stderr)
        return 1
    except (FileNotFoundError, FileExistsError, ConfigError, BrokenRun, RunLocked) as error:
        parser.error(str(error))
    print(f"trained: {final}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
