"""Behaviour 4, continued: Rebound and Stop against blocks and fighters, and no reaction moves a
platform block (infinite mass)."""

from __future__ import annotations

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
    ReactionStop,
    SpriteTemplate,
)

from .helpers import make_world

# --- Rebound ------------------------------------------------------------------------------------


def test_rebound_inactive_top_stops_at_the_surface():
    block = PlatformBlock(0.0, 300.0, 1000.0, 20.0)
    fighter = FighterBody(100.0, 200.0, 30.0, 50.0, group_id=1, vy=2.0, vx=0.25)
    world = make_world([[block], [fighter]], [CollisionKindNeutral(ReactionRebound())])

    world.step(40.0)  # would fall 80 px, 30 px into the block

    assert fighter.bottom == block.top
    assert fighter.vy == 0.0
    assert fighter.x == 100.0 + 0.25 * 40.0  # sliding along the surface is untouched
    assert fighter.vx == 0.25


@pytest.mark.parametrize("side", ["left", "right"])
def test_rebound_inactive_side_stops_at_the_surface(side):
    block = PlatformBlock(400.0, 0.0, 50.0, 600.0)
    direction = 1.0 if side == "left" else -1.0
    x = 360.0 if side == "left" else 460.0
    fighter = FighterBody(x, 100.0, 30.0, 50.0, group_id=1, vx=direction, vy=0.1)
    world = make_world([[block], [fighter]], [CollisionKindNeutral(ReactionRebound())])

    world.step(40.0)

    assert fighter.x == (block.left - fighter.width if side == "left" else block.right)
    assert fighter.vx == 0.0
    assert fighter.y == 100.0 + 0.1 * 40.0
    assert fighter.vy == 0.1


def test_rebound_inactive_bottom_stops_a_jump():
    block = PlatformBlock(0.0, 100.0, 1000.0, 20.0)
    fighter = FighterBody(100.0, 130.0, 30.0, 50.0, group_id=1, vy=-1.0)
    world = make_world([[block], [fighter]], [CollisionKindNeutral(ReactionRebound())])

    world.step(20.0)

    assert fighter.top == block.bottom
    assert fighter.vy == 0.0


@pytest.mark.parametrize("distance", [0.0, 3.0, 12.5])
def test_rebound_active_top_ends_distance_off_moving_away(distance):
    block = PlatformBlock(0.0, 300.0, 1000.0, 20.0)
    fighter = FighterBody(100.0, 240.0, 30.0, 50.0, group_id=1, vy=0.5)
    world = make_world(
        [[block], [fighter]], [CollisionKindNeutral(ReactionRebound(up=True, distance=distance))]
    )

    world.step(40.0)

    assert fighter.bottom == pytest.approx(block.top - distance)
    assert fighter.vy == -0.5


def test_rebound_active_left_edge_only():
    block = PlatformBlock(400.0, 300.0, 50.0, 300.0)
    rebound = ReactionRebound(left=True, distance=2.0)
    side = FighterBody(360.0, 400.0, 30.0, 50.0, group_id=1, vx=1.0)
    top = FighterBody(410.0, 240.0, 30.0, 50.0, group_id=2, vy=0.5)
    world = make_world([[block], [side], [top]], [CollisionKindNeutral(rebound)])

    world.step(40.0)

    assert side.right == pytest.approx(block.left - 2.0)
    assert side.vx == -1.0
    assert top.bottom == block.top  # the top edge is not active: a plain stop
    assert top.vy == 0.0


@pytest.mark.parametrize(("block_y", "height"), [(500.0, 50.0), (400.1, 50.3), (333.3333, 77.7)])
def test_fighter_lands_and_rests_without_jitter_for_10000_frames(block_y, height):
    block = PlatformBlock(0.0, block_y, 1000.0, 20.0)
    fighter = FighterBody(100.0, 20.0, 30.0, height, group_id=1)
    world = make_world(
        [[block], [fighter]], [CollisionKindNeutral(ReactionRebound())], gravity=0.002
    )
    for _ in range(200):  # fall and land
        world.step(16.0)
    rest_y = fighter.y
    assert fighter.bottom == pytest.approx(block.top, abs=1e-9)

    for _ in range(10_000):
        contacts = world.step(16.0)
        assert len(contacts) == 1
        assert fighter.y == rest_y
        assert fighter.vy == 0.0
    assert (fighter.x, fighter.vx) == (100.0, 0.0)


def test_rebound_friction_slows_sliding_to_a_stop_and_never_reverses():
    friction, dt = 0.001, 16.0
    block = PlatformBlock(0.0, 300.0, 1000.0, 20.0)
    fighter = FighterBody(100.0, 250.0, 30.0, 50.0, group_id=1, vx=0.3)
    world = make_world(
        [[block], [fighter]],
        [CollisionKindNeutral(ReactionRebound(friction=friction))],
        gravity=0.002,
    )

    x_before = fighter.x
    world.step(dt)
    assert fighter.vx == pytest.approx(0.3 - friction * dt)
    assert fighter.x == pytest.approx(x_before + (0.3 - friction * dt) * dt)

    for frame in range(2, 40):
        world.step(dt)
        assert fighter.vx == pytest.approx(max(0.0, 0.3 - frame * friction * dt), abs=1e-12)
        assert fighter.vx >= 0.0
    assert fighter.vx == 0.0
    resting = fighter.x
    world.step(dt)
    assert fighter.x == resting


