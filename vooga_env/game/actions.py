"""The action table shared by both fighters: one `Discrete(len(Action))` action per env step.

Left and right are in the fighter's own mirrored frame (for `fighter_1` they are swapped), matching
the mirrored observations, so one policy can play either seat.
"""

from __future__ import annotations

import enum
from typing import Any

import numpy as np


class Action(enum.IntEnum):
    """What a fighter does this step (the action repeats for each of the step's physics frames)."""

    IDLE = 0
    LEFT = 1  # walk (also steers in the air)
    RIGHT = 2
    JUMP = 3  # an impulse from the ground, or one of the air jumps; press again to jump again
    JUMP_LEFT = 4
    JUMP_RIGHT = 5
    DOWN = 6  # crouch on the ground (ducks high attacks), fast-fall in the air
    PUNCH = 7  # fast, short, light
    KICK = 8  # slower, longer, low, more knockback
    BLOCK = 9  # on the ground, facing the attacker: cuts damage and knockback; no moving


WALK = {
    Action.LEFT: -1.0,
    Action.RIGHT: 1.0,
    Action.JUMP_LEFT: -1.0,
    Action.JUMP_RIGHT: 1.0,
}
JUMPS = frozenset({Action.JUMP, Action.JUMP_LEFT, Action.JUMP_RIGHT})
ATTACKS = {Action.PUNCH: "punch", Action.KICK: "kick"}


def action_index(who: str, action: Any) -> int:
    """`action` as a plain int in 0..9 (a numpy integer or 0-d array too), or a clear error.

    `who` names the action's source in the message, e.g. "action for fighter_0".
    """
    value = action
    if isinstance(action, np.ndarray) and action.shape == ():
        value = action.item()
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, (int, np.integer)):
        raise TypeError(f"{who} must be an int in 0..{len(Action) - 1}, got {action!r}")
    if not 0 <= value < len(Action):
        raise ValueError(f"{who} must be in 0..{len(Action) - 1}, got {action!r}")
    return int(value)


def batch_actions(who: str, actions: Any, size: int) -> np.ndarray:
    """`actions` as an int64 array of `size` actions in 0..9, or an error naming `who`.

    Integral floats (1.0) pass as the ints they hold; 1.5 is refused rather than truncated.
    """
    array = np.asarray(actions)
    if array.shape != (size,):
        raise ValueError(f"{who} must have shape ({size},), got {array.shape}")
    integral = np.issubdtype(array.dtype, np.integer) or (
        np.issubdtype(array.dtype, np.floating) and bool(np.all(array == np.round(array)))
    )
    if not integral:
        raise TypeError(f"{who} must be ints in 0..{len(Action) - 1}, got {array!r}")
    bad = np.flatnonzero((array < 0) | (array >= len(Action)))
    if bad.size:
        raise ValueError(
            f"{who}[{bad[0]}] = {array[bad[0]].item()!r}: actions must be in 0..{len(Action) - 1}"
        )
    return array.astype(np.int64)


def check_seat(seat: Any, allowed: str = "0 or 1") -> int:
    """A learner's seat, 0 or 1 (a numpy integer too), as a plain int; `allowed` for the message."""
    if isinstance(seat, (bool, np.bool_)) or not isinstance(seat, (int, np.integer)):
        raise TypeError(f"seat must be {allowed}, got {seat!r}")
    if seat not in (0, 1):
        raise ValueError(f"seat must be {allowed}, got {seat!r}")
    return int(seat)
