"""Keep numba's on-disk cache of the kernel honest.

numba's `cache=True` notices a change to a compiled function's own file only, not to the helpers
and constants it takes from other files (`parts`, `layout`, `state`, ...), which are
compiled into it. So the kernel's cache files are dropped whenever any of those sources changed
since they were written (a stamp of their hash sits beside the cache). `python -m
vooga_env.kernel.warm_up` compiles them all ahead of a first step (`make` does it at install).
"""

from __future__ import annotations

import hashlib
import os
import sys
from pathlib import Path
from types import ModuleType

HERE = Path(__file__).resolve().parent
GAME = HERE.parent / "game"
# Every kernel module (a change to one that is not compiled only costs a recompile), and the game
# rules and formulas the kernel compiles in.
SOURCES = (
    *sorted(HERE.glob("*.py")),
    GAME / "observations.py",
    GAME / "actions.py",
    GAME / "outcome.py",
    GAME / "formulas.py",
    GAME / "pixels.py",
    GAME / "pixel_formulas.py",
    HERE.parent / "physics" / "formulas.py",
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
            return any(cache.glob("*.nbi"))
    except OSError:
        pass
    for path in cache.glob("*.nb[ci]"):
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
    from vooga_env.kernel import compiled as kernel

    return kernel


def load_raster() -> ModuleType:
    """The pixel rasteriser's module (its own compiled entry, a few seconds to compile), any
    stale cache dropped first."""
    drop_stale_kernel_cache()
    from vooga_env.kernel import raster

    return raster
