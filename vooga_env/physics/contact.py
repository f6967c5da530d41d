"""Contact detection: a swept box test between two sprites' moves this frame.

Detection only; what a contact does is up to the reactions (`reactions.py`).
"""

from __future__ import annotations

from dataclasses import dataclass

from vooga_env.physics import formulas
from vooga_env.physics.formulas import OVERLAP_EPSILON
from vooga_env.physics.sprites import SpriteTemplate

__all__ = ["OVERLAP_EPSILON", "Contact", "find_contact"]

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
    from the older sprite to the newer if neither tells. The test itself is `formulas.contact`.
    """
    found, axis, normal, time_of_impact, depth = formulas.contact(
        one.left,
        one.right,
        one.top,
        one.bottom,
        two.left,
        two.right,
        two.top,
        two.bottom,
        one.increment_x - two.increment_x,
        one.increment_y - two.increment_y,
        one.serial < two.serial,
    )
    if not found:
        return None
    return Contact(one, two, axis, normal, time_of_impact, depth, elapsed_time)
