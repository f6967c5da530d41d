"""Behaviour 4: each reaction's formula, checked against numbers worked out from the seed.

Force, MomentumConservation, Push and Punch here; Rebound and Stop in test_reactions_rebound_stop.

Scenes are in free space (gravity 0) unless the reaction is about the ground. A sprite that meets
its partner at the fraction t of the frame (the time of impact) moves as before until t and as the
reaction says afterwards, so "after" positions are `start + t * old_increment + (1 - t) * new`.
"""

from __future__ import annotations

import itertools

import pytest

from vooga_env.physics import (
    CollisionKindEnemy,
    CollisionKindNeutral,
    FighterBody,
    PlatformBlock,
    ReactionForce,
    ReactionMomentumConservation,
    ReactionPunch,
    ReactionPush,
    ReactionRebound,
    SpriteTemplate,
)

from .helpers import make_world

# --- Force --------------------------------------------------------------------------------------


@pytest.mark.parametrize("background_factor", [1.0, 0.8])
def test_force_adds_the_others_force_over_own_mass(background_factor):
    dt = 20.0
    one = FighterBody(100.0, 100.0, 20.0, 20.0, group_id=1, mass=200.0, vx=1.0)
    two = FighterBody(130.0, 100.0, 20.0, 20.0, group_id=2, mass=400.0)
    force = ReactionForce(force_x1=40.0, force_y1=-8.0, force_x2=-100.0, force_y2=20.0)
    # `one` is in the first team, so it is the reaction's sprite one
    world = make_world(
        [[one], [two]], [CollisionKindEnemy(force)], background_factor=background_factor
    )
    increment = 1.0 * dt * background_factor
    toi = (two.left - one.right) / increment
    rest = (1.0 - toi) * dt * background_factor  # how far a velocity change carries this frame

    world.step(dt)

    assert one.vx == pytest.approx(1.0 + -100.0 / 200.0)  # + force_x2 / mass_one
    assert one.vy == pytest.approx(0.0 + 20.0 / 200.0)  # + force_y2 / mass_one
    assert two.vx == pytest.approx(0.0 + 40.0 / 400.0)  # + force_x1 / mass_two
    assert two.vy == pytest.approx(0.0 + -8.0 / 400.0)  # + force_y1 / mass_two
    assert one.x == pytest.approx(100.0 + increment + rest * (-100.0 / 200.0), abs=1e-12)
    assert one.y == pytest.approx(100.0 + rest * (20.0 / 200.0), abs=1e-12)
    assert two.x == pytest.approx(130.0 + rest * (40.0 / 400.0), abs=1e-12)
    assert two.y == pytest.approx(100.0 + rest * (-8.0 / 400.0), abs=1e-12)


@pytest.mark.parametrize("side", ["left", "right", "above", "below"])
def test_force_does_not_depend_on_the_side_touched(side):
    offsets = {
        "left": (-30.0, 0.0),
        "right": (30.0, 0.0),
        "above": (0.0, -30.0),
        "below": (0.0, 30.0),
    }
    dx, dy = offsets[side]
    one = FighterBody(
        300.0 + dx, 300.0 + dy, 20.0, 20.0, group_id=1, mass=250.0, vx=-dx / 20.0, vy=-dy / 20.0
    )  # closes 30 px in 20 ms: meets at t = 1/3
    two = FighterBody(300.0, 300.0, 20.0, 20.0, group_id=2, mass=125.0)
    before = (one.vx, one.vy, two.vx, two.vy)
    world = make_world([[one], [two]], [CollisionKindEnemy(ReactionForce(5.0, 10.0, -25.0, 50.0))])

    world.step(20.0)

    assert (one.vx - before[0], one.vy - before[1]) == pytest.approx((-25.0 / 250.0, 50.0 / 250.0))
    assert (two.vx - before[2], two.vy - before[3]) == pytest.approx((5.0 / 125.0, 10.0 / 125.0))


# --- MomentumConservation ------------------------------------------------------------------------


