"""`PhysicsEngine` (the seed's abstract engine) and `FightPhysicsEngine`, its fighting-game one."""

from __future__ import annotations

from abc import ABC, abstractmethod

from vooga_env.physics import formulas, validation
from vooga_env.physics.motion import MotionAction
from vooga_env.physics.sprites import SpriteTemplate
from vooga_env.physics.validation import Checked


class PhysicsEngine(ABC):
    """Turns inputs into pending increments and keeps sprites inside the arena.

    The arena spans x in [0, width] and y in [0, height] px (y grows downwards). Subclasses say how
    a MotionAction becomes an increment (`process`), how an increment is stored
    (`set_next_location_increment`), and how far a velocity carries a sprite (`displacement`).
    """

    width = Checked(validation.positive)
    height = Checked(validation.positive)

    def __init__(self, width: float, height: float) -> None:
        self.width = width
        self.height = height

    bound_left = property(lambda self: 0.0, doc="The arena's left bound (px).")
    bound_up = property(lambda self: 0.0, doc="The arena's top bound (px).")
    bound_right = property(lambda self: self.width, doc="The arena's right bound (px).")
    bound_down = property(lambda self: self.height, doc="The arena's bottom bound (px).")

    @abstractmethod
    def process(self, motion_action: MotionAction, elapsed_time: float) -> None:
        """Turn `motion_action` into its sprite's pending increment for `elapsed_time` ms."""

    @abstractmethod
    def set_next_location_increment(self, sprite: SpriteTemplate, dx: float, dy: float) -> None:
        """Soft-set: add (dx, dy) px to what `sprite` will move this frame if nothing collides."""

    @abstractmethod
    def displacement(self, velocity: float, elapsed_time: float) -> float:
        """How far (px) `velocity` (px/ms) carries a sprite in `elapsed_time` ms in this engine."""

    def integrate(self, sprite: SpriteTemplate, elapsed_time: float) -> None:
        """Start a frame: the sprite's velocity becomes part of its pending increment."""
        self.set_next_location_increment(sprite, sprite.vx * elapsed_time, sprite.vy * elapsed_time)

    def keep_in_bounds(self, sprite: SpriteTemplate) -> None:  # noqa: B027 - a no-op by default
        """End a frame: put a sprite that left the arena back inside (the engine's rule)."""

    def is_out_left(self, sprite: SpriteTemplate, dx: float = 0.0) -> bool:
        """True if moving `dx` would put the sprite's left edge past the left bound."""
        return sprite.x + dx < self.bound_left

    def is_out_right(self, sprite: SpriteTemplate, dx: float = 0.0) -> bool:
        """True if moving `dx` would put the sprite's right edge past the right bound."""
        return sprite.x + dx + sprite.width > self.bound_right

    def is_out_up(self, sprite: SpriteTemplate, dy: float = 0.0) -> bool:
        """True if moving `dy` would put the sprite's top edge above the top bound."""
        return sprite.y + dy < self.bound_up

    def is_out_down(self, sprite: SpriteTemplate, dy: float = 0.0) -> bool:
        """True if moving `dy` would put the sprite wholly below the bottom bound (a ring-out)."""
        return sprite.y + dy > self.bound_down


class FightPhysicsEngine(PhysicsEngine):
    """The seed's engine: three factors, plus gravity as a real acceleration.

    - `background_factor`: every movement is multiplied by it (0.8 for a fight under water).
    - `out_bound_distance` (px): a sprite past the left, right or top bound is put back this far
      inside, its velocity into the bound zeroed. The bottom is open: falling out is a ring-out.
    - `speed_factor`: multiplies the vector of every MotionAction.
    - `gravity` (px/ms^2): added to each sprite's vertical velocity, times its `gravity_scale`.
    """

    background_factor = Checked(validation.positive)
    out_bound_distance = Checked(validation.non_negative)
    speed_factor = Checked(validation.non_negative)
    gravity = Checked(validation.finite)

    def __init__(
        self,
        width: float,
        height: float,
        *,
        background_factor: float = 1.0,
        out_bound_distance: float = 1.0,
        speed_factor: float = 0.5,
        gravity: float = 0.002,
    ) -> None:
        super().__init__(width, height)
        self.background_factor = background_factor
        self.out_bound_distance = out_bound_distance
        self.speed_factor = speed_factor
        self.gravity = gravity

    def process(self, motion_action: MotionAction, elapsed_time: float) -> None:
        elapsed_time = validation.positive("elapsed_time", elapsed_time)
        sprite = motion_action.sprite
        scale = sprite.speed * elapsed_time * self.speed_factor
        self.set_next_location_increment(
            sprite, scale * motion_action.vector_x, scale * motion_action.vector_y
        )

    def set_next_location_increment(self, sprite: SpriteTemplate, dx: float, dy: float) -> None:
        dx, dy = validation.finite("dx", dx), validation.finite("dy", dy)
        sprite.increment_x += dx * self.background_factor
        sprite.increment_y += dy * self.background_factor

    def displacement(self, velocity: float, elapsed_time: float) -> float:
        return formulas.displacement(velocity, elapsed_time, self.background_factor)

    def integrate(self, sprite: SpriteTemplate, elapsed_time: float) -> None:
        """Gravity first (semi-implicit Euler), then the velocity's share of the increment."""
        sprite.vy += self.gravity * sprite.gravity_scale * elapsed_time
        super().integrate(sprite, elapsed_time)

    def keep_in_bounds(self, sprite: SpriteTemplate) -> None:
        if self.is_out_left(sprite):
            sprite.x = self.bound_left + self.out_bound_distance
            sprite.vx = max(sprite.vx, 0.0)
        elif self.is_out_right(sprite):
            sprite.x = self.bound_right - sprite.width - self.out_bound_distance
            sprite.vx = min(sprite.vx, 0.0)
        if self.is_out_up(sprite):
            sprite.y = self.bound_up + self.out_bound_distance
            sprite.vy = max(sprite.vy, 0.0)

    def __repr__(self) -> str:
        return (
            f"FightPhysicsEngine(width={self.width:g}, height={self.height:g}, "
            f"background_factor={self.background_factor:g}, "
            f"out_bound_distance={self.out_bound_distance:g}, "
            f"speed_factor={self.speed_factor:g}, gravity={self.gravity:g})"
        )
