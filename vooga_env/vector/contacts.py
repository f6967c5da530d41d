"""Contact detection for N pairs at once: the broad phase's test and `physics.find_contact`.

Each function mirrors its scalar original operation for operation (the same float expressions in
the same order), so a contact's axis, normal, time of impact and depth are bit for bit the single
engine's. `py_max`/`py_min` are Python's `max`/`min` on two floats (the first wins ties, which
decides the sign of a zero), unlike `np.maximum`.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from vooga_env.physics.contact import OVERLAP_EPSILON


def py_max(first: np.ndarray | float, second: np.ndarray | float) -> np.ndarray:
    """Python's `max(first, second)` for floats, element-wise."""
    return np.where(second > first, second, first)


def py_min(first: np.ndarray | float, second: np.ndarray | float) -> np.ndarray:
    """Python's `min(first, second)` for floats, element-wise."""
    return np.where(second < first, second, first)


@dataclass
class Box:
    """A sprite's box and pending increment this frame (arrays, or floats for a static block)."""

    x: np.ndarray | float
    y: np.ndarray | float
    width: np.ndarray | float
    height: np.ndarray | float
    increment_x: np.ndarray | float = 0.0
    increment_y: np.ndarray | float = 0.0

    @property
    def right(self) -> np.ndarray | float:
        return self.x + self.width

    @property
    def bottom(self) -> np.ndarray | float:
        return self.y + self.height


@dataclass
class Contacts:
    """One pair's contact in every fight, seen from the first sprite (`found` False: none)."""

    found: np.ndarray  # (N,) bool
    vertical: np.ndarray  # (N,) bool: axis 1 (y), else axis 0 (x)
    normal: np.ndarray  # (N,) +1.0 or -1.0, from the first sprite towards the second
    time_of_impact: np.ndarray
    depth: np.ndarray


def swept_overlap(one: Box, two: Box) -> np.ndarray:
    """The sort-and-sweep broad phase's verdict: do the boxes swept along x touch (inclusive)?"""
    low_one = np.where(one.increment_x < 0.0, one.x + one.increment_x, one.x)
    low_two = np.where(two.increment_x < 0.0, two.x + two.increment_x, two.x)
    right_one, right_two = one.right, two.right
    high_one = np.where(one.increment_x > 0.0, right_one + one.increment_x, right_one)
    high_two = np.where(two.increment_x > 0.0, right_two + two.increment_x, right_two)
    return (low_two <= high_one) & (low_one <= high_two)


def find_contacts(one: Box, two: Box, candidate: np.ndarray) -> Contacts:
    """`find_contact(one, two)` where `candidate` holds, in every fight; `one` is the older."""
    move_x = one.increment_x - two.increment_x
    move_y = one.increment_y - two.increment_y
    left_one, right_one, top_one, bottom_one = one.x, one.right, one.y, one.bottom
    left_two, right_two, top_two, bottom_two = two.x, two.right, two.y, two.bottom
    entry_x, exit_x = _window(left_one, right_one, left_two, right_two, move_x)
    entry_y, exit_y = _window(top_one, bottom_one, top_two, bottom_two, move_y)
    entry = py_max(entry_x, entry_y)
    leave = py_min(exit_x, exit_y)
    found = candidate & ~((entry >= leave) | (entry > 1.0) | (leave <= 0.0))
    overlapping = entry < 0.0
    # boxes that already overlap: the axis of least penetration, ties to the faster motion
    depth_x = py_min(right_one, right_two) - py_max(left_one, left_two)
    depth_y = py_min(bottom_one, bottom_two) - py_max(top_one, top_two)
    vertical_overlap = np.where(
        depth_x != depth_y, ~(depth_x < depth_y), ~(np.abs(move_x) > np.abs(move_y))
    )
    gap = np.where(
        vertical_overlap,
        (top_two + bottom_two) - (top_one + bottom_one),
        (left_two + right_two) - (left_one + right_one),
    )
    toward = np.where(gap != 0.0, gap, np.where(vertical_overlap, move_y, move_x))
    # centres together, no motion: the older sprite (always `one` here) is the one behind
    toward = np.where(toward == 0.0, 1.0, toward)
    # boxes that meet during the frame: the axis crossed last
    vertical_swept = ~(entry_x > entry_y)
    swept_normal = np.where(np.where(vertical_swept, move_y, move_x) > 0.0, 1.0, -1.0)
    return Contacts(
        found=found,
        vertical=np.where(overlapping, vertical_overlap, vertical_swept),
        normal=np.where(overlapping, np.where(toward >= 0.0, 1.0, -1.0), swept_normal),
        # 0.0 where no contact, so that masked arithmetic on them stays finite
        time_of_impact=np.where(found & ~overlapping, py_max(entry, 0.0) + 0.0, 0.0),
        depth=np.where(found & overlapping, np.where(vertical_overlap, depth_y, depth_x), 0.0),
    )


def _window(low_one, high_one, low_two, high_two, move):
    """`contact._window` element-wise: the frame fractions (entry, exit) of overlap."""
    with np.errstate(divide="ignore", invalid="ignore"):
        ahead = (low_two - high_one) / move
        behind = (high_two - low_one) / move
    still = (high_one - low_two > OVERLAP_EPSILON) & (high_two - low_one > OVERLAP_EPSILON)
    positive, negative = move > 0.0, move < 0.0
    entry = np.where(positive, ahead, np.where(negative, behind, np.where(still, -np.inf, np.inf)))
    leave = np.where(positive, behind, np.where(negative, ahead, np.where(still, np.inf, -np.inf)))
    return entry, leave