def elastic(m1, m2, v1, v2):
    """The seed's formula, written out here independently of the engine."""
    return (
        (m1 - m2) / (m1 + m2) * v1 + 2 * m2 / (m1 + m2) * v2,
        (m2 - m1) / (m1 + m2) * v2 + 2 * m1 / (m1 + m2) * v1,
    )


@pytest.mark.parametrize(("v1", "v2"), [(1.0, -1.0), (0.75, -0.25), (1.0, 0.0), (0.5, 0.25)])
def test_momentum_conservation_equal_masses_swap_velocities(v1, v2):
    dt = 10.0
    one = FighterBody(100.0, 100.0, 10.0, 20.0, group_id=1, vx=v1)
    two = FighterBody(110.0 + 10.0 * (v1 - v2) / 2, 100.0, 10.0, 20.0, group_id=2, vx=v2)
    x1, x2 = one.x, two.x  # they close half the gap... and meet at t = 0.5
    world = make_world([[one], [two]], [CollisionKindEnemy(ReactionMomentumConservation())])

    contacts = world.step(dt)

    assert contacts[0].time_of_impact == pytest.approx(0.5)
    assert (one.vx, two.vx) == (v2, v1)
    assert one.x == pytest.approx(x1 + 0.5 * v1 * dt + 0.5 * v2 * dt, abs=1e-12)
    assert two.x == pytest.approx(x2 + 0.5 * v2 * dt + 0.5 * v1 * dt, abs=1e-12)


@pytest.mark.parametrize(
    ("m1", "m2", "v1", "v2"),
    [
        (100.0, 300.0, 1.0, 0.0),
        (300.0, 100.0, 1.0, 0.0),
        (50.0, 800.0, 0.6, -0.3),
        (700.0, 20.0, 0.05, -1.5),
    ],
)
def test_momentum_conservation_unequal_masses(m1, m2, v1, v2):
    dt = 20.0
    gap = 0.5 * (v1 - v2) * dt  # meet half way through the frame
    one = FighterBody(200.0, 100.0, 10.0, 20.0, group_id=1, mass=m1, vx=v1)
    two = FighterBody(210.0 + gap, 100.0, 10.0, 20.0, group_id=2, mass=m2, vx=v2)
    x1, x2 = one.x, two.x
    world = make_world([[one], [two]], [CollisionKindEnemy(ReactionMomentumConservation())])

    world.step(dt)

    w1, w2 = elastic(m1, m2, v1, v2)
    assert one.vx == pytest.approx(w1, rel=1e-12, abs=1e-15)
    assert two.vx == pytest.approx(w2, rel=1e-12, abs=1e-15)
    assert m1 * one.vx + m2 * two.vx == pytest.approx(m1 * v1 + m2 * v2, rel=1e-12, abs=1e-12)
    assert m1 * one.vx**2 + m2 * two.vx**2 == pytest.approx(m1 * v1**2 + m2 * v2**2, rel=1e-12)
    assert one.x == pytest.approx(x1 + 0.5 * dt * v1 + 0.5 * dt * w1, abs=1e-9)
    assert two.x == pytest.approx(x2 + 0.5 * dt * v2 + 0.5 * dt * w2, abs=1e-9)


def test_momentum_conservation_vertical():
    upper = FighterBody(100.0, 100.0, 20.0, 20.0, group_id=1, mass=100.0, vy=1.0)
    lower = FighterBody(100.0, 130.0, 20.0, 20.0, group_id=2, mass=300.0, vy=0.0)
    world = make_world([[upper], [lower]], [CollisionKindEnemy(ReactionMomentumConservation())])

    world.step(20.0)

    assert (upper.vy, lower.vy) == pytest.approx(elastic(100.0, 300.0, 1.0, 0.0))
    assert (upper.vx, lower.vx) == (0.0, 0.0)


