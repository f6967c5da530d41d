"""The fight's float formulas, written once: `Fight`, the hit reaction and the reward call them, the
compiled kernel compiles them (as it does `vooga_env.physics.formulas`, the engine's), so the
arithmetic of both backends is the same by construction.

Plain Python over floats (px, px/ms, health points) and the physics formulas: no objects, no
numpy, no numba; a formula calls only formulas and returns one type from every branch.
"""

from __future__ import annotations

from vooga_env.physics.formulas import py_min


def hitbox_x(left: float, right: float, facing: float, hitbox_width: float) -> float:
    """The hitbox's left edge: out of the attacker's front edge (`facing` +1 right, -1 left)."""
    return right if facing > 0 else left - hitbox_width


def hitbox_y(bottom: float, standing_height: float, offset_y: float) -> float:
    """The hitbox's top, placed from the feet: a crouched attack hits where a standing one would."""
    return bottom - standing_height + offset_y


def reaches(
    left: float, top: float, right: float, bottom: float, x: float, y: float, w: float, h: float
) -> bool:
    """Does a hitbox (x, y, w, h) overlap the fighter's box (left, top, right, bottom)? (reach)"""
    return x < right and left < x + w and y < bottom and top < y + h


def under(block_x: float, block_width: float, x: float, width: float) -> bool:
    """Is the block under a fighter whose left edge is at `x` (its spawn block's candidates)?"""
    return block_x < x + width and x < block_x + block_width


def hit_damage(damage: float, blocked: bool, block_damage: float) -> float:
    """The health points a hit takes: a block cuts them by the defender's `block_damage`."""
    return damage * (block_damage if blocked else 1.0)


def knockback(
    base: float, growth: float, damage_taken: float, damage: float, blocked: bool, block: float
) -> float:
    """The launch speed (px/ms): base + growth * (damage so far + this hit's), cut by a block."""
    power = base + growth * (damage_taken + damage)
    power *= block if blocked else 1.0
    return power


def time_out(terminated: bool, steps: int, max_cycles: int) -> bool:
    """The time limit: a fight that did not end is truncated once it has run `max_cycles` steps."""
    return not terminated and steps >= max_cycles


def edge_room(centre: float, stage_left: float, stage_right: float) -> float:
    """A fighter's room (px) from its centre to the nearer stage edge."""
    return py_min(centre - stage_left, stage_right - centre)


def edge_advantage(room_0: float, room_1: float, stage_left: float, stage_right: float) -> float:
    """fighter_0's room to its nearer edge minus fighter_1's, over the stage width (the reward's
    edge potential)."""
    return (room_0 - room_1) / (stage_right - stage_left)
