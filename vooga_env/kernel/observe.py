"""The kernel's `observe` stage: `observations.observe_both` of one fight, float32, clipped.

Each fighter's features are computed once, as fighter_0 sees them; fighter_1 sees the x-axis ones
(x, vx, facing) negated, which is exact in float64, in the float32 rounding and in the symmetric
clip. The relative x and y and the stage edges are computed per observer. Slots are named
(`layout.OBS_*`, from OBSERVATION_NAMES), the reach test is the fight's own formula.
"""

from __future__ import annotations

import numba
import numpy as np

from vooga_env.game.observations import HIGH, HITSTUN_SCALE, LOW, VELOCITY_SCALE
from vooga_env.kernel.layout import (
    KICK,
    OBS_BLOCKING,
    OBS_CROUCHING,
    OBS_DAMAGE_TAKEN,
    OBS_FACING,
    OBS_HEALTH,
    OBS_HITBOX_ACTIVE,
    OBS_HITSTUN,
    OBS_JUMPS_LEFT,
    OBS_KICK_REACH,
    OBS_KICKING,
    OBS_MOVE_PROGRESS,
    OBS_ON_GROUND,
    OBS_PUNCH_REACH,
    OBS_PUNCHING,
    OBS_STAGE_LEFT,
    OBS_STAGE_RIGHT,
    OBS_STOCKS,
    OBS_TIME_LEFT,
    OBS_VX,
    OBS_VY,
    OBS_X,
    OBS_Y,
    OPPONENT,
    PUNCH,
    S_BLOCKING,
    S_CROUCHING,
    S_FACING,
    S_HEALTH,
    S_HEIGHT,
    S_HIT_ACTIVE,
    S_HITSTUN,
    S_JUMPS_LEFT,
    S_MOVE,
    S_MOVE_FRAME,
    S_ON_GROUND,
    S_STEPS,
    S_STOCKS,
    S_VX,
    S_VY,
    S_X,
    S_Y,
)
from vooga_env.kernel.parts import F, _stack, _unmanaged, inline, stage


@inline
def _clip32(value):
    """np.clip(np.float32(value), LOW, HIGH), as observations.observe does."""
    clipped = np.float32(value)
    if clipped < LOW:
        clipped = np.float32(LOW)
    elif clipped > HIGH:
        clipped = np.float32(HIGH)
    return clipped


@inline
def _flag(value):
    return np.float32(1.0 if value else 0.0)


@inline
def _feature(out, i, f, k, value, sided):
    """Fighter f's feature k (float32, as fighter_0 sees it) into out[i, f, k] (its own) and
    out[i, 1 - f, OPPONENT + k] (its opponent's); fighter_1 sees the sided ones negated."""
    if sided:
        out[i, f, k] = -value if f == 1 else value
        out[i, 1 - f, OPPONENT + k] = -value if f == 0 else value
    else:
        out[i, f, k] = value
        out[i, 1 - f, OPPONENT + k] = value


@inline
def reach(p, s, i, f, m):
    """Fight.reach: would attack m, started now towards the opponent, touch it where it stands?"""
    fl, o, width = s.fl, 1 - f, p.f_width
    toward = (fl[S_X, o, i] + width / 2) - (fl[S_X, f, i] + width / 2)
    direction = fl[S_FACING, f, i] if toward == 0.0 else (1.0 if toward > 0.0 else -1.0)
    left, top = fl[S_X, o, i], fl[S_Y, o, i]
    right, bottom = left + width, top + fl[S_HEIGHT, o, i]
    hx = F.hitbox_x(fl[S_X, f, i], fl[S_X, f, i] + width, direction, p.hitbox_w[m])
    hy = F.hitbox_y(fl[S_Y, f, i] + fl[S_HEIGHT, f, i], p.f_height, p.hitbox_offset_y[m])
    return F.reaches(left, top, right, bottom, hx, hy, p.hitbox_w[m], p.hitbox_h[m])


