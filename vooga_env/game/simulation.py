"""What a `FightParallelEnv` steps: the physics engine's `Fight`, or the same rules compiled.

Two backends behind one small interface, `Simulation`, bit-identical in everything the env returns
(`tests/env/test_backends.py` plays both side by side); `kernel.backends.make_simulation` picks:

- `"engine"`: `vooga_env.game.fight.Fight` over the VOOGA physics engine. It runs every config, any
  `reward_fn`, and rendering; about 75 µs a step.
- `"compiled"`: the batched engine's numba kernel (`vooga_env.kernel.single`) for one fight,
  about 8 µs a step; the default wiring and the default reward only.
- `"auto"` (the default) picks "compiled" when it can run the env as asked, else "engine".

A step returns `(observations (2, 41) float32, rewards [r0, r1], terminated, truncated, winner,
info_columns)`: `winner` is an `Outcome` code (0 or 1, DRAW, GOING_ON); `info_columns` holds one
[fighter_0, fighter_1] pair per name in `INFO_KEYS`, as plain Python numbers.
"""

from __future__ import annotations

import math
from typing import Any, Protocol

import numpy as np

from vooga_env.game.config import FightConfig
from vooga_env.game.fight import Fight
from vooga_env.game.formulas import time_out
from vooga_env.game.observations import observe_both
from vooga_env.game.outcome import Outcome
from vooga_env.game.rewards import HitAndRingOutReward, RewardFn

StepResult = tuple[np.ndarray, list[float], bool, bool, int, tuple[list, ...]]


class Simulation(Protocol):
    """One fight, reset by a numpy Generator and stepped by a pair of action indices."""

    backend: str

    def reset(self, rng: np.random.Generator) -> np.ndarray:
        """Start a new fight (spawn jitter drawn from `rng`); both observations, (2, 41)."""
        ...

    def step(self, first: int, second: int) -> StepResult: ...

    def observe(self) -> np.ndarray:
        """Both fighters' observations now, (2, 41) float32."""
        ...

    def fighter_status(self) -> list[dict[str, Any]]:
        """Each fighter's top-left `x`, `y` (px), `health` and `stocks` now."""
        ...


class EngineSimulation:
    """`Fight` over the physics engine, rewarded by `reward_fn` (called with the step's events)."""

    backend = "engine"

    def __init__(self, config: FightConfig, reward_fn: RewardFn | None = None) -> None:
        self.fight = Fight(config)
        self.reward_fn = reward_fn or HitAndRingOutReward(config.rewards)
        self._max_cycles = config.max_cycles

    def reset(self, rng: np.random.Generator) -> np.ndarray:
        self.fight.reset(rng)
        reset_reward = getattr(self.reward_fn, "reset", None)
        if reset_reward is not None:
            reset_reward(self.fight)
        return observe_both(self.fight)

    def step(self, first: int, second: int) -> StepResult:
        fight = self.fight
        events = fight.step((first, second))
        try:
            rewards = _reward_pair(self.reward_fn, self.reward_fn(fight, events))
        except BaseException:
            fight.undo_step()  # a step whose reward failed did not happen
            raise
        terminated = events.over
        truncated = time_out(terminated, fight.steps, self._max_cycles)
        landed, blocked = [0, 0], [0, 0]
        for hit in events.hits:
            if hit.blocked:
                blocked[hit.defender] += 1
            else:
                landed[hit.attacker] += 1
        winner = Outcome.GOING_ON
        if terminated or truncated:
            winner = Outcome.of_leader(fight.winner())
        one, two = fight.fighters
        columns = (
            [one.health, two.health],
            [one.stocks, two.stocks],
            landed,
            blocked,
            events.damage_dealt,
            events.damage_taken,
            events.rung_out,
            events.knocked_out,
        )
        return observe_both(fight), rewards, terminated, truncated, winner, columns

    def observe(self) -> np.ndarray:
        return observe_both(self.fight)

    def fighter_status(self) -> list[dict[str, Any]]:
        return [
            {"x": f.x, "y": f.y, "health": f.health, "stocks": f.stocks}
            for f in self.fight.fighters
        ]


def _reward_pair(reward_fn: RewardFn, rewards: Any) -> list[float]:
    """A reward function's result as [reward_0, reward_1], or an error that blames it."""
    try:
        pair = [float(reward) for reward in rewards]
    except (TypeError, ValueError):
        pair = []
    if len(pair) != 2 or not all(math.isfinite(reward) for reward in pair):
        raise ValueError(
            f"reward_fn {reward_fn!r} returned {rewards!r}: it must return two finite numbers, "
            "(reward_0, reward_1)"
        )
    return pair
