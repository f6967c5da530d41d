"""Contact detection: a swept box test between two sprites' moves this frame.

Detection only; what a contact does is up to the reactions (`reactions.py`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from vooga_env.physics.sprites import SpriteTemplate

# Overlaps thinner than this (px) are float noise, not contact: sprites resting side by side must
# not catch on each other because a coordinate was rounded.
OVERLAP_EPSILON = 1e-9

_EDGES = {(0, 1.0): "right", (0, -1.0): "left", (1, 1.0): "down", (1, -1.0): "up"}


@dataclass(frozen=True, slots=True)
class Contact:
    """One pair's contact this frame, seen from `sprite`.

    `axis` is 0 (x) or 1 (y); `normal` is +1.0 or -1.0, the direction from `sprite` towards
    `other` along that axis. `time_of_impact` is the fraction of the frame (0..1) at which the
    boxes met, 0 if they already overlapped, in which case `depth` (px) is that overlap along the
    axis. `elapsed_time` is the frame's length (ms).
    """

    sprite: SpriteTemplate
    other: SpriteTemplate
    axis: int
    normal: float
    time_of_impact: float
    depth: float
    elapsed_time: float

    @property
    def edge(self) -> str:
        """The edge of `sprite` that touched: 'left', 'right', 'up' or 'down'."""
        return _EDGES[(self.axis, self.normal)]

    def flipped(self) -> Contact:
        """The same contact seen from `other`."""
        return Contact(
            self.other,
            self.sprite,
            self.axis,
            -self.normal,
            self.time_of_impact,
            self.depth,
            self.elapsed_time,
        )


def find_contact(one: SpriteTemplate, two: SpriteTemplate, elapsed_time: float) -> Contact | None:
    """The contact of `one` with `two` during this frame's pending increments, or None.

    Swept, so a fast sprite cannot pass through a thin one. The axis is the one along which the
    boxes came to overlap last (the face that was crossed); for boxes that already overlap, the axis
    of least penetration, ties going to the axis of faster relative motion; the normal points
    from `one`'s centre to `two`'s, or along their relative motion if the centres coincide, or
    from the older sprite to the newer if neither tells.
    """
    move_x = one.increment_x - two.increment_x
    move_y = one.increment_y - two.increment_y
    entry_x, exit_x = _window(one.left, one.right, two.left, two.right, move_x)
    entry_y, exit_y = _window(one.top, one.bottom, two.top, two.bottom, move_y)
    entry = max(entry_x, entry_y)
    leave = min(exit_x, exit_y)
    if entry >= leave or entry > 1.0 or leave <= 0.0:
        return None
    if entry < 0.0:
        depth_x = min(one.right, two.right) - max(one.left, two.left)
        depth_y = min(one.bottom, two.bottom) - max(one.top, two.top)
        if depth_x != depth_y:
            axis = 0 if depth_x < depth_y else 1
        else:
            axis = 0 if abs(move_x) > abs(move_y) else 1
        depth = (depth_x, depth_y)[axis]
        centre_gap = (
            (two.left + two.right) - (one.left + one.right),
            (two.top + two.bottom) - (one.top + one.bottom),
        )[axis]
        toward = centre_gap if centre_gap != 0.0 else (move_x, move_y)[axis]
        if toward == 0.0:  # centres coincide, no motion: the older sprite is the one behind
            toward = 1.0 if one.serial < two.serial else -1.0
        return Contact(one, two, axis, 1.0 if toward >= 0.0 else -1.0, 0.0, depth, elapsed_time)
    axis = 0 if entry_x > entry_y else 1
    normal = 1.0 if (move_x, move_y)[axis] > 0.0 else -1.0
    return Contact(one, two, axis, normal, max(entry, 0.0) + 0.0, 0.0, elapsed_time)


def _window(
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
