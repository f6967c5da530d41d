"""The engine's float formulas, written once: the physics engine calls them, the compiled kernel
compiles them (`vooga_env.kernel.parts.compiled`), so both do the same arithmetic by
construction and only the bookkeeping around them is written twice.

Plain Python over floats (px, ms, px/ms) and `math`: no objects, no numpy, no numba. A formula
calls only other formulas of this module (the kernel compiles those too) and returns one type
from every branch.
"""

from __future__ import annotations

import math

# Overlaps thinner than this (px) are float noise, not contact: sprites resting side by side must
# not catch on each other because a coordinate was rounded.
OVERLAP_EPSILON = 1e-9


def py_max(first: float, second: float) -> float:
    """`max(first, second)` as Python computes it: `first` unless `second` is larger."""
    return second if second > first else first


def py_min(first: float, second: float) -> float:
    """`min(first, second)` as Python computes it: `first` unless `second` is smaller."""
    return second if second < first else first


def within(value: float, low: float, high: float) -> float:
    """Clamp into [low, high]; contradicting bounds (a sprite squeezed both ways) meet halfway."""
    if low > high:
        return 0.5 * (low + high)
    return py_min(py_max(value, low), high)


def swept_interval(low: float, high: float, move: float) -> tuple[float, float]:
    """The interval [low, high] sweeps while moving `move` px: the broad phase's box along x."""
    return (low + move if move < 0.0 else low), (high + move if move > 0.0 else high)


def window(
    low_one: float, high_one: float, low_two: float, high_two: float, move: float
) -> tuple[float, float]:
    """The frame fractions (entry, exit) during which two intervals overlap, `one` moving `move`."""
    if move > 0.0:
        return (low_two - high_one) / move, (high_two - low_one) / move
    if move < 0.0:
        return (high_two - low_one) / move, (low_two - high_one) / move
    if high_one - low_two > OVERLAP_EPSILON and high_two - low_one > OVERLAP_EPSILON:
        return -math.inf, math.inf
    return math.inf, -math.inf


def contact(
    left_one: float,
    right_one: float,
    top_one: float,
    bottom_one: float,
    left_two: float,
    right_two: float,
    top_two: float,
    bottom_two: float,
    move_x: float,
    move_y: float,
    one_is_older: bool,
) -> tuple[bool, int, float, float, float]:
    """The swept contact test of box one moving (move_x, move_y) px relative to box two.

    (found, axis, normal, time_of_impact, depth); see `contact.find_contact` for the rules.
    """
    entry_x, exit_x = window(left_one, right_one, left_two, right_two, move_x)
    entry_y, exit_y = window(top_one, bottom_one, top_two, bottom_two, move_y)
    entry = py_max(entry_x, entry_y)
    leave = py_min(exit_x, exit_y)
    if entry >= leave or entry > 1.0 or leave <= 0.0:
        return False, 0, 0.0, 0.0, 0.0
    if entry < 0.0:
        depth_x = py_min(right_one, right_two) - py_max(left_one, left_two)
        depth_y = py_min(bottom_one, bottom_two) - py_max(top_one, top_two)
        if depth_x != depth_y:
            axis = 0 if depth_x < depth_y else 1
        else:
            axis = 0 if abs(move_x) > abs(move_y) else 1
        if axis == 0:
            depth, gap, move = depth_x, (left_two + right_two) - (left_one + right_one), move_x
        else:
            depth, gap, move = depth_y, (top_two + bottom_two) - (top_one + bottom_one), move_y
        toward = gap if gap != 0.0 else move
        if toward == 0.0:  # centres coincide, no motion: the older sprite is the one behind
            toward = 1.0 if one_is_older else -1.0
        return True, axis, 1.0 if toward >= 0.0 else -1.0, 0.0, depth
    axis = 0 if entry_x > entry_y else 1
    move = move_x if axis == 0 else move_y
    return True, axis, 1.0 if move > 0.0 else -1.0, py_max(entry, 0.0) + 0.0, 0.0


def displacement(velocity: float, elapsed_time: float, background_factor: float) -> float:
    """How far (px) `velocity` (px/ms) carries a sprite in `elapsed_time` ms (the fight engine)."""
    return velocity * elapsed_time * background_factor


def shares(mass_one: float, mass_two: float) -> tuple[float, float]:
    """How a separation splits between two sprites: inversely to mass, none for an immovable one."""
    if mass_one == math.inf:
        return (0.0, 1.0) if mass_two != math.inf else (0.0, 0.0)
    if mass_two == math.inf:
        return 1.0, 0.0
    total = mass_one + mass_two
    return mass_two / total, mass_one / total


def common(mass_one: float, value_one: float, mass_two: float, value_two: float) -> float:
    """The mass-weighted mean of two values (the push's common motion); an immovable one wins."""
    if mass_one == math.inf:
        return value_one
    if mass_two == math.inf:
        return value_two
    return (mass_one * value_one + mass_two * value_two) / (mass_one + mass_two)


def elastic(mass_one: float, mass_two: float, one: float, two: float) -> tuple[float, float]:
    """The seed's 1-D elastic collision for both sprites; an immovable sprite reflects the other."""
    if mass_one == math.inf and mass_two == math.inf:
        return one, two
    if mass_two == math.inf:
        return 2.0 * two - one, two
    if mass_one == math.inf:
        return one, 2.0 * one - two
    total = mass_one + mass_two
    return (
        (mass_one - mass_two) / total * one + 2.0 * mass_two / total * two,
        (mass_two - mass_one) / total * two + 2.0 * mass_one / total * one,
    )


def redirect_shift(time_of_impact: float, after: float, before: float) -> float:
    """The shift (px) of a sprite whose increment becomes `after` at the time of impact."""
    return (1.0 - time_of_impact) * (after - before)


def rebound_surface(block_start: float, block_size: float, own_size: float, normal: float) -> float:
    """Where a sprite's coordinate stops against a block face (`normal`: towards the block)."""
    return block_start - own_size if normal > 0.0 else block_start + block_size


def friction(velocity: float, amount: float, reference: float) -> float:
    """`velocity` up to `amount` px/ms closer to the surface's (`-reference`), not past it."""
    sliding = velocity + reference
    return -reference + math.copysign(py_max(abs(sliding) - amount, 0.0), sliding)
