"""Fight any policy yourself, with the keyboard, in a pygame window.

    python -m agents.play rush
    python -m agents.play runs/ppo.zip --seat 1 --rounds 3 --speed 0.75 --config platforms

Each round opens with a countdown, and ends on a result screen (Enter or Space: next round); a
match is best of --rounds rounds, of --stocks stocks each (default 3). The round's clock gives
each stock the config's time (`default`: 900 steps, 36 s at speed 1, so 108 s for 3 stocks)
unless --max-cycles sets it. On the match's result screen R or Enter plays a new match.

Every round is saved as a replay (the `vooga_env.tools.replay` format; watch it again with
`python -m agents.match --replay FILE --render`) in --replay-dir, by default runs/play/ under
the current folder, named <date>-<time>-<opponent>-m<match>-r<round>.json; each path is printed
as it is written. --no-replay saves nothing.

It needs a display. Without one it stops (exit status 2) and says how to get one; a test or a
screenshot script can set SDL_VIDEODRIVER=dummy to run it without a window on purpose.

"""

from __future__ import annotations

import argparse
import math
import os
import re
import sys
import time
from collections.abc import Callable, Iterable, Sequence
from pathlib import Path
from typing import Any

from vooga_env.envs.render import HEADLESS_DRIVERS
from vooga_env.game.config import ConfigError, FightConfig, load_config
from vooga_env.policies import SCRIPTED
from vooga_env.tools.match import EpisodeRecord
from vooga_env.tools.replay import Replay

from . import common
from .play_keys import HELP_TEXT
from .play_loop import SPEED_RANGE, Clock, Game, PlaySettings, check_speed, run
from .play_screens import Screens

DEFAULT_REPLAY_DIR = Path("runs/play")
PLAY_STOCKS = 3
NO_DISPLAY = (
    "no display to open the game's window on ({why}).\n"
    "Run it in a desktop session, or give it a display: over ssh, `ssh -X host` sets DISPLAY; "
    "for a virtual X display, `apt-get install xvfb` and run it under `xvfb-run -a python -m "
    "agents.play ...`, or start `Xvfb :99 &` and set DISPLAY=:99. To run with no window on "
    "purpose (tests, screenshots), set SDL_VIDEODRIVER=dummy."
)


def display_problem() -> str | None:
    """Why no window can be shown (SDL has no display, or only an off-screen one), or None.

    SDL falls back to its `offscreen` driver without a display: the game would run blind. A
    driver named in SDL_VIDEODRIVER is the user's choice and is kept, `dummy` included.
    """
    import pygame

    try:
        pygame.display.init()
    except pygame.error as error:
        return NO_DISPLAY.format(why=f"SDL: {error}")
    driver = pygame.display.get_driver()
    if driver in HEADLESS_DRIVERS and not os.environ.get("SDL_VIDEODRIVER"):
        pygame.display.quit()
        why = "DISPLAY and WAYLAND_DISPLAY are not set" if _no_display_vars() else "SDL found none"
        return NO_DISPLAY.format(why=f"{why}; SDL fell back to its {driver!r} driver")
    return None


class ReplaySaver:
    """Saves each round the game reports as a replay in `folder`; prints and keeps the paths."""

    def __init__(self, folder: str | Path, opponent: str, config: FightConfig) -> None:
        self.folder = Path(folder)
        self.stem = f"{time.strftime('%Y%m%d-%H%M%S')}-{re.sub(r'[^A-Za-z0-9_.-]+', '_', opponent)}"
        self.config = config
        self.saved: list[Path] = []

    def __call__(self, record: EpisodeRecord, game: Game) -> Path:
        name = f"{self.stem}-m{game.match.number}-r{len(game.match.rounds) + (not record.finished)}"
        path = self.folder / f"{name}.json"
        copy = 1
        while path.exists():  # two sessions started in the same second
            copy += 1
            path = self.folder / f"{name}-{copy}.json"
        Replay.from_episode(record, self.config).save(path)
        print(f"replay: {path}   (python -m agents.match --replay {path} --render)", flush=True)
        self.saved.append(path)
        return path


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="vooga-play",
        description="Fight a policy with the keyboard, in a window.",
        epilog=__doc__.split("\n\n", 1)[1] + HELP_TEXT,
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    parser.add_argument(
        "opponent", help="a scripted name, a saved model (.zip) or an exported fighter (.npz)"
    )
    parser.add_argument(
        "--seat",
        type=int,
        choices=(0, 1),
        default=0,
        help="0: you are fighter_0 (red, left); 1: fighter_1 (blue, right)",
    )
    common.add_fight_options(parser)
    parser.add_argument(
        "--stocks",
        type=common._positive,
        default=PLAY_STOCKS,
        help=f"stocks (lives) each per round (default {PLAY_STOCKS})",
    )
    parser.add_argument(
        "--rounds", type=common._positive, default=1, help="a match is best of N rounds (default 1)"
    )
    low, high = SPEED_RANGE
    parser.add_argument(
        "--speed",
        type=_speed,
        default=1.0,
        help=f"game speed, {low}..{high} times the env's render_fps (default 1)",
    )
    replays = parser.add_mutually_exclusive_group()
    replays.add_argument(
        "--replay-dir",
        type=Path,
        default=DEFAULT_REPLAY_DIR,
        metavar="DIR",
        help=f"save every round's replay here (default {DEFAULT_REPLAY_DIR}/)",
    )
    replays.add_argument("--no-replay", action="store_true", help="save no replays")
    return parser


