"""Ego-centric, mirrored observation vectors: what one fighter sees of the fight.

x-axis quantities are multiplied by the fighter's side (+1 for fighter_0, -1 for fighter_1), so
both fighters see the fight as if they started on the left: mirroring the world left-right swaps
the two observations exactly, and one policy can play either seat. Every entry is scaled to about
[-1, 1] and clipped into the space's bounds.
"""

from __future__ import annotations

import numpy as np

from vooga_env.game.fight import SIDES, Fight
from vooga_env.game.hits import Fighter

FIGHTER_FEATURES = (
    "x",  # centre, relative to the arena's centre, / half the arena width (opponent: minus own x)
    "y",  # centre, relative to the arena's centre, / half the arena height (opponent: minus own y)
    "vx",  # px/ms / VELOCITY_SCALE
    "vy",
    "facing",  # +1 facing forward (own frame's right), -1 backward
    "health",  # / max health
    "damage_taken",  # this stock's damage / max health (knockback grows with it)
    "on_ground",
    "jumps_left",  # / air jumps (1 when the config allows none)
    "punching",
    "kicking",
    "blocking",
    "crouching",
    "move_progress",  # frames into the current attack / its length
    "hitbox_active",
    "hitstun",  # frames left / 20
    "stocks",  # / starting stocks
    "punch_reach",  # 1 if a punch started now would touch the other fighter where it stands
    "kick_reach",  # likewise for a kick
)
GLOBAL_FEATURES = (
    "stage_left",  # own centre minus the stage edge on own frame's left, / arena width
    "stage_right",  # the stage edge on own frame's right minus own centre, / arena width
    "time_left",  # steps left / max_cycles
)
OBSERVATION_NAMES = (
    *(f"self_{name}" for name in FIGHTER_FEATURES),
    *(f"opponent_{name}" for name in FIGHTER_FEATURES),
    *GLOBAL_FEATURES,
)
OBSERVATION_SIZE = len(OBSERVATION_NAMES)
VELOCITY_SCALE = 2.0  # px/ms
HITSTUN_SCALE = 20.0  # frames
LOW, HIGH = -2.0, 2.0


def observe(fight: Fight, index: int) -> np.ndarray:
    """The float32 observation of fighter `index` (see OBSERVATION_NAMES for each entry)."""
    reach = (fight.reach(fight.fighters[0]), fight.reach(fight.fighters[1]))
    return _clipped([_values(fight, index, reach)])[0]


def observe_both(fight: Fight) -> np.ndarray:
    """Both fighters' observations as one (2, OBSERVATION_SIZE) float32 array, fighter_0's first."""
    reach = (fight.reach(fight.fighters[0]), fight.reach(fight.fighters[1]))
    return _clipped([_values(fight, 0, reach), _values(fight, 1, reach)])


def _clipped(rows: list[list[float]]) -> np.ndarray:
    array = np.array(rows, dtype=np.float32)
    return np.clip(array, LOW, HIGH, out=array)


def _values(fight: Fight, index: int, reach: tuple[tuple[bool, bool], ...]) -> list[float]:
    me, other = fight.fighters[index], fight.fighters[1 - index]
    side = SIDES[index]
    arena = fight.config.arena
    half_width, half_height = arena.width / 2.0, arena.height / 2.0
    stocks = fight.config.stocks
    own = _fighter(me, side, half_width, half_height, stocks, reach[index])
    opponent = _fighter(other, side, half_width, half_height, stocks, reach[1 - index])
    opponent[0] -= own[0]
    opponent[1] -= own[1]
    centre = me.x + me.width / 2.0
    edges = (centre - fight.stage_left, fight.stage_right - centre)
    if side < 0:
        edges = edges[::-1]
    remaining = 1.0 - fight.steps / fight.config.max_cycles
    own += opponent
    own += (edges[0] / arena.width, edges[1] / arena.width, remaining)
    return own


def _fighter(
    fighter: Fighter,
    side: float,
    half_width: float,
    half_height: float,
    stocks: int,
    reach: tuple[bool, bool],
) -> list[float]:
    config = fighter.config
    move, attack = fighter.move, fighter.attack
    progress = 0.0
    if attack is not None:
        progress = fighter.move_frame / (attack.startup + attack.active + attack.recovery)
    return [
        side * (fighter.x + fighter.width / 2.0 - half_width) / half_width,
        (fighter.y + fighter.height / 2.0 - half_height) / half_height,
        side * fighter.vx / VELOCITY_SCALE,
        fighter.vy / VELOCITY_SCALE,
        side * fighter.facing,
        fighter.health / config.health,
        fighter.damage_taken / config.health,
        float(fighter.on_ground),
        fighter.jumps_left / config.air_jumps if config.air_jumps else 1.0,
        float(move == "punch"),
        float(move == "kick"),
        float(fighter.blocking),
        float(fighter.crouching),
        progress,
        float(fighter.hitbox.active),
        fighter.hitstun / HITSTUN_SCALE,
        fighter.stocks / stocks,
        float(reach[0]),
        float(reach[1]),
    ]
