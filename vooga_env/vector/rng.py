"""`PCG64Streams`: one numpy PCG64 stream per fight, advanced with array operations.

A single env draws its spawn jitter from `gymnasium.utils.seeding.np_random(seed)`, a numpy
`Generator(PCG64(SeedSequence(seed)))`. Here every fight keeps that generator's 128-bit state and
increment as uint64 halves, so a fight's draws are exactly those of a single env seeded the same:
`uniform(low, high)` is `low + (high - low) * next_double()`, and `next_double()` is the top 53
bits of PCG64's XSL-RR output (the LCG step, then the output of the new state).
"""

from __future__ import annotations

import numpy as np
from gymnasium.utils import seeding

_MULTIPLIER = 0x2360ED051FC65DA44385DF649FCCF645  # PCG's default 128-bit multiplier
_MUL_HI = np.uint64(_MULTIPLIER >> 64)
_MUL_LO = np.uint64(_MULTIPLIER & 0xFFFFFFFFFFFFFFFF)
_LOW32 = np.uint64(0xFFFFFFFF)
_32 = np.uint64(32)
_MASK64 = (1 << 64) - 1


class PCG64Streams:
    """N independent PCG64 streams (state and increment: (N,) uint64 high and low halves)."""

    def __init__(self, size: int) -> None:
        self.state_hi = np.zeros(size, dtype=np.uint64)
        self.state_lo = np.zeros(size, dtype=np.uint64)
        self.inc_hi = np.zeros(size, dtype=np.uint64)
        self.inc_lo = np.ones(size, dtype=np.uint64)

    def seed(self, index: np.ndarray, seeds: list[int | None]) -> None:
        """Stream `index[i]` becomes `seeding.np_random(seeds[i])`'s generator.

        A Python loop over the seeded fights: seeding is numpy's SeedSequence, done once per
        explicit seed, never in a step.
        """
        for i, seed in zip(np.asarray(index).tolist(), seeds):
            generator, _ = seeding.np_random(seed)
            self.set_state(i, generator.bit_generator.state)

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

    def next_double(self, index: np.ndarray) -> np.ndarray:
        """Advance the streams `index` (an int array, no repeats) once; their doubles in [0, 1)."""
        hi, lo = self.state_hi[index], self.state_lo[index]
        # state = state * multiplier + inc (mod 2**128), in 64-bit halves
        new_lo = lo * _MUL_LO
        new_hi = _mulhi(lo, _MUL_LO) + lo * _MUL_HI + hi * _MUL_LO
        added = new_lo + self.inc_lo[index]
        new_hi = new_hi + self.inc_hi[index] + (added < new_lo).astype(np.uint64)
        self.state_hi[index], self.state_lo[index] = new_hi, added
        # XSL-RR output of the new state
        mixed = new_hi ^ added
        rotate = new_hi >> np.uint64(58)
        output = (mixed >> rotate) | (mixed << ((np.uint64(64) - rotate) & np.uint64(63)))
        return (output >> np.uint64(11)).astype(np.float64) * (1.0 / 9007199254740992.0)

    def uniform(self, index: np.ndarray, low: float, high: float) -> np.ndarray:
        """`Generator.uniform(low, high)` once for each stream in `index`."""
        return low + (high - low) * self.next_double(index)

    @property
    def nbytes(self) -> int:
        return sum(a.nbytes for a in (self.state_hi, self.state_lo, self.inc_hi, self.inc_lo))


def _mulhi(a: np.ndarray, b: np.uint64) -> np.ndarray:
    """The high 64 bits of the 128-bit products a * b (uint64)."""
    a0, a1 = a & _LOW32, a >> _32
    b0, b1 = b & _LOW32, b >> _32
    p00, p01, p10, p11 = a0 * b0, a0 * b1, a1 * b0, a1 * b1
    middle = (p00 >> _32) + (p01 & _LOW32) + (p10 & _LOW32)
    return p11 + (p01 >> _32) + (p10 >> _32) + (middle >> _32)
