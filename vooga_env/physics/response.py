"""`PendingResponse`: what reactions ask of one sprite this frame, combined without regard to order.

Reactions never move a sprite; they add displacement shifts and velocity changes (summed with
`math.fsum`, which is exact and so independent of the order of terms) and bound the final position
and velocity per axis (intervals intersected, also order-free). The sprite's update applies the
result once. This is the seed's "soft" setting, made safe for several contacts in one frame.
"""

from __future__ import annotations

import math

from vooga_env.physics.formulas import friction, within

AXES = (0, 1)  # 0 = x (right), 1 = y (down)


class PendingResponse:
    """Accumulated reaction results for one sprite and one frame; see the module docstring."""

    __slots__ = ("shifts", "velocity_changes", "position_bounds", "velocity_bounds", "friction")

    def __init__(self) -> None:
        self.shifts: tuple[list[float], list[float]] = ([], [])
        self.velocity_changes: tuple[list[float], list[float]] = ([], [])
        self.position_bounds = [[-math.inf, math.inf], [-math.inf, math.inf]]
        self.velocity_bounds = [[-math.inf, math.inf], [-math.inf, math.inf]]
        self.friction = [(0.0, 0.0, 0.0), (0.0, 0.0, 0.0)]

    def reset(self) -> None:
        """Forget this frame's requests."""
        for axis in AXES:
            self.shifts[axis].clear()
            self.velocity_changes[axis].clear()
            self.position_bounds[axis][:] = (-math.inf, math.inf)
            self.velocity_bounds[axis][:] = (-math.inf, math.inf)
            self.friction[axis] = (0.0, 0.0, 0.0)

    def shift(self, axis: int, pixels: float) -> None:
        """Move the sprite `pixels` further along `axis` this frame, on top of its increment."""
        if pixels != 0.0:
            self.shifts[axis].append(pixels)

    def change_velocity(self, axis: int, delta: float) -> None:
        """Change the sprite's persistent velocity along `axis` by `delta` px/ms."""
        if delta != 0.0:
            self.velocity_changes[axis].append(delta)

    def bound_position(self, axis: int, low: float = -math.inf, high: float = math.inf) -> None:
        """Keep the sprite's final coordinate (left or top edge, px) inside [low, high]."""
        bounds = self.position_bounds[axis]
        bounds[0] = max(bounds[0], low)
        bounds[1] = min(bounds[1], high)

    def bound_velocity(self, axis: int, low: float = -math.inf, high: float = math.inf) -> None:
        """Keep the sprite's final velocity along `axis` (px/ms) inside [low, high]."""
        bounds = self.velocity_bounds[axis]
        bounds[0] = max(bounds[0], low)
        bounds[1] = min(bounds[1], high)

    def slow_down(self, axis: int, amount: float, reference: float, carry: float) -> None:
        """Bring the velocity along `axis` up to `amount` px/ms closer to `reference`, once.

        `carry` (ms) is how far a change of 1 px/ms moves the sprite in the rest of the frame.
        Friction from several surfaces at once counts once (the strongest), so a sprite standing
        across two blocks is not slowed twice and never overshoots into reverse.
        """
        self.friction[axis] = max(self.friction[axis], (amount, -reference, carry))

    def resolve(
        self, axis: int, position: float, increment: float, velocity: float
    ) -> tuple[float, float]:
        """The final (coordinate, velocity) along `axis` given this frame's start and increment."""
        # fsum of one term is the term itself and of two their float sum, save that fsum never
        # returns -0.0 (adding 0.0 turns -0.0 into 0.0 and leaves every other value alone)
        changes, shifts = self.velocity_changes[axis], self.shifts[axis]
        new_velocity = math.fsum([velocity, *changes]) if changes else velocity + 0.0
        amount, reference, carry = self.friction[axis]
        slide = 0.0
        if amount > 0.0:
            slowed = friction(new_velocity, amount, reference)
            slide = (slowed - new_velocity) * carry
            new_velocity = slowed
        if shifts or slide != 0.0:
            new_position = math.fsum([position, increment, slide, *shifts])
        else:
            new_position = position + increment + 0.0
        new_position = within(new_position, *self.position_bounds[axis])
        return new_position, within(new_velocity, *self.velocity_bounds[axis])
