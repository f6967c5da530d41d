"""Behaviour 1: MotionActions become pending increments; velocities persist; gravity accelerates."""

from __future__ import annotations

import pytest

from vooga_env.physics import FighterBody, MotionAction, PlatformBlock, SpriteTemplate

from .helpers import make_world

DT = 16.0  # ms


@pytest.mark.parametrize("speed_factor", [0.5, 1.0, 2.0])
@pytest.mark.parametrize("background_factor", [1.0, 0.8])
@pytest.mark.parametrize("vector", [(1.0, 0.0), (-1.0, 0.0), (0.0, -1.0), (0.6, 0.8), (-0.25, 3.0)])
def test_process_sets_increment_from_the_seed_formula(speed_factor, background_factor, vector):
    sprite = SpriteTemplate(400.0, 300.0, 20.0, 30.0, speed=0.3)
    world = make_world([[sprite]], speed_factor=speed_factor, background_factor=background_factor)
    action = MotionAction(sprite, *vector)

    world.engine.process(action, DT)

    # speed * elapsed * vector * speed_factor, then every movement times background_factor
    expected_x = 0.3 * DT * vector[0] * speed_factor * background_factor
    expected_y = 0.3 * DT * vector[1] * speed_factor * background_factor
    assert sprite.increment_x == pytest.approx(expected_x, rel=1e-12, abs=1e-12)
    assert sprite.increment_y == pytest.approx(expected_y, rel=1e-12, abs=1e-12)
    assert (sprite.x, sprite.y) == (400.0, 300.0)  # process only sets the pending increment


def test_step_applies_motion_increment_once():
    sprite = SpriteTemplate(400.0, 300.0, 20.0, 30.0, speed=0.25)
    world = make_world([[sprite]], speed_factor=0.5)

    world.step(DT, [MotionAction.right(sprite)])

    assert sprite.x == 400.0 + 0.25 * DT * 1.0 * 0.5  # 2 px, exact in binary
    assert sprite.y == 300.0
    assert (sprite.increment_x, sprite.increment_y) == (0.0, 0.0)
    assert (sprite.vx, sprite.vy) == (0.0, 0.0)  # a MotionAction moves, it does not accelerate


def test_two_actions_in_one_frame_add_up():
    sprite = SpriteTemplate(400.0, 300.0, 20.0, 30.0, speed=0.25)
    world = make_world([[sprite]], speed_factor=0.5)

    world.step(DT, [MotionAction.right(sprite), MotionAction.up(sprite)])

    assert (sprite.x, sprite.y) == (400.0 + 2.0, 300.0 - 2.0)


def test_water_background_factor_scales_every_movement():
    """The seed's example: under water (background_factor 0.8) everything moves 0.8 as far."""
    dry = SpriteTemplate(100.0, 100.0, 20.0, 20.0, speed=0.3, vx=0.2, vy=-0.1)
    wet = SpriteTemplate(100.0, 100.0, 20.0, 20.0, speed=0.3, vx=0.2, vy=-0.1)
    dry_world = make_world([[dry]], background_factor=1.0)
    wet_world = make_world([[wet]], background_factor=0.8)

    dry_world.step(DT, [MotionAction(dry, 1.0, 0.5)])
    wet_world.step(DT, [MotionAction(wet, 1.0, 0.5)])

    dry_dx = (0.2 * DT + 0.3 * DT * 1.0 * 0.5) * 1.0
    dry_dy = (-0.1 * DT + 0.3 * DT * 0.5 * 0.5) * 1.0
    assert dry.x - 100.0 == pytest.approx(dry_dx, rel=1e-12)
    assert dry.y - 100.0 == pytest.approx(dry_dy, rel=1e-12)
    assert wet.x - 100.0 == pytest.approx(0.8 * dry_dx, rel=1e-12)
    assert wet.y - 100.0 == pytest.approx(0.8 * dry_dy, rel=1e-12)
    assert (wet.vx, wet.vy) == (0.2, -0.1)  # the factor scales movement, not the velocity


def test_speed_factor_scales_motion_actions_but_not_velocity():
    still = SpriteTemplate(100.0, 100.0, 20.0, 20.0, vx=0.5)
    world = make_world([[still]], speed_factor=3.0)

    world.step(DT)

    assert still.x == 100.0 + 0.5 * DT  # velocity * elapsed, speed_factor plays no part


