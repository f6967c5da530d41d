"""A world step that raises changes nothing: the next step moves each sprite once, not twice."""

from __future__ import annotations

import pytest

from vooga_env.physics import (
    CollisionKindCustom,
    CollisionKindNeutral,
    FighterBody,
    MotionAction,
    PlatformBlock,
    Reaction,
    ReactionRebound,
)

from .helpers import exact_state, make_world

GRAVITY, DT = 0.002, 16.0


class Explodes(Reaction):
    """A reaction that fails, as user code may."""

    def act(self, sprite_one, sprite_two, engine) -> None:
        raise ZeroDivisionError("boom")


def falling_scene(extra_kinds=()):
    """A fighter walking right and falling onto a block this frame, plus any extra kinds."""
    block = PlatformBlock(0.0, 300.0, 1000.0, 40.0, name="floor")
    fighter = FighterBody(100.0, 236.0, 40.0, 60.0, group_id=1, vx=0.1, vy=0.3, name="fighter")
    kinds = [CollisionKindNeutral(ReactionRebound(friction=0.001)), *extra_kinds]
    world = make_world([[block], [fighter]], kinds, gravity=GRAVITY)
    return world, fighter, block


def pending(sprite):
    return (sprite.increment_x, sprite.increment_y, sprite.status.collided, sprite.status.contacts)


@pytest.mark.parametrize(
    "bad_kind",
    [
        CollisionKindCustom(),  # no set_type: raises RuntimeError when it meets a pair
        CollisionKindNeutral(Explodes()),
    ],
    ids=["custom-kind-without-set-type", "reaction-that-raises"],
)
def test_a_step_that_raises_leaves_every_sprite_as_it_was(bad_kind):
    world, fighter, block = falling_scene([bad_kind])
    twin, twin_fighter, twin_block = falling_scene()
    before = exact_state([fighter, block])
    walk = MotionAction(fighter, 1.0, 0.0)
    with pytest.raises((RuntimeError, ZeroDivisionError)):
        world.step(DT, [walk])
    assert exact_state([fighter, block]) == before
    assert pending(fighter) == pending(block) == (0.0, 0.0, False, {})

    world.collision.remove_collision_kind(bad_kind)
    world.step(DT, [walk])
    twin.step(DT, [MotionAction(twin_fighter, 1.0, 0.0)])
    assert exact_state([fighter, block]) == exact_state([twin_fighter, twin_block])
    assert fighter.x != before[0][0]  # it did move, once


def test_increments_set_before_the_step_survive_a_failed_step():
    """A soft increment given before `step` is still pending after a step that raised."""
    bad_kind = CollisionKindCustom()
    world, fighter, _ = falling_scene([bad_kind])
    world.engine.set_next_location_increment(fighter, 2.0, 0.0)
    with pytest.raises(RuntimeError, match="set_type"):
        world.step(DT)
    assert (fighter.increment_x, fighter.increment_y) == (2.0, 0.0)
