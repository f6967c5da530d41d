"""`Policy`: the one interface every fighter is wrapped in, scripted, trained or a callable.

A policy maps a fighter's own observation to an action: `act(obs) -> int`, plus SB3's
`predict(obs, state=None, episode_start=None, deterministic=True) -> (action, state)`, so a scripted
fighter and a trained model stand in for each other.
"""

from __future__ import annotations

from typing import Any

import numpy as np


class Policy:
    """Base of every policy: `act` one observation; `predict` does the same in SB3's shape."""

    name = "policy"

    def reset(self, seed: int | None = None) -> None:
        """Start a new episode (scripted fighters reseed their randomness here)."""

    def act(self, observation: np.ndarray) -> int:
        raise NotImplementedError

    def predict(
        self,
        observation: np.ndarray,
        state: Any = None,
        episode_start: Any = None,
        deterministic: bool = True,
    ) -> tuple[np.ndarray, Any]:
        observation = np.asarray(observation)
        if observation.ndim == 2:
            return np.array([self.act(row) for row in observation]), state
        return np.array(self.act(observation)), state

    def __repr__(self) -> str:
        return f"{type(self).__name__}()"
