"""Fight any policy yourself, with the keyboard, in a pygame window.

    python -m agents.play rush
    python -m agents.play runs/ppo.zip --seat 1 --save-replay runs/me_vs_ppo.json

Keys (the seed's InputHandler: keys held map to the fighter's action each step):
    move: left/right arrows or A/D     jump: up arrow, W or space (with a direction: jump that way)
    crouch / fast-fall: down arrow or S
    punch: J or Z    kick: K or X    block: L or C    quit: Esc or close the window
Several keys at once: block beats kick beats punch beats jump beats crouch beats walking.
"""

from __future__ import annotations

import argparse
import sys
import time
from collections.abc import Callable, Collection, Iterable, Sequence
from typing import Any

from vooga_env.actions import Action
from vooga_env.config import FightConfig
from vooga_env.match import EpisodeRecord, episode_seeds
from vooga_env.policies import Policy
from vooga_env.replay import Replay

from . import common

try:
    import pygame
except ImportError:  # pragma: no cover - pygame is the `render` extra
    raise ImportError("playing needs pygame: pip install 'vooga-env[render]'") from None

LEFT_KEYS = (pygame.K_LEFT, pygame.K_a)
RIGHT_KEYS = (pygame.K_RIGHT, pygame.K_d)
JUMP_KEYS = (pygame.K_UP, pygame.K_w, pygame.K_SPACE)
DOWN_KEYS = (pygame.K_DOWN, pygame.K_s)
PUNCH_KEYS = (pygame.K_j, pygame.K_z)
KICK_KEYS = (pygame.K_k, pygame.K_x)
BLOCK_KEYS = (pygame.K_l, pygame.K_c)
QUIT_KEYS = (pygame.K_ESCAPE,)


def action_from_keys(held: Collection[int], seat: int = 0) -> Action:
    """The action for the keys held (pygame key codes), for the fighter in `seat`.

    Left and right are on the screen; `fighter_1`'s actions are mirrored, so for seat 1 the
    screen's left is its Action.RIGHT.
    """

    def down(keys: Sequence[int]) -> bool:
        return any(key in held for key in keys)

    screen = int(down(RIGHT_KEYS)) - int(down(LEFT_KEYS))  # -1 left, 0 none, 1 right
    direction = screen if seat == 0 else -screen
    if down(BLOCK_KEYS):
        return Action.BLOCK
    if down(KICK_KEYS):
        return Action.KICK
    if down(PUNCH_KEYS):
        return Action.PUNCH
    if down(JUMP_KEYS):
        return {-1: Action.JUMP_LEFT, 0: Action.JUMP, 1: Action.JUMP_RIGHT}[direction]
    if down(DOWN_KEYS):
        return Action.DOWN
    return {-1: Action.LEFT, 0: Action.IDLE, 1: Action.RIGHT}[direction]


class InputHandler:
    """Keeps the set of keys held from pygame's key events; `quit` once Esc or the close button."""

    def __init__(self, seat: int = 0) -> None:
        self.seat = seat
        self.held: set[int] = set()
        self.quit = False

    def handle(self, event: Any) -> None:
        if event.type == pygame.QUIT or (event.type == pygame.KEYDOWN and event.key in QUIT_KEYS):
            self.quit = True
        elif event.type == pygame.KEYDOWN:
            self.held.add(event.key)
        elif event.type == pygame.KEYUP:
            self.held.discard(event.key)
        elif event.type == pygame.WINDOWFOCUSLOST:
            self.held.clear()  # a key released in another window never sends its KEYUP here

    def action(self) -> Action:
        return action_from_keys(self.held, self.seat)


def run_play(
    opponent: Policy,
    seat: int = 0,
    config: str | FightConfig = "default",
    seed: int = 0,
    max_steps: int | None = None,
    get_events: Callable[[], Iterable[Any]] | None = None,
    end_pause: float = 0.0,
) -> tuple[EpisodeRecord, FightConfig]:
    """One game of the person (keyboard, in `seat`) against `opponent`, in a window.

    `get_events` gives each step's pygame events (default `pygame.event.get`); the game stops at
    its end, after `max_steps`, or when the person quits. Returns the game (with its actions) and
    the config, which make a replay.
    """
    import vooga_env

    if seat not in (0, 1):
        raise ValueError(f"seat must be 0 or 1, got {seat!r}")
    env = vooga_env.parallel_env(config=config, render_mode="human")
    agents = env.possible_agents
    env_seed, _, opponent_seed = episode_seeds(seed, 0)
    names = ("human", opponent.name) if seat == 0 else (opponent.name, "human")
    seeds = (None, opponent_seed) if seat == 0 else (opponent_seed, None)
    record = EpisodeRecord(env_seed, names, seeds, actions=[])
    handler = InputHandler(seat)
    get_events = get_events or pygame.event.get
    try:
        opponent.reset(opponent_seed)
        observations, _ = env.reset(seed=env_seed)
        while env.agents and (max_steps is None or record.steps < max_steps):
            for event in get_events():
                handler.handle(event)
            if handler.quit:
                break
            mine = int(handler.action())
            theirs = int(opponent.act(observations[agents[1 - seat]]))
            actions = (mine, theirs) if seat == 0 else (theirs, mine)
            observations, _, _, _, infos = env.step(dict(zip(agents, actions, strict=True)))
            record.add_step(actions, infos)
        record.close(env)
        if end_pause > 0 and not handler.quit:
            time.sleep(end_pause)
    finally:
        env.close()
    return record, env.config


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="vooga-play",
        description="Fight a policy with the keyboard.",
        epilog=__doc__.split("\n\n", 2)[2],
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    parser.add_argument("opponent", help="a scripted name or a saved model path (.zip)")
    parser.add_argument(
        "--seat",
        type=int,
        choices=(0, 1),
        default=0,
        help="0: you are fighter_0 (red, left); 1: fighter_1 (blue, right)",
    )
    common.add_fight_options(parser)
    parser.add_argument("--save-replay", metavar="FILE", help="save the game as a replay")
    return parser


def main(argv: Sequence[str] | None = None) -> int:
    parser = build_parser()
    args = parser.parse_args(argv)
    config = common.fight_config(parser, args)
    opponent = common.policy(parser, args.opponent)
    print(__doc__.split("\n\n", 2)[2].rstrip())
    record, config = run_play(opponent, args.seat, config, args.seed, end_pause=1.5)
    if record.winner is None:
        print(f"stopped after {record.steps} steps")
    else:
        you = f"fighter_{args.seat}"
        verdict = (
            "draw"
            if record.winner == "draw"
            else ("you win" if record.winner == you else f"{opponent.name} wins")
        )
        print(
            f"{verdict} after {record.steps} steps (health {record.health}, stocks {record.stocks})"
        )
    if args.save_replay:
        Replay.from_episode(record, config).save(args.save_replay)
        print(f"replay: {args.save_replay} (python -m agents.match --replay {args.save_replay})")
    return 0


if __name__ == "__main__":
    sys.exit(main())
