"""SB3 callbacks for training fighters: the curriculum ladder, self-play, checkpoints, and a
stop asked for by a signal."""

from __future__ import annotations

from abc import abstractmethod
from collections import deque
from collections.abc import Sequence
from pathlib import Path
from typing import Any

import numpy as np
from stable_baselines3.common.callbacks import BaseCallback, CheckpointCallback
from stable_baselines3.common.utils import ConstantSchedule

from vooga_env.policies.models import FrozenPolicy, load_model
from vooga_env.tools.elo import START_RATING, update

from .checkpoints import CHECKPOINTS, atomic_write, check_finite, save_checkpoint
from .common import STOP_REQUESTED
from .train_config import CurriculumConfig, SelfPlayConfig


class StopWhenRequested(BaseCallback):
    """Raise KeyboardInterrupt at the next step once a stop was requested (`stop_on_signals`).

    A signal handler's exception is raised wherever the interpreter happens to be, and numpy
    drops one raised in the `__array_function__` lookup it makes on an argument's type (an enum
    member's, in the scripted fighters): a league sent SIGTERM once trained on for good.
    """

    def _on_step(self) -> bool:
        if STOP_REQUESTED.is_set():
            raise KeyboardInterrupt
        return True


class StepDecay(BaseCallback):
    """A PPO setting falling linearly from `start` to `end` over the first `steps` timesteps,
    then `end`; `apply` sets it on the model.

    Set from the step count before each update, so a resumed run carries on where it was (SB3's
    own schedules follow the fraction of `total_timesteps`, which a run stopped by the clock
    never reaches).
    """

    def __init__(self, start: float, end: float, steps: int) -> None:
        super().__init__()
        self.start, self.end, self.steps = start, end, steps

    def coefficient(self, timesteps: int) -> float:
        done = min(timesteps / self.steps, 1.0)
        return self.start + (self.end - self.start) * done

    def _on_rollout_end(self) -> None:
        self.apply(self.coefficient(self.num_timesteps))

    @abstractmethod
    def apply(self, value: float) -> None:
        """Set the setting on `self.model`."""

    def _on_step(self) -> bool:
        return True


class EntropySchedule(StepDecay):
    """PPO's entropy coefficient (SB3 schedules the learning rate and clip range, not this)."""

    def apply(self, value: float) -> None:
        self.model.ent_coef = value
        self.logger.record("train/ent_coef_now", value)


class LearningRateSchedule(StepDecay):
    """PPO's learning rate, so that the last steps of a run refine the policy instead of
    moving it by tens of points between checkpoints (SB3 logs it as train/learning_rate)."""

    def apply(self, value: float) -> None:
        self.model.learning_rate = value
        self.model.lr_schedule = ConstantSchedule(value)


def learner_won(info: dict[str, Any]) -> float | None:
    """The learner's score at an episode's end: 1, 0.5 or 0 (None before the end)."""
    winner = info.get("winner")
    if winner is None:
        return None
    if winner == "draw":
        return 0.5
    return 1.0 if winner == f"fighter_{info['seat']}" else 0.0


class CurriculumCallback(BaseCallback):
    """Scripted opponents from weak to strong, promoted on the win rate over recent games.

    Each env draws its opponent for every game: from the current rung, or (the last
    `review_ratio` of the envs) from a rung drawn among the current and earlier ones.
    """

    def __init__(
        self, config: CurriculumConfig, seed: int, stage: int = 0, results: Sequence[float] = ()
    ) -> None:
        super().__init__()
        self.config = config
        self.stage = stage
        self.results: deque[float] = deque(results, maxlen=config.window)
        self.rng = np.random.default_rng(seed)

    def _on_training_start(self) -> None:
        for index in range(self.training_env.num_envs):
            self._draw(index)

    def _on_step(self) -> bool:
        fighters = self.config.rung(self.stage)
        for index, (done, info) in enumerate(zip(self.locals["dones"], self.locals["infos"])):
            if not done:
                continue
            outcome = learner_won(info)
            if outcome is not None and info.get("opponent") in fighters:
                self.results.append(outcome)
            self._draw(index)
        if len(self.results) == self.config.window:
            rate = float(np.mean(self.results))
            self.logger.record("curriculum/win_rate", rate)
            if rate >= self.config.promote_win_rate and self.stage + 1 < len(self.config.ladder):
                self.stage += 1
                self.results.clear()
                print(
                    f"step {self.num_timesteps}: won {rate:.0%} of the last {self.config.window}"
                    f" games, promoted to {self.opponent}",
                    flush=True,
                )
        self.logger.record("curriculum/stage", self.stage)
        return True

    @property
    def opponent(self) -> str:
        """The current rung (fighters joined by '+' when it is mixed)."""
        return self.config.ladder[self.stage]

    def _draw(self, index: int) -> None:
        """Env `index`'s opponent for its next game."""
        envs = self.training_env.num_envs
        reviewer = index >= envs - int(round(envs * self.config.review_ratio))
        stage = int(self.rng.integers(self.stage + 1)) if reviewer else self.stage
        fighters = self.config.rung(stage)
        name = fighters[int(self.rng.integers(len(fighters)))]
        self.training_env.env_method(
            "set_opponent", name, int(self.rng.integers(2**31)), indices=[index]
        )

    def state(self) -> dict[str, Any]:
        return {"stage": self.stage, "opponent": self.opponent, "results": list(self.results)}


