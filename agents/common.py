"""What the command-line tools share: the fight options, policy and config look-up with clean
errors, a progress bar, plain-text tables and JSON output, and how Ctrl-C and SIGTERM stop them."""

from __future__ import annotations

import argparse
import json
import math
import os
import signal
import sys
import threading
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import Any

from vooga_env.game.config import ConfigError, FightConfig, load_config
from vooga_env.policies import SCRIPTED, Policy, make_policy
from vooga_env.tools.files import atomic_write_text
from vooga_env.tools.match import EpisodeRecord

# pygame greets on stdout when imported; that would break --json output.
os.environ.setdefault("PYGAME_HIDE_SUPPORT_PROMPT", "1")


def one_core() -> Any:
    """Torch and numpy's BLAS on one thread each, from now on (or, used as a context, until its
    end): a run has one core of this 2-core machine, and threads only wait on each other once
    the other core is busy (numpy's BLAS on two threads was 27x slower on a 680-row batch of
    a policy, docs/league.md)."""
    import torch
    from threadpoolctl import threadpool_limits

    torch.set_num_threads(1)
    return threadpool_limits(limits=1, user_api="blas")


def quiet_logger(model: Any) -> Any:
    """The model, logging nowhere unless it has a TensorBoard folder: SB3's learn() without one
    still makes an empty tempdir/SB3-<time> folder, one per learn (every league and exploiter
    left one in /tmp). With a folder, SB3 sets its logger up itself, as before."""
    if model.tensorboard_log is None:
        from stable_baselines3.common.logger import Logger

        model.set_logger(Logger(folder=None, output_formats=[]))
    return model


STOP_REQUESTED = threading.Event()


def stop_on_signals() -> None:
    """Take SIGTERM as Ctrl-C in this process, and Ctrl-C itself unless it is ignored here (a
    league's process leaves it to its parent): a KeyboardInterrupt now, and again at the next
    training step (`callbacks.StopWhenRequested`) if the first one was lost. Python's own Ctrl-C
    raises once only, where numpy may drop it as it dropped a SIGTERM's."""
    signal.signal(signal.SIGTERM, request_stop)
    if signal.getsignal(signal.SIGINT) is signal.default_int_handler:
        signal.signal(signal.SIGINT, request_stop)


def request_stop(signum: int, frame: Any) -> None:
    """The handler `stop_on_signals` installs (the RLlib trainer keeps it over Ray's SIGTERM)."""
    STOP_REQUESTED.set()
    raise KeyboardInterrupt


def start_without_ctrl_c(processes: list[Any]) -> None:
    """Start `processes` with SIGINT ignored (an ignored signal stays ignored in the new
    interpreter): Ctrl-C is the caller's, which stops them its own way. Only the main thread
    may set a handler; elsewhere Ctrl-C does not reach the caller anyway."""
    if threading.current_thread() is not threading.main_thread():
        for process in processes:
            process.start()
        return
    previous = signal.signal(signal.SIGINT, signal.SIG_IGN)
    try:
        for process in processes:
            process.start()
    finally:
        signal.signal(signal.SIGINT, previous)


class WindowClosed(Exception):
    """The person closed the pygame window: stop quietly."""


def add_fight_options(parser: argparse.ArgumentParser, episodes: int | None = None) -> None:
    """--config, --max-cycles, --seed, and (if `episodes` is given) --episodes with that default."""
    parser.add_argument(
        "--config", default="default", help="a config name from configs/ or a .toml path"
    )
    parser.add_argument(
        "--max-cycles", type=int, default=None, help="override the config's episode length (steps)"
    )
    parser.add_argument("--seed", type=_non_negative, default=0, help="base seed (default 0)")
    if episodes is not None:
        parser.add_argument(
            "--episodes", type=_positive, default=episodes, help=f"games (default {episodes})"
        )