@stage
def fighter_features(p, s, out, i, f, position):
    """Fighter f's features (`FIGHTER_FEATURES`), into its own slots and its opponent's."""
    fl, it, fg = s.fl, s.it, s.fg
    m = it[S_MOVE, f, i]
    health = fl[S_HEALTH, f, i]
    _feature(out, i, f, OBS_X, _clip32(position[f, 0]), True)
    _feature(out, i, f, OBS_Y, _clip32(position[f, 1]), False)
    _feature(out, i, f, OBS_VX, _clip32(1.0 * fl[S_VX, f, i] / VELOCITY_SCALE), True)
    _feature(out, i, f, OBS_VY, _clip32(fl[S_VY, f, i] / VELOCITY_SCALE), False)
    _feature(out, i, f, OBS_FACING, _clip32(1.0 * fl[S_FACING, f, i]), True)
    _feature(out, i, f, OBS_HEALTH, _clip32(health / p.health), False)
    _feature(out, i, f, OBS_DAMAGE_TAKEN, _clip32((p.health - health) / p.health), False)
    _feature(out, i, f, OBS_ON_GROUND, _flag(fg[S_ON_GROUND, f, i]), False)
    air = p.air_jumps
    jumps = _clip32(it[S_JUMPS_LEFT, f, i] / air if air else 1.0)
    _feature(out, i, f, OBS_JUMPS_LEFT, jumps, False)
    _feature(out, i, f, OBS_PUNCHING, _flag(m == PUNCH), False)
    _feature(out, i, f, OBS_KICKING, _flag(m == KICK), False)
    _feature(out, i, f, OBS_BLOCKING, _flag(fg[S_BLOCKING, f, i]), False)
    _feature(out, i, f, OBS_CROUCHING, _flag(fg[S_CROUCHING, f, i]), False)
    progress = _clip32(it[S_MOVE_FRAME, f, i] / p.total[m] if m != 0 else 0.0)
    _feature(out, i, f, OBS_MOVE_PROGRESS, progress, False)
    _feature(out, i, f, OBS_HITBOX_ACTIVE, _flag(fg[S_HIT_ACTIVE, f, i]), False)
    _feature(out, i, f, OBS_HITSTUN, _clip32(it[S_HITSTUN, f, i] / HITSTUN_SCALE), False)
    _feature(out, i, f, OBS_STOCKS, _clip32(it[S_STOCKS, f, i] / p.stocks), False)
    _feature(out, i, f, OBS_PUNCH_REACH, _flag(reach(p, s, i, f, PUNCH)), False)
    _feature(out, i, f, OBS_KICK_REACH, _flag(reach(p, s, i, f, KICK)), False)


@stage
def observe(p, s, out, i, position):
    """Both fighters' observations of fight i into out[i]; `position` (2, 2): scratch."""
    fl, width = s.fl, p.f_width
    half_width, half_height = p.width / 2.0, p.height / 2.0
    for f in range(2):  # (x, y) in float64, as fighter_0 sees them
        position[f, 0] = 1.0 * (fl[S_X, f, i] + width / 2.0 - half_width) / half_width
        position[f, 1] = (fl[S_Y, f, i] + fl[S_HEIGHT, f, i] / 2.0 - half_height) / half_height
    for f in range(2):
        fighter_features(p, s, out, i, f, position)
    remaining = _clip32(1.0 - s.ct[S_STEPS, i] / p.max_cycles)
    for me in range(2):
        side = 1.0 if me == 0 else -1.0
        other = 1 - me
        own_x, own_y = side * position[me, 0], position[me, 1]
        out[i, me, OPPONENT + OBS_X] = _clip32(side * position[other, 0] - own_x)
        out[i, me, OPPONENT + OBS_Y] = _clip32(position[other, 1] - own_y)
        centre = fl[S_X, me, i] + width / 2.0
        first, second = centre - p.stage_left, p.stage_right - centre
        if side < 0:
            first, second = second, first
        out[i, me, OBS_STAGE_LEFT] = _clip32(first / p.width)
        out[i, me, OBS_STAGE_RIGHT] = _clip32(second / p.width)
        out[i, me, OBS_TIME_LEFT] = remaining


@inline
def _observe(p, s, index, out):
    """`observe` of the fights `index`, into out[i] ((N, 2, 41) float32); records: parts."""
    out = _unmanaged(out)
    position = numba.carray(_stack(4, np.float64), (2, 2))
    for i in index:
        observe(p, s, out, i, position)