class SelfPlayCallback(BaseCallback):
    """A pool of frozen snapshots of the learner; each env's opponent redrawn every swap_steps.

    Elo: the learner, every snapshot and the scripted fighters are rated from the learner's games;
    a new snapshot starts at the learner's rating. The ratings are logged and kept with the
    checkpoints.
    """

    def __init__(
        self, config: SelfPlayConfig, folder: Path, seed: int, state: dict[str, Any] | None = None
    ) -> None:
        super().__init__()
        self.config = config
        self.folder = folder
        self.rng = np.random.default_rng(seed)
        state = state or {}
        self.pool: list[str] = state.get("pool", [])
        self.ratings: dict[str, float] = state.get("ratings", {"learner": START_RATING})
        for name in config.scripted:  # fixed anchors: the learner's games against them count too
            self.ratings.setdefault(name, START_RATING)
        self.last_save = state.get("last_save", 0)
        self.last_swap = -self.config.swap_steps
        self._frozen: dict[str, FrozenPolicy] = {}

    def _on_training_start(self) -> None:
        if not self.pool:
            self._snapshot()
        self._swap()

    def _on_step(self) -> bool:
        if self.num_timesteps - self.last_save >= self.config.save_steps:
            self._snapshot()
        if self.num_timesteps - self.last_swap >= self.config.swap_steps:
            self._swap()
        for done, info in zip(self.locals["dones"], self.locals["infos"]):
            outcome = learner_won(info) if done else None
            opponent = info.get("opponent")
            if outcome is not None and opponent in self.ratings:
                self.ratings["learner"], self.ratings[opponent] = update(
                    self.ratings["learner"], self.ratings[opponent], outcome
                )
        self.logger.record("selfplay/learner_elo", self.ratings["learner"])
        self.logger.record("selfplay/pool_size", len(self.pool))
        return True

    def _snapshot(self) -> None:
        name = f"snapshot_{self.num_timesteps}"
        check_finite(self.model, self.num_timesteps)  # a diverged snapshot would poison the pool
        atomic_write(self.folder / f"{name}.zip", self.model.save)
        self.pool.append(name)
        self.ratings.setdefault(name, self.ratings["learner"])
        self.pool = self.pool[-self.config.window :]
        self._frozen = {key: policy for key, policy in self._frozen.items() if key in self.pool}
        self.last_save = self.num_timesteps

    def _frozen_policy(self, name: str) -> FrozenPolicy:
        if name not in self._frozen:
            self._frozen[name] = FrozenPolicy(
                load_model(self.folder / f"{name}.zip"), name, deterministic=False
            )
        return self._frozen[name]

    def _swap(self) -> None:
        config = self.config
        for index in range(self.training_env.num_envs):
            draw = self.rng.random()
            if draw < config.scripted_ratio and config.scripted:
                name = config.scripted[int(self.rng.integers(len(config.scripted)))]
                opponent: Any = name
            else:
                if self.rng.random() < config.play_against_latest_ratio:
                    name = self.pool[-1]
                else:
                    name = self.pool[int(self.rng.integers(len(self.pool)))]
                opponent = self._frozen_policy(name)
            self.training_env.env_method(
                "set_opponent", opponent, int(self.rng.integers(2**31)), indices=[index]
            )
        self.last_swap = self.num_timesteps

    def state(self) -> dict[str, Any]:
        return {"pool": self.pool, "ratings": self.ratings, "last_save": self.last_save}


class StateCheckpointCallback(CheckpointCallback):
    """SB3's CheckpointCallback (its schedule and names), saving through `save_checkpoint`:
    atomic files, committed in the run's state, never a non-finite model."""

    def __init__(self, save_freq: int, folder: Path, parts: list[Any]) -> None:
        super().__init__(save_freq, str(folder / CHECKPOINTS), name_prefix="ppo")
        self.folder = folder
        self.parts = parts

    def _on_step(self) -> bool:
        if self.n_calls % self.save_freq == 0:
            save_checkpoint(self.model, self.folder, self.parts)
        return True

    def _on_rollout_end(self) -> None:
        check_finite(self.model, self.num_timesteps)  # stop at the first bad update, not later
