"""Keep numba's on-disk cache of the kernel honest.

numba's `cache=True` notices a change to a compiled function's own file only, not to the helpers
and constants it takes from other files (`kernel_parts`, `layout`, `state`, ...), which are
compiled into it. So the kernel's cache files are dropped whenever any of those sources changed
since they were written (a stamp of their hash sits beside the cache). `python -m
vooga_env.vector.cache` compiles them all ahead of a first step (`make` does it at install).
"""

from __future__ import annotations

import hashlib
import os
import sys
from pathlib import Path
from types import ModuleType

HERE = Path(__file__).resolve().parent
SOURCES = (
    HERE / "kernel.py",
    HERE / "kernel_parts.py",
    HERE / "kernel_step.py",
    HERE / "kernel_observe.py",
    HERE / "stages.py",
    HERE / "layout.py",
    HERE / "state.py",
    HERE.parent / "observations.py",
    HERE.parent / "actions.py",
    HERE.parent / "outcome.py",
    HERE.parent / "physics" / "formulas.py",
    HERE.parent / "formulas.py",
)


# numba's OpenMP pool shares libgomp with torch and changes torch's thread count when it starts;
# the work-queue layer has no such side effect. Used only where `threads` > 1 is asked for.
THREADING_LAYER = "workqueue"
_announced = False


def drop_stale_kernel_cache() -> bool:
    """Delete the kernel's cached machine code if its sources changed since it was cached;
    whether a current cache is there."""
    digest = hashlib.sha256(b"".join(path.read_bytes() for path in SOURCES)).hexdigest()
    cache = HERE / "__pycache__"
    stamp = cache / "kernel_sources.sha256"
    try:
        if stamp.read_text() == digest:
            return any(cache.glob("kernel*.nbi"))
    except OSError:
        pass
    for path in cache.glob("kernel*.nb[ci]"):
        path.unlink(missing_ok=True)
    try:
        cache.mkdir(exist_ok=True)
        stamp.write_text(digest)
    except OSError:  # a read-only install: numba caches elsewhere (NUMBA_CACHE_DIR) or not at all
        pass
    return False


def load_kernel() -> ModuleType:
    """The compiled kernel's module, its stale cache dropped first; says once on stderr when
    the first step will compile (under a minute, once per install) rather than stall
    without a word."""
    global _announced
    import numba

    if "NUMBA_THREADING_LAYER" not in os.environ:
        numba.config.THREADING_LAYER = THREADING_LAYER
    if not drop_stale_kernel_cache() and not _announced:
        _announced = True
        print(
            "vooga_env: compiling the fight kernels with numba (under a minute, once per "
            "install; cached on disk afterwards)...",
            file=sys.stderr,
            flush=True,
        )
    from vooga_env.vector import kernel

    return kernel


def warm_up() -> float:
    """Compile (or load) every kernel the envs use, now rather than at a first step; seconds."""
    import time

    import numpy as np

    from vooga_env.parallel import parallel_env
    from vooga_env.vector.engine import VectorFight

    start = time.perf_counter()
    env = parallel_env(backend="compiled")
    env.reset(seed=0)
    env.step({agent: 0 for agent in env.possible_agents})
    for threads in (1, 2):  # the serial step, and the one in chunks on threads
        fights = VectorFight(2, backend="numba", threads=threads)
        fights.reset(seed=0)
        fights.step(np.zeros((2, 2), dtype=np.int64))
        fights.advance(np.zeros((2, 2), dtype=np.int64))
    return time.perf_counter() - start


if __name__ == "__main__":
    print("numba: compiling the fight kernels once (cached on disk for later runs)...", flush=True)
    print(f"numba: ready in {warm_up():.0f} s")
