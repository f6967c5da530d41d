"""Ctrl-C at a terminal, for the tests of commands that must stop cleanly on it."""

from __future__ import annotations

import os
import signal
import subprocess
import time
from collections.abc import Callable
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]


def interrupt_when(
    command: list[str],
    ready: Callable[[], bool],
    wait: float,
    stop: float,
    signum: int = signal.SIGINT,
    says: str = "--resume",
) -> str:
    """Run `command` from the checkout, send it `signum` (SIGINT: Ctrl-C; SIGTERM: `kill`, a
    job scheduler) once `ready()` (within `wait` seconds), and return its stderr; it must exit
    with 130 within `stop` seconds and say what to do next (`says`: how to `--resume`).
    Whatever happens, nothing it started is left running."""
    # As at a terminal: a suite started in the background (`cmd &` in a script) inherits an
    # ignored SIGINT, and Python installs no KeyboardInterrupt handler when SIGINT is ignored.
    process = subprocess.Popen(
        command,
        cwd=ROOT,
        stderr=subprocess.PIPE,
        text=True,
        preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL),
        start_new_session=True,  # its own group: killed whole if the test fails
    )
    try:
        deadline = time.monotonic() + wait
        while not ready():
            assert process.poll() is None and time.monotonic() < deadline
            time.sleep(0.2)
        process.send_signal(signum)
        _, stderr = process.communicate(timeout=stop)
    finally:
        left = _end_group(process.pid, grace=0 if process.poll() is None else 10)
        process.wait()
    assert not left, f"processes of {command} ran on after it exited"
    assert process.returncode == 130, stderr
    assert says in stderr
    return stderr


def group_size(marker: str) -> int:
    """How many processes share the process group of the one with `marker` in its command line
    (0 if none has): the processes a command started, as Linux's /proc lists them."""
    groups, leaders = [], []
    for proc in Path("/proc").glob("[0-9]*"):
        try:
            command, stat = (proc / "cmdline").read_bytes(), (proc / "stat").read_text()
        except OSError:  # ended meanwhile
            continue
        groups.append(stat.rsplit(")", 1)[1].split()[2])  # after the name: state, ppid, pgrp
        if marker.encode() in command:
            leaders.append(proc.name)
    return groups.count(leaders[0]) if len(leaders) == 1 else 0


def _end_group(group: int, grace: float) -> bool:
    """Give process group `group` `grace` seconds to end, then kill what is left of it; returns
    whether anything was."""
    deadline = time.monotonic() + grace
    try:
        while time.monotonic() < deadline:
            os.killpg(group, 0)
            time.sleep(0.1)
        os.killpg(group, signal.SIGKILL)
    except ProcessLookupError:
        return False
    return True
