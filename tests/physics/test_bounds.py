"""Behaviour 5: left, right and top bounds send a sprite back inside; the bottom is open."""

from __future__ import annotations

import pytest

from vooga_env.physics import FighterBody, MotionAction, PlatformBlock, SpriteTemplate

from .helpers import make_world

WIDTH, HEIGHT = 800.0, 600.0


@pytest.mark.parametrize("out_bound_distance", [0.0, 1.0, 7.5])
def test_left_bound(out_bound_distance):
    sprite = SpriteTemplate(2.0, 300.0, 20.0, 20.0, vx=-1.0, vy=0.25)
    world = make_world(
        [[sprite]], width=WIDTH, height=HEIGHT, out_bound_distance=out_bound_distance
    )

    world.step(10.0)

    assert sprite.x == 0.0 + out_bound_distance
    assert sprite.vx == 0.0
    assert (sprite.y, sprite.vy) == (300.0 + 2.5, 0.25)  # the other axis goes on


@pytest.mark.parametrize("out_bound_distance", [0.0, 1.0, 7.5])
def test_right_bound(out_bound_distance):
    sprite = SpriteTemplate(WIDTH - 25.0, 300.0, 20.0, 20.0, vx=1.0)
    world = make_world(
        [[sprite]], width=WIDTH, height=HEIGHT, out_bound_distance=out_bound_distance
    )

    world.step(10.0)

    assert sprite.right == WIDTH - out_bound_distance
    assert sprite.vx == 0.0


@pytest.mark.parametrize("out_bound_distance", [0.0, 1.0, 7.5])
def test_top_bound(out_bound_distance):
    sprite = SpriteTemplate(300.0, 3.0, 20.0, 20.0, vx=0.5, vy=-1.0)
    world = make_world(
        [[sprite]], width=WIDTH, height=HEIGHT, out_bound_distance=out_bound_distance
    )

    world.step(10.0)

    assert sprite.y == 0.0 + out_bound_distance
    assert sprite.vy == 0.0
    assert (sprite.x, sprite.vx) == (305.0, 0.5)


def test_motion_action_into_a_bound():
    sprite = FighterBody(1.0, 300.0, 20.0, 20.0, group_id=1, speed=1.0)
    world = make_world([[sprite]], width=WIDTH, height=HEIGHT, out_bound_distance=4.0)

    world.step(16.0, [MotionAction.left(sprite)])

    assert sprite.x == 4.0


def test_only_velocity_into_the_bound_is_zeroed():
    """A sprite outside but already moving back in keeps its velocity."""
    sprite = SpriteTemplate(-50.0, 300.0, 20.0, 20.0, vx=0.5)
    world = make_world([[sprite]], width=WIDTH, height=HEIGHT, out_bound_distance=1.0)

    world.step(10.0)  # -45: still outside

    assert sprite.x == 1.0
    assert sprite.vx == 0.5


def test_corner_bounds_apply_on_both_axes():
    sprite = SpriteTemplate(WIDTH - 21.0, 1.0, 20.0, 20.0, vx=1.0, vy=-1.0)
    world = make_world([[sprite]], width=WIDTH, height=HEIGHT, out_bound_distance=2.0)

    world.step(10.0)

    assert (sprite.right, sprite.y, sprite.vx, sprite.vy) == (WIDTH - 2.0, 2.0, 0.0, 0.0)


def test_out_bound_distance_is_a_settable_attribute():
    sprite = SpriteTemplate(2.0, 300.0, 20.0, 20.0, vx=-1.0)
    world = make_world([[sprite]], width=WIDTH, height=HEIGHT, out_bound_distance=1.0)
    world.engine.out_bound_distance = 9.0

    world.step(10.0)

    assert sprite.x == 9.0


def test_bottom_is_open_and_falling_out_is_out_down():
    gravity = 0.002
    sprite = FighterBody(300.0, HEIGHT - 30.0, 20.0, 20.0, group_id=1, vy=0.5)
    world = make_world([[sprite]], width=WIDTH, height=HEIGHT, gravity=gravity)
    engine = world.engine
    seen_partly_out = False

    for _ in range(20):
        world.step(16.0)
        if sprite.top <= HEIGHT < sprite.bottom:
            seen_partly_out = True
            assert not engine.is_out_down(sprite)  # partly below is not out yet
    assert seen_partly_out
    assert sprite.top > HEIGHT  # nothing stopped it
    assert engine.is_out_down(sprite)
    assert sprite.vy > 0.5  # still falling


def test_bound_tests_with_a_pending_move():
    engine = make_world([[]], width=WIDTH, height=HEIGHT).engine
    sprite = SpriteTemplate(10.0, 10.0, 20.0, 20.0)

    assert not engine.is_out_left(sprite) and engine.is_out_left(sprite, -10.5)
    assert not engine.is_out_left(sprite, -10.0)
    assert not engine.is_out_up(sprite) and engine.is_out_up(sprite, -10.5)
    assert not engine.is_out_right(sprite, WIDTH - 30.0)
    assert engine.is_out_right(sprite, WIDTH - 29.5)
    assert not engine.is_out_down(sprite, HEIGHT - 10.0)  # top exactly on the bottom bound
    assert engine.is_out_down(sprite, HEIGHT - 9.5)
    assert (engine.bound_left, engine.bound_up, engine.bound_right, engine.bound_down) == (
        0.0,
        0.0,
        WIDTH,
        HEIGHT,
    )


def test_platform_blocks_are_not_kept_in_bounds():
    """A stage may be wider than the arena: an immovable block stays where it was put."""
    floor = PlatformBlock(-100.0, 550.0, WIDTH + 200.0, 20.0)
    ceiling = PlatformBlock(0.0, -10.0, WIDTH, 20.0)
    world = make_world([[floor, ceiling]], width=WIDTH, height=HEIGHT)

    world.step(16.0)

    assert (floor.x, floor.y, ceiling.x, ceiling.y) == (-100.0, 550.0, 0.0, -10.0)
