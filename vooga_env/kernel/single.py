"""`CompiledSimulation`: one fight on the numba kernel, behind `FightParallelEnv`.

The batched engine's kernel at N = 1, with every buffer allocated once, so a step costs one
compiled call (both frames and both observations) and a few list conversions. Spawn jitter comes
from the env's own Generator (its PCG64 state is handed to the kernel's stream and back), so
seeding is exactly the engine's.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from vooga_env.game.config import FightConfig
from vooga_env.game.observations import OBSERVATION_SIZE
from vooga_env.game.simulation import StepResult
from vooga_env.kernel.cache import load_kernel
from vooga_env.kernel.params import FightParams, check_supported
from vooga_env.kernel.state import FightState, StepEvents


class CompiledSimulation:
    """One fight as a `FightState` of size 1, stepped by the compiled kernel."""

    backend = "compiled"

    def __init__(self, config: FightConfig) -> None:
        check_supported(config)
        self.kernel = load_kernel().Kernel(FightParams.from_config(config))
        self.state = FightState(1)
        self._index = np.zeros(1, dtype=np.int64)
        self._bounds = np.array([0, 1], dtype=np.int64)
        self._actions = np.zeros((1, 2), dtype=np.int64)
        self._events = StepEvents(1)
        self._rewards = np.zeros((1, 2))
        self._truncated = np.zeros(1, dtype=bool)
        self._winner = np.zeros(1, dtype=np.int64)
        # (2,) and (2, 2) views of the size-1 arrays, for the infos
        events = self._events
        self._health, self._stocks = self.state.health[:, 0], self.state.stocks[:, 0]
        self._hits, self._damage = events.hits[:, :, 0], events.damage[:, :, 0]
        self._outs = events.outs[:, :, 0]

    def reset(self, rng: np.random.Generator) -> np.ndarray:
        streams = self.state.rng
        streams.set_state(0, rng.bit_generator.state)
        self.kernel.reset(self.state, self._index)
        rng.bit_generator.state = streams.get_state(0)
        return self.observe()

    def step(self, first: int, second: int) -> StepResult:
        actions = self._actions
        actions[0, 0] = first
        actions[0, 1] = second
        out = np.empty((1, 2, OBSERVATION_SIZE), dtype=np.float32)
        self.kernel.step_observe(
            self.state,
            actions,
            self._events,
            self._rewards,
            self._truncated,
            self._winner,
            out,
            self._bounds,
        )
        columns = (
            self._health.tolist(),
            self._stocks.tolist(),
            *self._hits.tolist(),
            *self._damage.tolist(),
            *self._outs.tolist(),
        )
        return (
            out[0],
            self._rewards[0].tolist(),
            bool(self._events.over[0]),
            bool(self._truncated[0]),
            int(self._winner[0]),
            columns,
        )

    def observe(self) -> np.ndarray:
        out = np.empty((1, 2, OBSERVATION_SIZE), dtype=np.float32)
        self.kernel.observe(self.state, out, self._index)
        return out[0]

    def fighter_status(self) -> list[dict[str, Any]]:
        s = self.state
        return [
            {
                "x": float(s.x[f, 0]),
                "y": float(s.y[f, 0]),
                "health": float(s.health[f, 0]),
                "stocks": int(s.stocks[f, 0]),
            }
            for f in (0, 1)
        ]
