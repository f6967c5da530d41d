"""Training configuration: frozen dataclasses loaded from `configs/train/*.toml`."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import Any

from vooga_env.game.config import (
    CONFIG_DIR,
    SEED_MAX,
    ConfigError,
    build_config,
    load_config,
    overridden_source,
    read_toml,
)
from vooga_env.game.facing import FRAMES
from vooga_env.game.pixels import pixel_spec
from vooga_env.policies import SCRIPTED

TRAIN_DIR = CONFIG_DIR / "train"
MODES = ("scripted", "selfplay")
OBS_TYPES = ("vector", "pixels")  # "both" would need MultiInputPolicy: not a recipe yet


def _refuse(key: str, value: Any, allowed: str) -> None:
    raise ConfigError(f"{key} = {value!r} is not allowed: {allowed}")


def _at_least(config: Any, low: int, *keys: str) -> None:
    for key in keys:
        if getattr(config, key) < low:
            _refuse(key, getattr(config, key), f"must be >= {low}")


def _within(config: Any, low: float, high: float, *keys: str) -> None:
    for key in keys:
        if not low <= getattr(config, key) <= high:
            _refuse(key, getattr(config, key), f"must be in [{low:g}, {high:g}]")


def _fighters(key: str, names: tuple[str, ...]) -> None:
    for name in names:
        if name not in SCRIPTED:
            _refuse(key, list(names), f"{name!r} is not one of {', '.join(SCRIPTED)}")


@dataclass(frozen=True)
class PPOConfig:
    """Stable-Baselines3 PPO hyperparameters (see its docs); `net_arch` for both heads."""

    learning_rate: float = 3e-4
    n_steps: int = 256
    batch_size: int = 512
    n_epochs: int = 4
    gamma: float = 0.99
    gae_lambda: float = 0.95
    ent_coef: float = 0.01
    # With ent_decay_steps > 0, ent_coef falls linearly to ent_coef_final over that many steps
    # and stays there: explore early, play near the argmax by the end (callbacks.EntropySchedule).
    ent_coef_final: float = 0.0
    ent_decay_steps: int = 0
    # Likewise, with lr_decay_steps > 0 the learning rate falls to learning_rate_final
    # (callbacks.LearningRateSchedule): a policy that settles instead of swinging at the end.
    learning_rate_final: float = 0.0
    lr_decay_steps: int = 0
    clip_range: float = 0.2
    net_arch: tuple[int, ...] = (64, 64)
    normalize_reward: bool = False  # SB3's VecNormalize on rewards only (inference needs nothing)
    # "opponent": the network sees every fight turned to face its opponent (FacingPolicy), so a
    # crossed-over fight is one it knows; "seat": as the env mirrors it, by seat.
    frame: str = "seat"

    def __post_init__(self) -> None:
        # SB3 takes all of these and fails (or trains nothing) only once training has started.
        for key in ("learning_rate", "clip_range"):
            if not getattr(self, key) > 0:
                _refuse(key, getattr(self, key), "must be > 0")
        _at_least(self, 1, "n_steps", "n_epochs")
        _at_least(self, 2, "batch_size")  # SB3 normalises advantages over each minibatch
        _within(self, 0.0, 1.0, "gamma", "gae_lambda")
        for key in (
            "ent_coef",
            "ent_coef_final",
            "ent_decay_steps",
            "learning_rate_final",
            "lr_decay_steps",
        ):
            if getattr(self, key) < 0:
                _refuse(key, getattr(self, key), "must be >= 0")
        if any(width < 1 for width in self.net_arch):
            _refuse("net_arch", list(self.net_arch), "every layer needs >= 1 unit")
        if self.frame not in FRAMES:
            _refuse("frame", self.frame, f"one of {', '.join(FRAMES)}")


@dataclass(frozen=True)
class CurriculumConfig:
    """Scripted opponents from weak to strong; promoted when the learner's win rate over the
    last `window` games passes `promote_win_rate`. `review_ratio` of the envs replay earlier rungs.

    A rung is one fighter's name, or several joined by "+" ("rush+turtle"): a mixed rung, each
    game against one of them drawn at random. Every env draws its opponent again for each game.
    """

    ladder: tuple[str, ...] = ("idle", "random", "rush")
    promote_win_rate: float = 0.8
    window: int = 50
    review_ratio: float = 0.25

    def __post_init__(self) -> None:
        for rung in self.ladder:
            for name in rung.split("+"):
                if name not in SCRIPTED:
                    raise ConfigError(
                        f"ladder = {rung!r} is not allowed: {name!r} is not one of "
                        f"{', '.join(SCRIPTED)} (several joined by '+' make a mixed rung)"
                    )
        if not self.ladder:
            raise ConfigError("ladder = [] is not allowed: name at least one opponent")
        if not 0.0 < self.promote_win_rate <= 1.0:
            raise ConfigError(
                f"promote_win_rate = {self.promote_win_rate} is not allowed: in (0, 1]"
            )
        if not 0.0 <= self.review_ratio < 1.0:
            raise ConfigError(f"review_ratio = {self.review_ratio} is not allowed: in [0, 1)")
        _at_least(self, 1, "window")

    def rung(self, stage: int) -> tuple[str, ...]:
        """The fighters of rung `stage`."""
        return tuple(self.ladder[stage].split("+"))


@dataclass(frozen=True)
class SelfPlayConfig:
    """Self-play against frozen snapshots, in ML-Agents' ghost-trainer vocabulary.

    A snapshot of the learner is saved every `save_steps`; the pool keeps the last `window`.
    Every `swap_steps` each env draws its opponent: the latest snapshot with probability
    `play_against_latest_ratio`, else one from the pool (or, with `scripted_ratio`, a scripted
    fighter from `scripted`, which keeps the learner honest against fixed styles).
    """

    save_steps: int = 20_000
    swap_steps: int = 4_096
    window: int = 10
    play_against_latest_ratio: float = 0.5
    scripted_ratio: float = 0.2
    scripted: tuple[str, ...] = ("rush", "turtle", "zoner", "edge_guard")

    def __post_init__(self) -> None:
        _at_least(self, 1, "save_steps", "swap_steps", "window")
        _within(self, 0.0, 1.0, "play_against_latest_ratio", "scripted_ratio")
        _fighters("scripted", self.scripted)
        if self.scripted_ratio > 0 and not self.scripted:
            _refuse("scripted", [], f"name a fighter for scripted_ratio = {self.scripted_ratio}")


@dataclass(frozen=True)
class TrainConfig:
    """One training run: the fight config, the opponents, PPO, checkpoints and evaluation."""

    mode: str = "scripted"
    fight: str = "default"
    total_timesteps: int = 1_000_000
    n_envs: int = 8
    seed: int = 0
    minutes: float = 0.0  # wall-time budget; training stops there (0: no budget)
    init: str = ""  # a saved model (.zip) to start from, e.g. the curriculum's; "": a new network
    checkpoint_every: int = 50_000
    eval_games: int = 200
    ppo: PPOConfig = PPOConfig()
    curriculum: CurriculumConfig = CurriculumConfig()
    selfplay: SelfPlayConfig = SelfPlayConfig()
    obs_type: str = "vector"  # or "pixels": CnnPolicy on the fighter's images
    pixel_size: tuple[int, ...] = (84, 84)  # (height, width) of the images
    frame_stack: int = 1  # images stacked as channels (SB3's VecFrameStack)
    name: str = "default"

    def __post_init__(self) -> None:
        if self.mode not in MODES:
            raise ConfigError(f"mode = {self.mode!r} is not allowed: one of {', '.join(MODES)}")
        _at_least(self, 1, "total_timesteps", "n_envs", "checkpoint_every", "eval_games")
        if self.n_envs * self.ppo.n_steps < 2:
            _refuse(
                "n_envs", self.n_envs, f"n_envs * ppo.n_steps ({self.ppo.n_steps}) must be >= 2"
            )
        if not 0 <= self.seed <= SEED_MAX - self.n_envs:  # env i is seeded seed + i
            _refuse("seed", self.seed, f"must be in 0 .. {SEED_MAX - self.n_envs}")
        if self.obs_type not in OBS_TYPES:
            _refuse("obs_type", self.obs_type, f"one of {', '.join(OBS_TYPES)}")
        try:
            pixel_spec(self.obs_type, self.pixel_size)
        except ValueError as error:
            raise ConfigError(str(error)) from None
        _at_least(self, 1, "frame_stack")
        if self.obs_type == "vector" and self.frame_stack != 1:
            _refuse("frame_stack", self.frame_stack, "1 with obs_type = 'vector'")
        if self.obs_type == "pixels" and self.ppo.frame != "seat":
            _refuse("ppo.frame", self.ppo.frame, "'seat' with obs_type = 'pixels'")
        if self.minutes < 0:
            _refuse("minutes", self.minutes, "must be >= 0 (0: no time budget)")
        try:
            load_config(self.fight)
        except ConfigError as error:
            raise ConfigError(f"fight = {self.fight!r} is not allowed: {error}") from None


def load_train_config(config: str | Path, **overrides: Any) -> TrainConfig:
    """A TrainConfig from a name in configs/train/ or a .toml path, plus top-level overrides."""
    data, path = read_toml(config, TRAIN_DIR, "training config")
    given = {key: value for key, value in overrides.items() if value is not None}
    data.update(given)
    return build_config(TrainConfig, data, overridden_source(path, given))
