"""RLlib training configuration: frozen dataclasses loaded from `configs/train/rllib_*.toml`."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import Any

from vooga_env.game.config import ConfigError, build_config, read_toml
from vooga_env.policies import SCRIPTED

from .train_config import TRAIN_DIR

ACTIVATIONS = ("tanh", "relu")


@dataclass(frozen=True)
class RLlibPPOConfig:
    """RLlib PPO hyperparameters in RLlib's names (`PPOConfig.training`); `net_arch` is
    `fcnet_hiddens`, the layers shared by the policy and value heads."""

    lr: float = 3e-4
    gamma: float = 0.99
    gae_lambda: float = 0.95  # RLlib's `lambda_`
    train_batch_size: int = 4096  # env steps of one iteration, over all env runners
    minibatch_size: int = 512
    num_epochs: int = 4
    entropy_coeff: float = 0.01
    clip_param: float = 0.2
    net_arch: tuple[int, ...] = (64, 64)
    activation: str = "tanh"

    def __post_init__(self) -> None:
        if self.activation not in ACTIVATIONS:
            raise ConfigError(
                f"activation = {self.activation!r} is not allowed: one of {', '.join(ACTIVATIONS)}"
            )
        for key in ("train_batch_size", "minibatch_size", "num_epochs"):
            if getattr(self, key) <= 0:
                raise ConfigError(f"{key} = {getattr(self, key)} is not allowed: must be > 0")
        if self.minibatch_size > self.train_batch_size:
            raise ConfigError(
                f"minibatch_size = {self.minibatch_size} is not allowed: at most "
                f"train_batch_size ({self.train_batch_size})"
            )


@dataclass(frozen=True)
class LeagueConfig:
    """Who the learner (`main`) meets: the scripted fighters and frozen snapshots of itself.

    A snapshot of `main` joins the pool as a new RLModule every `snapshot_every` iterations; the
    pool keeps the newest `window` snapshots. Each episode's opponent is drawn with weight
    `(1 - win_rate) ** pfsp_power + 0.05` (prioritized fictitious self-play: the opponents
    `main` beats least come most often; 0 draws uniformly), win rates tracked per opponent as an
    exponential average with `win_rate_decay` per iteration.
    """

    scripted: tuple[str, ...] = ("idle", "rush", "turtle", "zoner", "edge_guard")
    snapshot_every: int = 5
    window: int = 5
    pfsp_power: float = 1.0
    win_rate_decay: float = 0.7

    def __post_init__(self) -> None:
        for name in self.scripted:
            if name not in SCRIPTED:
                raise ConfigError(
                    f"scripted = {name!r} is not allowed: one of {', '.join(SCRIPTED)}"
                )
        if len(set(self.scripted)) != len(self.scripted):
            raise ConfigError(f"scripted = {list(self.scripted)} is not allowed: names repeat")
        for key in ("snapshot_every", "window"):
            if getattr(self, key) <= 0:
                raise ConfigError(f"{key} = {getattr(self, key)} is not allowed: must be > 0")
        if self.pfsp_power < 0:
            raise ConfigError(f"pfsp_power = {self.pfsp_power} is not allowed: must be >= 0")
        if not 0.0 <= self.win_rate_decay < 1.0:
            raise ConfigError(f"win_rate_decay = {self.win_rate_decay} is not allowed: in [0, 1)")


@dataclass(frozen=True)
class RLlibTrainConfig:
    """One RLlib run: the fight, the cluster layout, PPO, the league and checkpoints."""

    fight: str = "default"
    iterations: int = 100
    seed: int = 0
    minutes: float = 0.0  # wall-time budget; training stops there (0: no budget)
    env_runners: int = 0  # 0: sample in the driver process
    envs_per_runner: int = 8
    checkpoint_every: int = 5  # iterations
    learners: int = 0  # 0: one learner in the driver process; N: N learner actors (DDP)
    gpus_per_learner: float = 0.0  # 1: each learner (or the driver's) trains on a GPU
    ppo: RLlibPPOConfig = RLlibPPOConfig()
    league: LeagueConfig = LeagueConfig()
    name: str = "rllib"

    def __post_init__(self) -> None:
        for key in ("iterations", "envs_per_runner", "checkpoint_every"):
            if getattr(self, key) <= 0:
                raise ConfigError(f"{key} = {getattr(self, key)} is not allowed: must be > 0")
        if self.learners < 0 or self.gpus_per_learner < 0:
            key = "learners" if self.learners < 0 else "gpus_per_learner"
            raise ConfigError(f"{key} = {getattr(self, key)} is not allowed: must be >= 0")
        if self.env_runners < 0:
            raise ConfigError(f"env_runners = {self.env_runners} is not allowed: must be >= 0")
        if self.minutes < 0:
            raise ConfigError(f"minutes = {self.minutes} is not allowed: must be >= 0")


def load_rllib_config(config: str | Path, **overrides: Any) -> RLlibTrainConfig:
    """An RLlibTrainConfig from a name in configs/train/ or a .toml path, plus overrides."""
    data, path = read_toml(config, TRAIN_DIR, "training config")
    for key, value in overrides.items():  # a table (ppo={...}) changes only the keys it names
        if isinstance(value, dict) and isinstance(data.get(key), dict):
            data[key] = {**data[key], **value}
        elif value is not None:
            data[key] = value
    return build_config(RLlibTrainConfig, data, str(path))
