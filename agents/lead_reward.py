"""A reward for leading: the league's learner gains a little on every step it leads and loses as
much on every step it trails.

A win on time pays the leader at the clock, but at `gamma = 0.99` a reward 870 steps away is worth
0.0002 of itself, so a learner cannot see that a small lead kept is a win, nor that one given away
is a loss: exploiters that took a lead and stalled beat it (docs/league.md, "Playing for time").
Training-side only (a VecEnv wrapper, as VecNormalize): the fight's own rewards, which exploiters,
evaluation and every env face, are unchanged.
"""

from __future__ import annotations

from typing import Any

import numpy as np
from stable_baselines3.common.vec_env import VecEnvWrapper

from vooga_env.game.observations import OBSERVATION_NAMES

_SCORES = [
    OBSERVATION_NAMES.index(name)
    for name in ("self_stocks", "opponent_stocks", "self_health", "opponent_health")
]


def leads(observations: np.ndarray) -> np.ndarray:
    """+1 where the observing fighter leads (more stocks, then more health; as `Fight.winner`),
    -1 where it trails, 0 where level: one per row of (n, OBSERVATION_SIZE) observations."""
    stocks, other_stocks, health, other_health = (observations[:, i] for i in _SCORES)
    by_health = np.sign(np.round(health - other_health, 6))
    return np.where(stocks != other_stocks, np.sign(stocks - other_stocks), by_health)


class LeadReward(VecEnvWrapper):
    """Adds `per_step` * `leads(observation)` to each slot's reward, read from the observation the
    step returns (a slot whose fight ended sees its next fight's start: level, nothing added)."""

    def __init__(self, venv: Any, per_step: float) -> None:
        super().__init__(venv)
        self.per_step = per_step

    def reset(self) -> np.ndarray:
        return self.venv.reset()

    def step_wait(self) -> Any:
        observations, rewards, dones, infos = self.venv.step_wait()
        bonus = self.per_step * leads(observations).astype(np.float32)
        return observations, rewards + bonus, dones, infos