def test_momentum_conservation_only_while_closing():
    one = FighterBody(100.0, 100.0, 20.0, 20.0, group_id=1, vx=-0.1)
    two = FighterBody(115.0, 100.0, 20.0, 20.0, group_id=2, vx=0.1)  # 5 px overlap, parting
    world = make_world([[one], [two]], [CollisionKindEnemy(ReactionMomentumConservation())])

    world.step(10.0)

    assert (one.vx, two.vx) == (-0.1, 0.1)
    # only the starting overlap is undone, half each (equal masses)
    assert one.x == pytest.approx(100.0 - 1.0 - 2.5)
    assert two.x == pytest.approx(115.0 + 1.0 + 2.5)


def test_momentum_conservation_against_a_block_reflects():
    block = PlatformBlock(200.0, 0.0, 20.0, 600.0)
    ball = SpriteTemplate(170.0, 100.0, 10.0, 10.0, vx=1.0)
    world = make_world([[block], [ball]], [CollisionKindNeutral(ReactionMomentumConservation())])

    world.step(40.0)  # meets the block at t = 0.5, then comes back 20 px

    assert ball.vx == -1.0
    assert ball.x == pytest.approx(170.0)
    assert (block.x, block.vx) == (200.0, 0.0)


# --- Push ---------------------------------------------------------------------------------------


def test_push_common_velocity():
    dt, m1, m2, v1, v2 = 20.0, 100.0, 300.0, 1.0, 0.0
    pusher = FighterBody(100.0, 100.0, 10.0, 20.0, group_id=1, mass=m1, vx=v1)
    pushed = FighterBody(120.0, 100.0, 10.0, 20.0, group_id=2, mass=m2, vx=v2)
    world = make_world([[pusher], [pushed]], [CollisionKindEnemy(ReactionPush())])
    common = (m1 * v1 + m2 * v2) / (m1 + m2)  # 0.25
    toi = (pushed.left - pusher.right) / (v1 * dt)  # 0.5

    world.step(dt)

    assert (pusher.vx, pushed.vx) == (common, common)
    assert pusher.x == pytest.approx(100.0 + toi * v1 * dt + (1 - toi) * common * dt)
    assert pushed.x == pytest.approx(120.0 + (1 - toi) * common * dt)
    assert pusher.right == pytest.approx(pushed.left)
    assert m1 * pusher.vx + m2 * pushed.vx == m1 * v1 + m2 * v2
    for _ in range(20):  # and they go on together
        world.step(dt)
        assert pusher.right == pytest.approx(pushed.left)
        assert (pusher.vx, pushed.vx) == (common, common)


@pytest.mark.parametrize("order", list(itertools.permutations(range(3))))
def test_push_does_not_drive_a_grounded_sprite_into_the_ground(order):
    """Whatever the team order, `on_ground` is known before any reaction runs."""
    gravity, dt = 0.002, 16.0
    floor = PlatformBlock(0.0, 500.0, 1000.0, 20.0)
    below = FighterBody(100.0, 450.0, 40.0, 50.0, group_id=2, mass=200.0)  # standing
    above = FighterBody(100.0, 400.0, 40.0, 46.0, group_id=1, mass=800.0, vy=0.5)  # 4 px above
    teams = [[floor], [above], [below]]
    world = make_world(
        [teams[i] for i in order],
        [CollisionKindEnemy(ReactionPush()), CollisionKindNeutral(ReactionRebound())],
        gravity=gravity,
    )
    fall = (0.5 + gravity * dt) * dt

    world.step(dt)

    assert (below.y, below.vy) == (450.0, 0.0)  # not pushed into the floor
    assert above.vy == 0.0  # the one on top just stops moving down
    assert above.y < 400.0 + fall  # ... during this frame, not after it


def test_push_carries_a_sprite_that_is_not_on_the_ground():
    above = FighterBody(100.0, 400.0, 40.0, 46.0, group_id=1, mass=800.0, vy=0.5)
    below = FighterBody(100.0, 450.0, 40.0, 50.0, group_id=2, mass=200.0)
    world = make_world([[above], [below]], [CollisionKindEnemy(ReactionPush())])

    world.step(16.0)

    common = (800.0 * 0.5 + 200.0 * 0.0) / 1000.0
    assert (above.vy, below.vy) == pytest.approx((common, common))


