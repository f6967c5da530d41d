"""A run folder that loses nothing: atomic writes, one state file that commits each checkpoint,
no non-finite model saved, and a lock so that one run at a time uses the folder.

Every checkpoint is written under a name of its own (`checkpoints/ppo_N_steps.zip`, SB3's names,
and `checkpoints/ppo_vecnormalize_N_steps.pkl`), each atomically (temp file, fsync, rename). Then
`train_state.json` is replaced atomically: it names the checkpoint it belongs to, with its step
count and SHA-256, so it commits the checkpoint. Last, `latest.zip` and `vec_normalize.pkl` are
linked to the committed files. A kill at any point leaves a state file that names whole,
matching files; `read_state` checks them, and `--resume` puts `latest.zip` back in step with the
state if a kill fell between the state and the link.
"""

from __future__ import annotations

import dataclasses
import errno
import fcntl
import hashlib
import json
import os
import shutil
from pathlib import Path
from typing import Any

import numpy as np

from vooga_env.tools.files import atomic_write, atomic_write_text, fsync

STATE_FILE = "train_state.json"
LATEST = "latest.zip"
NORMALIZER_FILE = "vec_normalize.pkl"  # VecNormalize's running statistics, for --resume
LOCK_FILE = ".lock"
CHECKPOINTS = "checkpoints"


class RunLocked(RuntimeError):
    """Another live process holds the run folder's lock."""


class Diverged(RuntimeError):
    """The model holds non-finite weights: it is not saved, the last good checkpoint stays."""


class BrokenRun(ValueError):
    """The run folder's state file, or a file it names, cannot be used to resume."""


def atomic_link(source: Path, path: Path) -> None:
    """Make `path` another name of `source` (a hard link), replacing what `path` was atomically."""
    temporary = path.with_name(f".{path.name}.{os.getpid()}.link")
    temporary.unlink(missing_ok=True)
    os.link(source, temporary)
    os.replace(temporary, path)
    fsync(path.parent)


def sha256(path: Path) -> str:
    digest = hashlib.sha256()
    with path.open("rb") as file:
        for chunk in iter(lambda: file.read(1 << 20), b""):
            digest.update(chunk)
    return digest.hexdigest()


def check_finite(model: Any, step: int) -> None:
    """Raise Diverged naming every policy tensor that holds NaN or inf values."""
    bad = []
    total = 0
    for name, tensor in model.policy.state_dict().items():
        values = tensor.detach().cpu().numpy()
        count = int(values.size - np.isfinite(values).sum())
        if count:
            bad.append(f"{name} ({count} of {values.size})")
            total += count
    if bad:
        more = f" and {len(bad) - 3} more tensors" if len(bad) > 3 else ""
        raise Diverged(
            f"training diverged by step {step}: {total} non-finite weights, in "
            + ", ".join(bad[:3])
            + more
        )


def checkpoint_names(step: int) -> tuple[str, str]:
    """The model's and the normaliser's files of the checkpoint at `step` (SB3's names)."""
    return f"{CHECKPOINTS}/ppo_{step}_steps.zip", f"{CHECKPOINTS}/ppo_vecnormalize_{step}_steps.pkl"


def save_checkpoint(model: Any, folder: Path, parts: list[Any]) -> dict[str, Any]:
    """Write the checkpoint at the model's step and commit it in train_state.json; return the state.

    A model with non-finite weights raises Diverged before anything is written. `parts` are
    callbacks whose `state()` (the curriculum's stage, the self-play pool) rides in the state.
    """
    step = int(model.num_timesteps)
    check_finite(model, step)
    model_name, normalizer_name = checkpoint_names(step)
    atomic_write(folder / model_name, model.save)
    state: dict[str, Any] = {
        "num_timesteps": step,
        "checkpoint": model_name,
        "sha256": {model_name: sha256(folder / model_name)},
    }
    normalizer = model.get_vec_normalize_env()
    if normalizer is not None:
        atomic_write(folder / normalizer_name, normalizer.save)
        state["normalizer"] = normalizer_name
        state["sha256"][normalizer_name] = sha256(folder / normalizer_name)
    for part in parts:
        state.update(part.state())
    atomic_write_text(folder / STATE_FILE, json.dumps(state, indent=2))
    link_latest(folder, state)
    return state


def link_latest(folder: Path, state: dict[str, Any]) -> None:
    """Point latest.zip (and vec_normalize.pkl) at the files the state commits."""
    atomic_link(folder / state["checkpoint"], folder / LATEST)
    if "normalizer" in state:
        atomic_link(folder / state["normalizer"], folder / NORMALIZER_FILE)


