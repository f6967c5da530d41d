"""`PCG64Streams`: one numpy PCG64 stream's state per fight, for the kernel to advance.

A single env draws its spawn jitter from `gymnasium.utils.seeding.np_random(seed)`, a numpy
`Generator(PCG64(SeedSequence(seed)))`, built here the same way without gymnasium. Every fight
keeps that generator's 128-bit state and increment as uint64 halves, so a fight's draws are
exactly those of a single env seeded the same; the kernel's `_next_double` is the draw (`parts`).
"""

from __future__ import annotations

import numpy as np

_MASK64 = (1 << 64) - 1


class PCG64Streams:
    """N independent PCG64 streams (state and increment: (N,) uint64 high and low halves)."""

    def __init__(self, size: int) -> None:
        self.state_hi = np.zeros(size, dtype=np.uint64)
        self.state_lo = np.zeros(size, dtype=np.uint64)
        self.inc_hi = np.zeros(size, dtype=np.uint64)
        self.inc_lo = np.ones(size, dtype=np.uint64)

    def seed(self, index: np.ndarray, seeds: list[int | None]) -> None:
        """Stream `index[i]` becomes the generator `seeding.np_random(seeds[i])` would make.

        A Python loop over the seeded fights: seeding is numpy's SeedSequence, done once per
        explicit seed, never in a step.
        """
        for i, seed in zip(np.asarray(index).tolist(), seeds):
            self.set_state(i, np.random.PCG64(np.random.SeedSequence(seed)).state)

    def set_state(self, i: int, state: dict) -> None:
        """Load stream `i` from a numpy PCG64 `bit_generator.state` dict."""
        if state["bit_generator"] != "PCG64":
            raise ValueError(f"need a PCG64 state, got {state['bit_generator']}")
        inner = state["state"]
        self.state_hi[i], self.state_lo[i] = inner["state"] >> 64, inner["state"] & _MASK64
        self.inc_hi[i], self.inc_lo[i] = inner["inc"] >> 64, inner["inc"] & _MASK64

    def get_state(self, i: int) -> dict:
        """Stream `i` as a numpy PCG64 `bit_generator.state` dict."""
        return {
            "bit_generator": "PCG64",
            "state": {
                "state": (int(self.state_hi[i]) << 64) | int(self.state_lo[i]),
                "inc": (int(self.inc_hi[i]) << 64) | int(self.inc_lo[i]),
            },
            "has_uint32": 0,
            "uinteger": 0,
        }

    @property
    def nbytes(self) -> int:
        return sum(a.nbytes for a in (self.state_hi, self.state_lo, self.inc_hi, self.inc_lo))
