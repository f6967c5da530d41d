"""Files written whole or not at all: a temp file beside the target, fsync, then one rename."""

from __future__ import annotations

import os
import secrets
from collections.abc import Callable
from pathlib import Path
from typing import Any


def atomic_write(path: Path, write: Callable[[str], Any]) -> Path:
    """Write `path` through `write(temporary_path)`, then fsync and rename it into place.

    Readers (and a later resume) see the old file or the new one whole, never a part.
    """
    path.parent.mkdir(parents=True, exist_ok=True)
    temporary = str(path.with_name(f".{path.name}.{os.getpid()}.{secrets.token_hex(4)}.tmp"))
    os.close(os.open(temporary, os.O_WRONLY | os.O_CREAT | os.O_EXCL, 0o666))  # umask applies
    try:
        write(temporary)
        fsync(temporary)
        os.replace(temporary, path)
    except BaseException:
        Path(temporary).unlink(missing_ok=True)
        raise
    fsync(path.parent)  # makes the rename durable: the name lives in the folder
    return path


def atomic_write_text(path: Path, text: str) -> Path:
    return atomic_write(path, lambda temporary: Path(temporary).write_text(text))


def fsync(path: str | Path) -> None:
    handle = os.open(path, os.O_RDONLY)
    try:
        os.fsync(handle)
    finally:
        os.close(handle)
