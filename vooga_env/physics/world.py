"""`World`: the seed's per-frame system update as one call."""

from __future__ import annotations

from collections.abc import Iterable

from vooga_env.physics import validation
from vooga_env.physics.collision import Collision
from vooga_env.physics.contact import Contact
from vooga_env.physics.engine import PhysicsEngine
from vooga_env.physics.groups import SpriteGroupTemplate
from vooga_env.physics.kinds import CollisionKind
from vooga_env.physics.motion import MotionAction


class World:
    """An engine, a group of teams and the collision kinds, stepped a frame at a time.

    One `step` is, in order: every active sprite's velocity (after gravity) becomes its pending
    increment; each MotionAction adds to its sprite's increment; `check_group_collision` flags the
    contacts and records the reactions; each sprite takes the reactions' result if it collided and
    its increment otherwise; sprites out of the arena are put back; every status is reset.
    A step that raises (say, a custom reaction's error) leaves every sprite as it was before it.
    """

    def __init__(
        self,
        engine: PhysicsEngine,
        group: SpriteGroupTemplate,
        kinds: CollisionKind | Iterable[CollisionKind],
    ) -> None:
        self.collision = Collision(group, kinds, engine)

    @property
    def engine(self) -> PhysicsEngine:
        return self.collision.engine

    @property
    def group(self) -> SpriteGroupTemplate:
        return self.collision.collision_group

    def step(
        self, elapsed_time: float, motion_actions: Iterable[MotionAction] = ()
    ) -> list[Contact]:
        """Advance one frame of `elapsed_time` ms; returns the frame's contacts."""
        elapsed_time = validation.positive("elapsed_time", elapsed_time)
        engine, group = self.engine, self.group
        motion_actions = list(motion_actions)
        for action in motion_actions:
            if not isinstance(action, MotionAction):
                raise TypeError(f"motion_actions must hold MotionAction objects, got {action!r}")
            if action.sprite not in group:
                raise ValueError(f"motion action for {action.sprite!r}, which is not in this world")
        sprites = [sprite for sprite in group.sprites() if sprite.active]
        saved = [
            (
                sprite,
                sprite.x,
                sprite.y,
                sprite.vx,
                sprite.vy,
                sprite.increment_x,
                sprite.increment_y,
            )
            for sprite in sprites
        ]
        try:
            for sprite in sprites:
                engine.integrate(sprite, elapsed_time)
            for action in motion_actions:
                if action.sprite.active:
                    engine.process(action, elapsed_time)
            contacts = self.collision.check_group_collision(elapsed_time)
            for sprite in sprites:
                sprite.update()
                if sprite.movable:
                    engine.keep_in_bounds(sprite)
        except BaseException:
            _restore(saved)
            raise
        return contacts


def _restore(saved: list[tuple]) -> None:
    """Undo a step that raised half-way: each sprite as it was, nothing pending, no contacts."""
    for sprite, x, y, vx, vy, increment_x, increment_y in saved:
        sprite.x, sprite.y, sprite.vx, sprite.vy = x, y, vx, vy
        sprite.increment_x, sprite.increment_y = increment_x, increment_y
        sprite.response.reset()
        sprite.status.reset()