def add_output_options(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--json", action="store_true", help="print JSON instead of a table")
    parser.add_argument("--no-progress", action="store_true", help="no progress bar")


def fight_config(parser: argparse.ArgumentParser, args: argparse.Namespace) -> FightConfig:
    """The config the options name, or a usage error naming the bad name or key."""
    overrides = {} if args.max_cycles is None else {"max_cycles": args.max_cycles}
    try:
        return load_config(args.config, **overrides)
    except ConfigError as error:
        parser.error(str(error))


def policy(parser: argparse.ArgumentParser, spec: str) -> Policy:
    """A scripted fighter or a saved model, or a usage error that lists the known names."""
    try:
        return make_policy(spec)
    except (ValueError, FileNotFoundError, ImportError) as error:
        message = str(error)
        if not all(name in message for name in SCRIPTED):
            message += f" (scripted fighters: {', '.join(SCRIPTED)})"
        parser.error(message)


def progress_bar(
    total: int, enabled: bool, description: str
) -> tuple[Callable[[EpisodeRecord], None] | None, Callable[[], None]]:
    """A per-game callback that advances a tqdm bar on stderr, and a function that closes it."""
    if not enabled:
        return None, lambda: None
    try:
        from tqdm import tqdm
    except ImportError:  # the bar is a nicety; tqdm comes with the `train` extra
        return None, lambda: None
    bar = tqdm(total=total, desc=description, unit="game", file=sys.stderr, leave=False)
    return (lambda _record: bar.update()), bar.close


def stop_on_window_close(_record: EpisodeRecord) -> None:
    """A step hook for human rendering: raise WindowClosed on the window's close button or Esc.

    It empties pygame's event queue each step, so that a long watch cannot fill it.
    """
    import pygame

    if not pygame.display.get_init():
        return
    for event in pygame.event.get():
        if event.type == pygame.QUIT or (
            event.type == pygame.KEYDOWN and event.key == pygame.K_ESCAPE
        ):
            raise WindowClosed


def table(headers: Sequence[str], rows: Sequence[Sequence[Any]]) -> str:
    """A plain-text table: text left-aligned, numbers right-aligned, floats to 2 places."""
    cells = [[_cell(value) for value in row] for row in rows]
    widths = [max(len(str(h)), *(len(row[i]) for row in cells)) for i, h in enumerate(headers)]
    numeric = [
        all(_is_number(row[i]) for row in rows) if rows else False for i in range(len(headers))
    ]

    def line(values: Sequence[str]) -> str:
        return "  ".join(
            value.rjust(width) if right else value.ljust(width)
            for value, width, right in zip(values, widths, numeric, strict=True)
        ).rstrip()

    rule = "  ".join("-" * width for width in widths)
    return "\n".join([line([str(h) for h in headers]), rule, *(line(row) for row in cells)])


def check_output(parser: argparse.ArgumentParser, flag: str, path: str | Path) -> None:
    """A usage error now, before any game is played, if `path` cannot be written later."""
    path = Path(path)
    if path.is_dir():
        parser.error(f"{flag} {path} is a folder; give a file name")
    folder = next((parent for parent in path.parents if parent.exists()), Path("."))
    if not folder.is_dir():
        parser.error(f"{flag} {path}: {folder} is a file, not a folder")
    if not os.access(folder, os.W_OK):
        parser.error(f"{flag} {path}: cannot write in {folder}")


def write_json(path: str | Path, data: Any) -> Path:
    """Write JSON atomically (temp file, fsync, rename): a reader never sees half a report."""
    return atomic_write_text(Path(path), json.dumps(data, indent=2) + "\n")


def print_json(data: Any) -> None:
    print(json.dumps(data, indent=2))


def fps(config: FightConfig) -> float:
    """Env steps per second of game time."""
    return 1000.0 / (config.physics.frame_time * config.frame_skip)


def _cell(value: Any) -> str:
    if isinstance(value, float):
        return f"{value:.2f}"
    return str(value)


def _is_number(value: Any) -> bool:
    return isinstance(value, (int, float)) and not isinstance(value, bool)


def _positive(text: str) -> int:
    value = int(text)
    if value < 1:
        raise argparse.ArgumentTypeError(f"must be >= 1, got {value}")
    return value


def _non_negative(text: str) -> int:
    value = int(text)
    if value < 0:
        raise argparse.ArgumentTypeError(f"must be >= 0, got {value}")
    return value


def budget_minutes(minutes: float | None, configured: float) -> float:
    """A run's wall-time budget: `minutes` where given (0: none, whatever the config says), else
    the config's."""
    if minutes is None:
        return configured
    if not (math.isfinite(minutes) and minutes >= 0):
        raise ConfigError(f"minutes = {minutes!r} is not allowed: must be >= 0 (0: no budget)")
    return minutes


def _minutes(text: str) -> float:
    """A training CLI's --minutes, refused at the flag rather than after the run's set-up."""
    try:
        return budget_minutes(float(text), 0.0)
    except ConfigError:
        raise argparse.ArgumentTypeError(
            f"must be a number >= 0 (0: no budget), got {text!r}"
        ) from None
