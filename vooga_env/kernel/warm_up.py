"""Compile (or load) every kernel the envs use, ahead of a first step: `python -m
vooga_env.kernel.warm_up` (`make` runs it at install)."""

from __future__ import annotations

import time

import numpy as np

from vooga_env.game.config import load_config
from vooga_env.kernel.single import CompiledSimulation
from vooga_env.kernel.vector_fight import VectorFight


def warm_up() -> float:
    """Step one compiled fight and the batched engine on one and two threads; seconds."""
    start = time.perf_counter()
    fight = CompiledSimulation(load_config("default"))
    fight.reset(np.random.default_rng(0))
    fight.step(0, 0)
    for threads in (1, 2):  # the serial step, and the one in chunks on threads
        fights = VectorFight(2, backend="numba", threads=threads)
        fights.reset(seed=0)
        fights.step(np.zeros((2, 2), dtype=np.int64))
        fights.advance(np.zeros((2, 2), dtype=np.int64))
    return time.perf_counter() - start


if __name__ == "__main__":
    print("numba: compiling the fight kernels once (cached on disk for later runs)...", flush=True)
    print(f"numba: ready in {warm_up():.0f} s")
