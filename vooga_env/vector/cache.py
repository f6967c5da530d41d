"""Keep numba's on-disk cache of the kernel honest.

numba's `cache=True` notices a change to a compiled function's own file only, not to the helpers
and constants it takes from other files (`kernel_parts`, `frame`, `state`, ...), which are
compiled into it. So the kernel's cache files are dropped whenever any of those sources changed
since they were written (a stamp of their hash sits beside the cache).
"""

from __future__ import annotations

import hashlib
from pathlib import Path
from types import ModuleType

HERE = Path(__file__).resolve().parent
SOURCES = (
    HERE / "kernel.py",
    HERE / "kernel_parts.py",
    HERE / "kernel_step.py",
    HERE / "frame.py",
    HERE / "state.py",
    HERE.parent / "observations.py",
    HERE.parent / "actions.py",
    HERE.parent / "physics" / "contact.py",
)


def drop_stale_kernel_cache() -> None:
    """Delete the kernel's cached machine code if its sources changed since it was cached."""
    digest = hashlib.sha256(b"".join(path.read_bytes() for path in SOURCES)).hexdigest()
    cache = HERE / "__pycache__"
    stamp = cache / "kernel_sources.sha256"
    try:
        if stamp.read_text() == digest:
            return
    except OSError:
        pass
    for path in cache.glob("kernel*.nb[ci]"):
        path.unlink(missing_ok=True)
    try:
        cache.mkdir(exist_ok=True)
        stamp.write_text(digest)
    except OSError:  # a read-only install: numba caches elsewhere (NUMBA_CACHE_DIR) or not at all
        pass


def load_kernel() -> ModuleType:
    """The compiled kernel's module (numba needed), its stale cache dropped first."""
    drop_stale_kernel_cache()
    from vooga_env.vector import kernel

    return kernel
