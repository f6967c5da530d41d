"""`MotionAction`: what an input (a key, or an agent's action) asks one sprite to do this frame."""

from __future__ import annotations

from dataclasses import dataclass

from vooga_env.physics import validation
from vooga_env.physics.sprites import SpriteTemplate


@dataclass(frozen=True)
class MotionAction:
    """A direction for `sprite`, scaled by its speed, the engine's speed factor and the frame time.

    The vector is unitless (the original keys used unit vectors); `PhysicsEngine.process` turns it
    into a pending increment of `speed * elapsed * vector * speed_factor` px.
    """

    sprite: SpriteTemplate
    vector_x: float
    vector_y: float

    def __post_init__(self) -> None:
        if not isinstance(self.sprite, SpriteTemplate):
            raise TypeError(f"sprite must be a SpriteTemplate, got {self.sprite!r}")
        object.__setattr__(self, "vector_x", validation.finite("vector_x", self.vector_x))
        object.__setattr__(self, "vector_y", validation.finite("vector_y", self.vector_y))

    @classmethod
    def left(cls, sprite: SpriteTemplate) -> MotionAction:
        return cls(sprite, -1.0, 0.0)

    @classmethod
    def right(cls, sprite: SpriteTemplate) -> MotionAction:
        return cls(sprite, 1.0, 0.0)

    @classmethod
    def up(cls, sprite: SpriteTemplate) -> MotionAction:
        return cls(sprite, 0.0, -1.0)

    @classmethod
    def down(cls, sprite: SpriteTemplate) -> MotionAction:
        return cls(sprite, 0.0, 1.0)