def test_speed_factor_is_a_settable_attribute():
    sprite = SpriteTemplate(100.0, 100.0, 20.0, 20.0, speed=0.25)
    world = make_world([[sprite]], speed_factor=0.5)
    world.engine.speed_factor = 2.0
    world.engine.background_factor = 0.5

    world.step(DT, [MotionAction.left(sprite)])

    assert sprite.x == 100.0 - 0.25 * DT * 2.0 * 0.5


def test_velocity_persists_without_gravity_or_contact():
    """No hidden damping: with gravity 0 and nothing to touch, velocity never changes."""
    sprite = SpriteTemplate(100.0, 3000.0, 20.0, 20.0, vx=0.125, vy=-0.0625)
    world = make_world([[sprite]], width=5000.0, height=5000.0, gravity=0.0)

    for frame in range(1, 1001):
        world.step(10.0)
        assert (sprite.vx, sprite.vy) == (0.125, -0.0625)
        # binary fractions: every partial sum is exact
        assert sprite.x == 100.0 + frame * 0.125 * 10.0
        assert sprite.y == 3000.0 - frame * 0.0625 * 10.0


def test_gravity_accelerates_semi_implicitly():
    """vy += gravity * dt first, then y += vy * dt: after n frames y = y0 + g dt^2 n(n+1)/2."""
    gravity = 0.002
    sprite = SpriteTemplate(100.0, 10.0, 20.0, 20.0)
    world = make_world([[sprite]], width=1000.0, height=100000.0, gravity=gravity)

    for frame in range(1, 61):
        world.step(DT)
        assert sprite.vy == pytest.approx(frame * gravity * DT, rel=1e-12)
        expected_y = 10.0 + gravity * DT * DT * frame * (frame + 1) / 2
        assert sprite.y == pytest.approx(expected_y, rel=1e-12)
    assert sprite.vx == 0.0


def test_gravity_scale_and_platforms():
    floating = SpriteTemplate(100.0, 100.0, 20.0, 20.0, gravity_scale=0.0)
    heavy = SpriteTemplate(300.0, 100.0, 20.0, 20.0, gravity_scale=2.0)
    block = PlatformBlock(500.0, 100.0, 50.0, 10.0)
    world = make_world([[floating], [heavy], [block]], gravity=0.001)

    world.step(10.0)

    assert (floating.y, floating.vy) == (100.0, 0.0)
    assert heavy.vy == pytest.approx(2.0 * 0.001 * 10.0, rel=1e-12)
    assert heavy.y == pytest.approx(100.0 + 2.0 * 0.001 * 10.0 * 10.0, rel=1e-12)
    assert (block.x, block.y, block.vx, block.vy) == (500.0, 100.0, 0.0, 0.0)


def test_motion_action_directions_are_screen_coordinates():
    sprite = FighterBody(0.0, 0.0, 10.0, 10.0, group_id=1)
    assert (MotionAction.left(sprite).vector_x, MotionAction.left(sprite).vector_y) == (-1.0, 0.0)
    assert (MotionAction.right(sprite).vector_x, MotionAction.right(sprite).vector_y) == (1.0, 0.0)
    assert (MotionAction.up(sprite).vector_x, MotionAction.up(sprite).vector_y) == (0.0, -1.0)
    assert (MotionAction.down(sprite).vector_x, MotionAction.down(sprite).vector_y) == (0.0, 1.0)


def test_inactive_sprite_is_neither_moved_nor_collided():
    sleeper = FighterBody(100.0, 100.0, 20.0, 20.0, group_id=1, vx=1.0)
    other = FighterBody(110.0, 100.0, 20.0, 20.0, group_id=2)
    sleeper.active = False
    world = make_world([[sleeper], [other]], gravity=0.002)

    contacts = world.step(DT, [MotionAction.right(sleeper)])

    assert contacts == []
    assert (sleeper.x, sleeper.y, sleeper.vx, sleeper.vy) == (100.0, 100.0, 1.0, 0.0)
    assert (sleeper.increment_x, sleeper.increment_y) == (0.0, 0.0)  # nothing left pending

    sleeper.active = True
    other.x = 500.0
    world.step(DT)
    assert sleeper.x == 100.0 + 1.0 * DT  # only this frame's velocity, no stale action


def test_sprite_edges():
    sprite = SpriteTemplate(10.0, 20.0, 30.0, 40.0)
    assert (sprite.left, sprite.right, sprite.top, sprite.bottom) == (10.0, 40.0, 20.0, 60.0)
