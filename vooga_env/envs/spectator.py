"""`Spectator`: one fight of a batch, replayed on the physics engine so that it can be drawn.

The batch keeps its fights as arrays and the viewer draws the engine's sprites; the two backends
are bit-identical, so replaying fight 0's actions on an `EngineSimulation` from the same PCG64
state shows exactly the fight the batch steps. Only a batch asked for `render_mode="rgb_array"`
keeps one, and pays an engine step (~75 µs) per batch step for it.
"""

from __future__ import annotations

import numpy as np

from vooga_env.envs.render import LazyViewer, frames_per_second
from vooga_env.game.config import FightConfig
from vooga_env.game.outcome import Outcome
from vooga_env.game.simulation import EngineSimulation


class Spectator:
    """The engine's copy of one batched fight, and a viewer for it."""

    def __init__(self, config: FightConfig) -> None:
        self.simulation = EngineSimulation(config)
        self._rng = np.random.Generator(np.random.PCG64())
        self.viewer = LazyViewer(self.simulation, "rgb_array", frames_per_second(config))

    def reset(self, rng_state: dict | None = None) -> None:
        """Start the next game; from `rng_state` (the batched fight's PCG64 state just before
        its reset) on a new seed, else continuing the stream as the batch does."""
        if rng_state is not None:
            self._rng.bit_generator.state = rng_state
        self.simulation.reset(self._rng)

    def step(self, first: int, second: int) -> None:
        """Step the copy; a fight that ends starts the next game, as the batch's auto-reset."""
        *_, winner, _ = self.simulation.step(first, second)
        if winner != Outcome.GOING_ON:
            self.reset()

    def render(self) -> np.ndarray:
        """The fight's current frame, (H, W, 3) uint8."""
        return self.viewer.draw()

    def close(self) -> None:
        self.viewer.close()
