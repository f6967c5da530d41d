"""Helpers shared by the physics tests: build a world, read exact state, watch statuses.

Nothing here imitates the engine: `AnyPair` and `StatusProbe` are real `CollisionKind` and
`Reaction` subclasses, run by the real `World.step`.
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Sequence

from vooga_env.physics import (
    CollisionKind,
    FightPhysicsEngine,
    Reaction,
    SpriteGroupTemplate,
    SpriteTemplate,
    World,
)
from vooga_env.physics.engine import PhysicsEngine

ARENA_WIDTH = 1000.0  # px
ARENA_HEIGHT = 600.0  # px
FLAGS = ("left", "right", "up", "down", "on_ground")


def make_world(
    teams: Iterable[Iterable[SpriteTemplate]],
    kinds: CollisionKind | Iterable[CollisionKind] = (),
    *,
    width: float = ARENA_WIDTH,
    height: float = ARENA_HEIGHT,
    **engine_kwargs: float,
) -> World:
    """A world whose teams are `teams`, in that order. Gravity is 0 unless given."""
    engine_kwargs.setdefault("gravity", 0.0)
    engine = FightPhysicsEngine(width, height, **engine_kwargs)
    group = SpriteGroupTemplate()
    for team in teams:
        group.add_sprite_array(list(team))
    return World(engine, group, kinds)


def exact_state(sprites: Sequence[SpriteTemplate]) -> tuple[tuple[str, ...], ...]:
    """x, y, vx, vy of each sprite as `float.hex` strings: equal means bit-identical."""
    return tuple(
        (sprite.x.hex(), sprite.y.hex(), sprite.vx.hex(), sprite.vy.hex()) for sprite in sprites
    )


def all_finite(sprites: Iterable[SpriteTemplate]) -> bool:
    """True if no sprite's position or velocity is NaN or infinite."""
    return all(math.isfinite(v) for s in sprites for v in (s.x, s.y, s.vx, s.vy))


class AnyPair(CollisionKind):
    """A kind that matches every contacting pair."""

    def is_this_kind(self, sprite_one: SpriteTemplate, sprite_two: SpriteTemplate) -> bool:
        return True


class StatusProbe(Reaction):
    """Records both sprites' status flags as they stand when reactions run (all contacts known)."""

    def __init__(self) -> None:
        self.flags: dict[SpriteTemplate, dict[str, bool]] = {}
        self.calls: list[tuple[SpriteTemplate, SpriteTemplate]] = []

    def act(
        self, sprite_one: SpriteTemplate, sprite_two: SpriteTemplate, engine: PhysicsEngine
    ) -> None:
        self.calls.append((sprite_one, sprite_two))
        for sprite in (sprite_one, sprite_two):
            self.flags[sprite] = {name: getattr(sprite.status, name) for name in FLAGS}

    def edges(self, sprite: SpriteTemplate) -> set[str]:
        """The flags that were set on `sprite`, as a set of names."""
        return {name for name, value in self.flags.get(sprite, {}).items() if value}
