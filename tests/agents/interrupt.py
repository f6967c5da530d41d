"""Ctrl-C at a terminal, for the tests of commands that must stop cleanly on it."""

from __future__ import annotations

import signal
import subprocess
import time
from collections.abc import Callable
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]


def interrupt_when(command: list[str], ready: Callable[[], bool], wait: float, stop: float) -> str:
    """Run `command` from the checkout, send it SIGINT once `ready()` (within `wait` seconds),
    and return its stderr; it must exit with 130 within `stop` seconds and say how to
    `--resume`."""
    # As at a terminal: a suite started in the background (`cmd &` in a script) inherits an
    # ignored SIGINT, and Python installs no KeyboardInterrupt handler when SIGINT is ignored.
    process = subprocess.Popen(
        command,
        cwd=ROOT,
        stderr=subprocess.PIPE,
        text=True,
        preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL),
    )
    deadline = time.monotonic() + wait
    while not ready():
        assert process.poll() is None and time.monotonic() < deadline
        time.sleep(0.2)
    process.send_signal(signal.SIGINT)
    _, stderr = process.communicate(timeout=stop)
    assert process.returncode == 130, stderr
    assert "--resume" in stderr
    return stderr