def main(
    argv: Sequence[str] | None = None,
    events: Callable[[], Iterable[Any]] | None = None,
    clock: Clock | None = None,
) -> int:
    """The command; `events` and `clock` replace the window's (tests drive it with scripts)."""
    parser = build_parser()
    args = parser.parse_args(argv)
    config = play_config(parser, args)
    os.environ.setdefault("SDL_AUDIODRIVER", "dummy")  # no sound: no audio device needed
    problem = display_problem()
    if problem is not None:
        print(f"{parser.prog}: {problem}", file=sys.stderr)
        return 2
    opponent = common.policy(parser, args.opponent)
    label = opponent.name if args.opponent in SCRIPTED else Path(args.opponent).name
    import vooga_env

    env = vooga_env.parallel_env(config=config, backend="engine")
    saver = None if args.no_replay else ReplaySaver(args.replay_dir, label, env.config)
    settings = PlaySettings(args.seat, args.rounds, args.speed, args.seed)
    game = Game(env, opponent, settings, on_round_end=saver, opponent_name=label)
    print(HELP_TEXT, flush=True)
    try:
        run(game, _window(game), events, clock)
    except KeyboardInterrupt:  # Ctrl-C in the terminal: stop as Esc does, keeping the round
        game.quit()
    finally:
        env.close()
        _close_window()
    _summary(game, saver)
    return 0


def play_config(parser: argparse.ArgumentParser, args: argparse.Namespace) -> FightConfig:
    """The stage with --stocks stocks; its clock keeps the config's time per stock (900 steps a
    stock on `default`) unless --max-cycles sets it. A bad name or value is a usage error."""
    try:
        base = load_config(args.config)
        max_cycles = args.max_cycles
        if max_cycles is None:
            max_cycles = math.ceil(base.max_cycles * args.stocks / base.stocks)
        return load_config(base, stocks=args.stocks, max_cycles=max_cycles)
    except ConfigError as error:
        parser.error(str(error))


def _summary(game: Game, saver: ReplaySaver | None) -> None:
    for match in game.matches:
        if not match.rounds:
            continue  # quit before its first round ended
        wins, losses = match.count("win"), match.count("loss")
        verdict = {"win": "you won", "loss": f"{game.opponent_name} won", "draw": "drawn"}
        rounds = ", ".join(f"{r.outcome} ({r.how})" for r in match.rounds)
        print(f"match {match.number}: {verdict[match.outcome]} {wins}-{losses}; rounds: {rounds}")
    if saver is not None and saver.saved:
        print(f"{len(saver.saved)} replay(s) in {saver.folder}/")


def _window(game: Game) -> Callable[[], None]:
    """Open the game's window (the stage's size); returns what draws a frame in it."""
    import pygame

    arena = game.env.config.arena
    window = pygame.display.set_mode((int(arena.width), int(arena.height)))
    pygame.display.set_caption(f"vooga_env: you vs {game.opponent_name}")
    screens = Screens(game, window)

    def draw() -> None:
        screens.draw()
        pygame.display.flip()

    return draw


def _close_window() -> None:
    import pygame

    pygame.display.quit()


def _speed(text: str) -> float:
    try:
        value: Any = float(text)
    except ValueError:
        value = text
    try:
        return check_speed(value)
    except ValueError as error:
        raise argparse.ArgumentTypeError(str(error)) from None


def _no_display_vars() -> bool:
    return not (os.environ.get("DISPLAY") or os.environ.get("WAYLAND_DISPLAY"))


if __name__ == "__main__":
    sys.exit(main())
