"""The sprites the engine moves: `SpriteTemplate`, `FighterBody` and `PlatformBlock`.

Coordinates are screen pixels (x right, y down) of the sprite's top-left corner; velocities are
px/ms. A sprite's pending `increment_x/increment_y` (px) is this frame's soft next location
increment: engine calls add to it, reactions add to its `response`, and `update()` applies one of
the two once (the seed's CollisionStatus rule).
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Hashable

from vooga_env.physics import validation
from vooga_env.physics.response import PendingResponse
from vooga_env.physics.status import CollisionStatus
from vooga_env.physics.validation import Checked

# Creation order, the tie-break for two boxes whose centres coincide (contact.py): unlike the
# order of teams, it does not change when a scene lists its sprites differently.
_SERIALS = itertools.count()


class SpriteTemplate:
    """A box that moves: position, size, mass, speed, a persistent velocity and its contact status.

    `mass` may be `math.inf`: such a sprite is never moved by a reaction (`movable` is False).
    `speed` (px/ms) scales the MotionActions given to the sprite; `gravity_scale` multiplies the
    engine's gravity for it (0 for sprites that float, such as attack hitboxes). `serial` is the
    sprite's creation order.
    """

    x = Checked(validation.finite)
    y = Checked(validation.finite)
    vx = Checked(validation.finite)
    vy = Checked(validation.finite)
    width = Checked(validation.positive)
    height = Checked(validation.positive)
    mass = Checked(validation.mass)
    speed = Checked(validation.non_negative)
    gravity_scale = Checked(validation.finite)
    increment_x = Checked(validation.finite)
    increment_y = Checked(validation.finite)

    def __init__(
        self,
        x: float,
        y: float,
        width: float,
        height: float,
        *,
        mass: float = 200.0,
        speed: float = 0.3,
        vx: float = 0.0,
        vy: float = 0.0,
        gravity_scale: float = 1.0,
        name: str = "",
    ) -> None:
        self.x = x
        self.y = y
        self.width = width
        self.height = height
        self.mass = mass
        self.speed = speed
        self.vx = vx
        self.vy = vy
        self.gravity_scale = gravity_scale
        self.name = name
        self.active = True
        self.status = CollisionStatus()
        self.response = PendingResponse()
        self.increment_x = 0.0
        self.increment_y = 0.0
        self.serial = next(_SERIALS)

    @property
    def left(self) -> float:
        return self.x

    @property
    def right(self) -> float:
        return self.x + self.width

    @property
    def top(self) -> float:
        return self.y

    @property
    def bottom(self) -> float:
        return self.y + self.height

    @property
    def movable(self) -> bool:
        """False for infinite mass: reactions leave such a sprite alone."""
        return self.mass != math.inf

    def update(self) -> None:
        """Apply this frame's result once: the reactions' if the sprite collided, else its move.

        Then clear the increment, the reactions' requests and the collision status for next frame.
        """
        # written past the `Checked` descriptors: the engine's own results, from checked values
        state = self.__dict__
        if self.status.collided:
            state["x"], state["vx"] = self.response.resolve(0, self.x, self.increment_x, self.vx)
            state["y"], state["vy"] = self.response.resolve(1, self.y, self.increment_y, self.vy)
            self.response.reset()
        else:
            state["x"] = self.x + self.increment_x
            state["y"] = self.y + self.increment_y
        state["increment_x"] = state["increment_y"] = 0.0
        self.status.reset()

    def __repr__(self) -> str:
        label = f"{self.name!r}, " if self.name else ""
        return (
            f"{type(self).__name__}({label}x={self.x:.2f}, y={self.y:.2f}, "
            f"w={self.width:g}, h={self.height:g}, vx={self.vx:.3f}, vy={self.vy:.3f})"
        )


class FighterBody(SpriteTemplate):
    """A fighter: a sprite with a team `group_id` (who is friend or enemy) and `health`."""

    health = Checked(validation.finite)

    def __init__(
        self,
        x: float,
        y: float,
        width: float,
        height: float,
        *,
        group_id: Hashable,
        mass: float = 200.0,
        speed: float = 0.3,
        health: float = 100.0,
        **kwargs: float | str,
    ) -> None:
        super().__init__(x, y, width, height, mass=mass, speed=speed, **kwargs)  # type: ignore[arg-type]
        if group_id is None or not isinstance(group_id, Hashable):
            raise TypeError(f"group_id must be a hashable team id, got {group_id!r}")
        self.group_id = group_id
        self.health = health


class PlatformBlock(SpriteTemplate):
    """A block of the stage: infinite mass and no gravity, so nothing it touches can move it."""

    def __init__(self, x: float, y: float, width: float, height: float, *, name: str = "") -> None:
        super().__init__(
            x, y, width, height, mass=math.inf, speed=0.0, gravity_scale=0.0, name=name
        )
