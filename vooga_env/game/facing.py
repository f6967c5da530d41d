"""The opponent-facing frame: a fighter's observation turned so that its opponent is on its right.

Observations are mirrored by seat (`observations`), so each fighter sees itself start on the left;
once the fighters cross over (a jump over, a random_sides start) the opponent is on its left, a
view a policy trained from the usual sides has hardly seen. Turned into the opponent-facing frame,
a crossed-over fight looks like the world mirrored back, which is the same fight on a symmetric
stage: right means forward and left back, as the inputs of most fighting games do. A policy that
plays in this frame turns each observation with `face_opponent` and turns its action back with
`TURNED_ACTIONS`.
"""

from __future__ import annotations

import numpy as np

from vooga_env.game.actions import Action
from vooga_env.game.observations import OBSERVATION_NAMES

FRAMES = ("seat", "opponent")
"""How a policy sees the fight: as its seat's mirrored observation, or turned to face the other."""

OPPONENT_X = OBSERVATION_NAMES.index("opponent_x")


def _mirror() -> tuple[np.ndarray, np.ndarray]:
    """Each turned entry's source index and sign: x, vx and facing flip, the stage edges swap."""
    index = np.arange(len(OBSERVATION_NAMES))
    sign = np.ones(len(OBSERVATION_NAMES), dtype=np.float32)
    for who in ("self", "opponent"):
        for name in ("x", "vx", "facing"):
            sign[OBSERVATION_NAMES.index(f"{who}_{name}")] = -1.0
    left, right = OBSERVATION_NAMES.index("stage_left"), OBSERVATION_NAMES.index("stage_right")
    index[left], index[right] = right, left
    return index, sign


MIRROR_INDEX, MIRROR_SIGN = _mirror()


def _turned_actions() -> np.ndarray:
    turned = np.arange(len(Action))
    for one, other in ((Action.LEFT, Action.RIGHT), (Action.JUMP_LEFT, Action.JUMP_RIGHT)):
        turned[one], turned[other] = other, one
    return turned


TURNED_ACTIONS = _turned_actions()
"""An action (or logit) index in the turned frame -> the same move in the seat's frame (and back:
left and right swap, so turning twice is no turn)."""


def face_opponent(observations: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Observations (n, 41) in the opponent-facing frame, and which rows were turned (n,).

    A row is turned when its opponent is on its left (a fighter straight above stays as it is).
    """
    turned = observations[:, OPPONENT_X] < 0
    faced = np.where(turned[:, None], observations[:, MIRROR_INDEX] * MIRROR_SIGN, observations)
    return faced, turned