def test_push_only_while_closing():
    one = FighterBody(100.0, 100.0, 20.0, 20.0, group_id=1, mass=100.0, vx=-0.1)
    two = FighterBody(115.0, 100.0, 20.0, 20.0, group_id=2, mass=300.0, vx=0.1)
    world = make_world([[one], [two]], [CollisionKindEnemy(ReactionPush())])

    world.step(10.0)

    assert (one.vx, two.vx) == (-0.1, 0.1)
    # the starting 5 px overlap is undone inversely to mass: 3/4 by the light one
    assert one.x == pytest.approx(100.0 - 1.0 - 5.0 * 300.0 / 400.0)
    assert two.x == pytest.approx(115.0 + 1.0 + 5.0 * 100.0 / 400.0)


# --- Punch --------------------------------------------------------------------------------------


@pytest.mark.parametrize(
    ("punch", "direction", "expected_x"),
    [
        (ReactionPunch(), 1.0, lambda engine, w: engine.width - w),
        (ReactionPunch(), -1.0, lambda engine, w: 0.0),
        (ReactionPunch(left=100.0, right=800.0), 1.0, lambda engine, w: 800.0 - w),
        (ReactionPunch(left=100.0, right=800.0), -1.0, lambda engine, w: 100.0),
    ],
)
def test_punch_sends_the_struck_sprite_to_the_far_bound(punch, direction, expected_x):
    puncher = FighterBody(
        480.0 - direction * 30.0, 300.0, 20.0, 40.0, group_id=1, vx=direction * 1.0
    )
    struck = FighterBody(480.0, 300.0, 20.0, 40.0, group_id=2, vx=direction * 0.2)
    start = puncher.x
    world = make_world([[puncher], [struck]], [CollisionKindEnemy(punch)])

    world.step(20.0)

    assert struck.x == expected_x(world.engine, struck.width)
    assert struck.vx == 0.0  # its velocity into the bound is zeroed
    assert (struck.y, puncher.y) == (300.0, 300.0)
    assert puncher.x == start + direction * 20.0  # the puncher goes on as it was
    assert puncher.vx == direction * 1.0


@pytest.mark.parametrize(("direction", "expected_y"), [(-1.0, 50.0), (1.0, 550.0 - 40.0)])
def test_punch_vertical(direction, expected_y):
    puncher = FighterBody(
        300.0, 300.0 - direction * 50.0, 20.0, 40.0, group_id=1, vy=direction * 1.0
    )
    struck = FighterBody(300.0, 300.0, 20.0, 40.0, group_id=2)
    world = make_world(
        [[puncher], [struck]], [CollisionKindEnemy(ReactionPunch(up=50.0, down=550.0))]
    )

    world.step(20.0)

    assert struck.y == expected_y
    assert struck.vy == 0.0


def test_punch_strikes_the_slower_closer_and_both_when_equal():
    faster = FighterBody(400.0, 300.0, 20.0, 40.0, group_id=1, vx=0.5)
    slower = FighterBody(440.0, 300.0, 20.0, 40.0, group_id=2, vx=-1.0)
    world = make_world([[faster], [slower]], [CollisionKindEnemy(ReactionPunch())])
    world.step(20.0)
    assert faster.x == 0.0  # `slower` closes faster, so it is the puncher
    assert slower.x == pytest.approx(440.0 - 20.0)

    one = FighterBody(400.0, 300.0, 20.0, 40.0, group_id=1, vx=1.0)
    two = FighterBody(440.0, 300.0, 20.0, 40.0, group_id=2, vx=-1.0)
    world = make_world([[one], [two]], [CollisionKindEnemy(ReactionPunch())])
    world.step(20.0)
    assert (one.x, two.x) == (0.0, world.engine.width - two.width)