def remove_partial_files(folder: Path) -> list[Path]:
    """Delete the temp files of writes a kill cut short (only the run holding the lock may)."""
    partial = [*folder.rglob(".*.tmp"), *folder.rglob(".*.link")]
    for path in partial:
        path.unlink()
    return partial


def holds_run(folder: Path) -> bool:
    """Whether `folder` holds a run: a committed state or a latest checkpoint."""
    return (folder / STATE_FILE).exists() or (folder / LATEST).exists()


def resume_state(folder: Path) -> dict[str, Any]:
    """The committed state of the run in `folder`, with the temp files of cut-short writes gone
    and latest.zip pointing at it again (a kill between the state and its link left it behind)."""
    remove_partial_files(folder)
    state = read_state(folder)
    link_latest(folder, state)
    return state


def start_fresh(folder: Path, overwrite: bool, config: Any, config_file: str) -> None:
    """Make `folder` a new run's and write its config there. A folder holding a run is refused,
    or with `overwrite` emptied but for our lock; a folder holding none is never emptied (so
    `--out .` deletes nothing)."""
    if holds_run(folder):
        if not overwrite:
            raise FileExistsError(
                f"{folder} holds a run already: --resume continues it, --overwrite starts over "
                "(deleting it), or pick another --out"
            )
        for path in folder.iterdir():
            if path.name == LOCK_FILE:  # ours now
                continue
            if path.is_dir() and not path.is_symlink():
                shutil.rmtree(path)
            else:
                path.unlink()
    atomic_write_text(folder / config_file, json.dumps(dataclasses.asdict(config), indent=2))


def read_state(folder: Path) -> dict[str, Any]:
    """The committed state, its files checked against their SHA-256; BrokenRun says what is off."""
    path = folder / STATE_FILE
    try:
        state = json.loads(path.read_text())
    except FileNotFoundError:
        raise BrokenRun(f"--resume: {folder} has no {STATE_FILE}, no checkpoint") from None
    except (OSError, json.JSONDecodeError) as error:
        raise BrokenRun(f"--resume: cannot read {path}: {error}") from None
    if not isinstance(state, dict) or not isinstance(state.get("sha256"), dict):
        raise BrokenRun(
            f"--resume: {path} has no sha256 table (an older vooga_env's run?): --overwrite "
            "starts over"
        )
    for key in ("checkpoint", "normalizer"):
        if key in state and state[key] not in state["sha256"]:
            raise BrokenRun(f"--resume: {path}: {key} {state[key]!r} has no sha256")
    for name, expected in state["sha256"].items():
        file = folder / name
        if not file.is_file() or sha256(file) != expected:
            raise BrokenRun(f"--resume: {file}, committed in {path}, is missing or changed")
    return state


class RunLock:
    """An exclusive lock on a run folder, held while a run uses it (a `with` block).

    The kernel holds the lock (`flock`) and drops it when the process dies, however it dies; the
    file names the holder's pid, for the message that refuses a second run. A file that names a
    pid while its lock is free was left by a killed run: the lock is taken over, and said so.
    """

    def __init__(self, folder: Path) -> None:
        self.path = folder / LOCK_FILE
        self.handle: int | None = None
        self.stale_pid: str = ""

    def __enter__(self) -> RunLock:
        self.path.parent.mkdir(parents=True, exist_ok=True)
        handle = os.open(self.path, os.O_RDWR | os.O_CREAT, 0o644)
        try:
            fcntl.flock(handle, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except OSError as error:
            holder = os.read(handle, 64).decode(errors="replace").strip() or "unknown"
            os.close(handle)
            if error.errno not in (errno.EAGAIN, errno.EACCES):
                raise
            raise RunLocked(
                f"{self.path.parent} is in use by another training run (pid {holder}): wait for "
                "it to end or stop it, or pick another --out"
            ) from None
        self.stale_pid = os.read(handle, 64).decode(errors="replace").strip()
        os.ftruncate(handle, 0)
        os.pwrite(handle, f"{os.getpid()}\n".encode(), 0)
        self.handle = handle
        return self

    def __exit__(self, *exc_info: object) -> None:
        if self.handle is not None:
            os.ftruncate(self.handle, 0)  # empty: released cleanly, not left by a killed run
            os.close(self.handle)
            self.handle = None
