"""The keyboard of `agents.play`: which keys are held, the fighter's action they make, and the
control keys (pause, restart, next, quit) with the help text the game shows for them."""

from __future__ import annotations

from collections.abc import Collection, Sequence
from typing import Any

from vooga_env.game.actions import Action

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
FIGHT_KEYS = frozenset(
    LEFT_KEYS + RIGHT_KEYS + JUMP_KEYS + DOWN_KEYS + PUNCH_KEYS + KICK_KEYS + BLOCK_KEYS
)
"""Every key that moves the fighter; the first one pressed hides the key help."""

QUIT_KEYS = (pygame.K_ESCAPE,)
PAUSE_KEYS = (pygame.K_p,)
RESTART_KEYS = (pygame.K_r,)
NEXT_KEYS = (pygame.K_RETURN, pygame.K_KP_ENTER, pygame.K_SPACE)

FIGHT_HELP = (
    "move: left/right arrows or A/D      jump: up arrow, W or Space      crouch: down arrow or S",
    "punch: J or Z      kick: K or X      block: L or C",
)
CONTROL_HELP = "P: pause      Esc: quit"
HELP_TEXT = "\n".join(
    (
        "Keys (held keys make the fighter's action each step):",
        *(f"    {line}" for line in FIGHT_HELP),
        f"    {CONTROL_HELP}      R: restart the match (paused or on a result screen)",
        "Several keys at once: block beats kick beats punch beats jump beats crouch beats walking.",
    )
)


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
    """Keeps the set of keys held from pygame's key events."""

    def __init__(self, seat: int = 0) -> None:
        self.seat = seat
        self.held: set[int] = set()

    def handle(self, event: Any) -> None:
        if event.type == pygame.KEYDOWN:
            self.held.add(event.key)
        elif event.type == pygame.KEYUP:
            self.held.discard(event.key)
        elif event.type == pygame.WINDOWFOCUSLOST:
            self.held.clear()  # a key released in another window never sends its KEYUP here

    def action(self) -> Action:
        return action_from_keys(self.held, self.seat)