def test_a_sprite_squeezed_between_two_blocks_ends_half_way():
    """Two stops that cannot both hold (a 30 px fighter in a 20 px slot) meet half way."""
    left_wall = PlatformBlock(100.0, 0.0, 50.0, 600.0)
    right_wall = PlatformBlock(170.0, 0.0, 50.0, 600.0)
    fighter = FighterBody(145.0, 100.0, 30.0, 50.0, group_id=1, vx=0.3)
    world = make_world(
        [[left_wall, right_wall], [fighter]], [CollisionKindNeutral(ReactionRebound())]
    )

    world.step(16.0)

    low, high = left_wall.right, right_wall.left - fighter.width  # 150 and 140
    assert fighter.x == 0.5 * (low + high)
    assert fighter.vx == 0.0


def test_rebound_ignores_pairs_without_a_platform_block():
    fighter = FighterBody(100.0, 100.0, 20.0, 20.0, group_id=1, vx=1.0)
    crate = SpriteTemplate(130.0, 100.0, 20.0, 20.0)
    world = make_world([[fighter], [crate]], [CollisionKindNeutral(ReactionRebound())])

    assert len(world.step(20.0)) == 1
    assert (fighter.x, fighter.vx, crate.x) == (120.0, 1.0, 130.0)


# --- Stop ---------------------------------------------------------------------------------------


@pytest.mark.parametrize("distance", [0.0, 0.2, 0.5, 3.0])
@pytest.mark.parametrize(("m1", "m2"), [(200.0, 200.0), (100.0, 300.0), (900.0, 10.0)])
def test_stop_leaves_exactly_distance_between(distance, m1, m2):
    dt = 16.0
    one = FighterBody(100.0, 100.0, 20.0, 20.0, group_id=1, mass=m1, vx=5.0)
    two = FighterBody(150.0, 100.0, 2.0, 20.0, group_id=2, mass=m2, vx=-0.5)
    toi = (two.left - one.right) / ((5.0 + 0.5) * dt)
    meet_one, meet_two = 100.0 + toi * 5.0 * dt, 150.0 - toi * 0.5 * dt
    world = make_world([[one], [two]], [CollisionKindEnemy(ReactionStop(distance=distance))])

    world.step(dt)

    assert two.left - one.right == pytest.approx(distance, abs=1e-9)
    assert one.x == pytest.approx(meet_one - distance * m2 / (m1 + m2), abs=1e-9)
    assert two.x == pytest.approx(meet_two + distance * m1 / (m1 + m2), abs=1e-9)
    assert (one.vx, two.vx) == (0.0, 0.0)


@pytest.mark.parametrize("overlap", [5.0, 0.75])
def test_stop_from_an_overlap_opens_exactly_distance(overlap):
    one = FighterBody(100.0, 100.0, 20.0, 20.0, group_id=1, mass=100.0)
    two = FighterBody(120.0 - overlap, 100.0, 20.0, 20.0, group_id=2, mass=300.0)
    world = make_world([[one], [two]], [CollisionKindEnemy(ReactionStop(distance=1.0))])

    world.step(16.0)

    extra = 1.0 + overlap  # from a gap of -overlap to +1 px, shared inversely to mass
    assert two.left - one.right == pytest.approx(1.0, abs=1e-12)
    assert one.x == pytest.approx(100.0 - extra * 300.0 / 400.0, abs=1e-12)
    assert two.x == pytest.approx(120.0 - overlap + extra * 100.0 / 400.0, abs=1e-12)


def test_stop_against_a_block_only_the_sprite_moves():
    block = PlatformBlock(0.0, 300.0, 1000.0, 20.0)
    fighter = FighterBody(100.0, 200.0, 30.0, 50.0, group_id=1, vy=2.0)
    world = make_world([[block], [fighter]], [CollisionKindNeutral(ReactionStop(distance=2.0))])

    world.step(40.0)

    assert block.top - fighter.bottom == pytest.approx(2.0)
    assert fighter.vy == 0.0
    assert (block.x, block.y) == (0.0, 300.0)


# --- every reaction ---------------------------------------------------------------------------


@pytest.mark.parametrize(
    "reaction",
    [
        ReactionForce(100.0, 100.0, -100.0, -100.0),
        ReactionMomentumConservation(),
        ReactionPunch(),
        ReactionPush(),
        ReactionRebound(up=True, left=True, distance=4.0, friction=0.01),
        ReactionStop(distance=1.0),
    ],
    ids=lambda r: type(r).__name__,
)
@pytest.mark.parametrize("block_first", [True, False])
def test_no_reaction_moves_a_platform_block(reaction, block_first):
    block = PlatformBlock(300.0, 300.0, 100.0, 20.0)
    fighter = FighterBody(290.0, 240.0, 30.0, 50.0, group_id=1, vx=0.2, vy=1.0)
    teams = [[block], [fighter]] if block_first else [[fighter], [block]]
    world = make_world(teams, [CollisionKindNeutral(reaction)], gravity=0.002)

    contacts = sum(len(world.step(16.0)) for _ in range(10))

    assert contacts > 0
    assert (block.x, block.y, block.vx, block.vy) == (300.0, 300.0, 0.0, 0.0)
