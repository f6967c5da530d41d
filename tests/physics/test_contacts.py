"""Behaviour 3: contact edges on both sprites, decided by penetration and motion; no tunnelling."""

from __future__ import annotations

import pytest

from vooga_env.physics import (
    CollisionKindEnemy,
    CollisionKindNeutral,
    FighterBody,
    PlatformBlock,
    ReactionMomentumConservation,
    ReactionPush,
    ReactionRebound,
    ReactionStop,
    SpriteTemplate,
)

from .helpers import AnyPair, StatusProbe, make_world

OPPOSITE = {"left": "right", "right": "left", "up": "down", "down": "up"}

# A 20x20 mover 10 px from a 40x40 target at (200, 200), closing at 1 px/ms for 20 ms: it meets the
# target half way through the frame. Keyed by the mover's edge that touches.
APPROACHES = {
    "right": ((170.0, 210.0), (1.0, 0.0)),
    "left": ((250.0, 210.0), (-1.0, 0.0)),
    "down": ((210.0, 170.0), (0.0, 1.0)),
    "up": ((210.0, 250.0), (0.0, -1.0)),
}


@pytest.mark.parametrize("edge", sorted(APPROACHES))
@pytest.mark.parametrize("who_moves", ["mover", "target", "both"])
def test_edges_recorded_on_both_sprites(edge, who_moves):
    (x, y), (ux, uy) = APPROACHES[edge]
    share = {"mover": (1.0, 0.0), "target": (0.0, -1.0), "both": (0.5, -0.5)}[who_moves]
    mover = FighterBody(x, y, 20.0, 20.0, group_id=1, vx=ux * share[0], vy=uy * share[0])
    target = FighterBody(200.0, 200.0, 40.0, 40.0, group_id=2, vx=ux * share[1], vy=uy * share[1])
    probe = StatusProbe()
    world = make_world([[mover], [target]], [AnyPair(probe)])

    contacts = world.step(20.0)

    assert len(contacts) == 1
    contact = contacts[0]
    assert contact.sprite is mover and contact.other is target  # seen from the lower team
    assert contact.edge == edge
    assert contact.flipped().edge == OPPOSITE[edge]
    assert contact.axis == (0 if edge in ("left", "right") else 1)
    assert contact.time_of_impact == pytest.approx(10.0 / 20.0)
    assert probe.edges(mover) == {edge}
    assert probe.edges(target) == {OPPOSITE[edge]}  # two fighters: no on_ground
    assert not mover.status.collided and not target.status.collided  # reset by the update


def test_landing_on_a_platform_sets_on_ground_and_down():
    block = PlatformBlock(0.0, 300.0, 1000.0, 20.0)
    fighter = FighterBody(100.0, 240.0, 30.0, 50.0, group_id=1, vy=0.5)  # 10 px above
    probe = StatusProbe()
    world = make_world([[block], [fighter]], [AnyPair(probe)])

    contacts = world.step(40.0)

    assert [c.edge for c in contacts] == ["up"]  # seen from the block (team 0)
    assert probe.edges(fighter) == {"down", "on_ground"}
    assert probe.edges(block) == {"up"}


def test_resting_on_a_platform_is_a_contact_every_frame():
    block = PlatformBlock(0.0, 300.0, 1000.0, 20.0)
    fighter = FighterBody(100.0, 250.0, 30.0, 50.0, group_id=1)  # standing on it
    probe = StatusProbe()
    world = make_world(
        [[block], [fighter]],
        [AnyPair(probe), CollisionKindNeutral(ReactionRebound())],
        gravity=0.002,
    )

    for _ in range(20):
        probe.flags.clear()
        assert len(world.step(16.0)) == 1
        assert probe.edges(fighter) == {"down", "on_ground"}


def test_standing_on_a_fighter_is_down_but_not_on_ground():
    """`on_ground` means the bottom edge rests on something immovable (a platform)."""
    lower = FighterBody(100.0, 300.0, 40.0, 40.0, group_id=1)
    upper = FighterBody(100.0, 250.0, 40.0, 40.0, group_id=2, vy=0.5)
    probe = StatusProbe()
    world = make_world([[lower], [upper]], [AnyPair(probe)])

    world.step(40.0)

    assert probe.edges(upper) == {"down"}
    assert probe.edges(lower) == {"up"}


def test_walking_into_a_wall_is_a_side_contact_not_ground():
    wall = PlatformBlock(300.0, 0.0, 20.0, 600.0)
    fighter = FighterBody(270.0, 100.0, 20.0, 50.0, group_id=1, vx=1.0)
    probe = StatusProbe()
    world = make_world([[wall], [fighter]], [AnyPair(probe)])

    world.step(20.0)

    assert probe.edges(fighter) == {"right"}
    assert probe.edges(wall) == {"left"}


@pytest.mark.parametrize(
    ("other_xy", "edge"),
    [
        ((136.0, 130.0), "right"),  # overlap 4 px in x, 10 px in y: x is the least penetration
        ((130.0, 136.0), "down"),  # overlap 10 px in x, 4 px in y
        ((64.0, 70.0), "left"),  # overlap 4 px in x from the left side
        ((70.0, 64.0), "up"),
    ],
)
def test_overlapping_sprites_touch_on_the_axis_of_least_penetration(other_xy, edge):
    """Deep overlaps (here >= 3 px on both axes, where the original engine set no flag at all)."""
    one = SpriteTemplate(100.0, 100.0, 40.0, 40.0)
    two = SpriteTemplate(*other_xy, 40.0, 40.0)
    probe = StatusProbe()
    world = make_world([[one], [two]], [AnyPair(probe)])

    contacts = world.step(16.0)

    assert [c.edge for c in contacts] == [edge]
    assert contacts[0].time_of_impact == 0.0
    assert contacts[0].depth == 4.0
    assert probe.edges(one) == {edge}
    assert probe.edges(two) == {OPPOSITE[edge]}


@pytest.mark.parametrize(("velocity", "edge"), [((-0.5, -0.1), "right"), ((-0.1, -0.5), "down")])
def test_equal_overlaps_go_to_the_axis_of_faster_relative_motion(velocity, edge):
    one = SpriteTemplate(100.0, 100.0, 40.0, 40.0)
    two = SpriteTemplate(135.0, 135.0, 40.0, 40.0, vx=velocity[0], vy=velocity[1])
    world = make_world([[one], [two]], [AnyPair(StatusProbe())])

    contacts = world.step(1.0)

    assert [c.edge for c in contacts] == [edge]


@pytest.mark.parametrize(
    ("other_xy", "edge"),
    [
        ((125.0, 110.0), "right"),  # y already overlaps; x closes at a quarter frame
        ((110.0, 130.0), "down"),  # x already overlaps; y closes at half a frame
        ((125.0, 130.0), "down"),  # both gaps: the face crossed last (y at 0.5 > x at 0.25)
        ((130.0, 125.0), "right"),
    ],
)
def test_diagonal_approach_touches_the_face_crossed_last(other_xy, edge):
    mover = SpriteTemplate(100.0, 100.0, 20.0, 20.0, vx=1.0, vy=1.0)
    target = SpriteTemplate(*other_xy, 40.0, 40.0)
    world = make_world([[mover], [target]], [AnyPair(StatusProbe())])

    contacts = world.step(20.0)

    assert [c.edge for c in contacts] == [edge]


@pytest.mark.parametrize(
    ("v_one", "v_two", "expected"),
    [
        (0.0, 0.0, 0),  # flush and still: resting side by side is not a contact
        (0.3, 0.3, 0),  # flush, moving together
        (-0.3, 0.0, 0),  # flush, moving apart
        (0.3, 0.0, 1),  # flush, closing: contact at once
    ],
)
def test_flush_sprites_touch_only_when_closing(v_one, v_two, expected):
    one = SpriteTemplate(100.0, 100.0, 40.0, 40.0, vx=v_one)
    two = SpriteTemplate(140.0, 100.0, 40.0, 40.0, vx=v_two)
    world = make_world([[one], [two]], [AnyPair(StatusProbe())])

    contacts = world.step(16.0)

    assert len(contacts) == expected
    if expected:
        assert contacts[0].time_of_impact == 0.0


def test_near_miss_is_not_a_contact():
    """No pixel tolerance: 2.5 px apart (inside the original's 3 px) is no contact."""
    one = SpriteTemplate(100.0, 100.0, 40.0, 40.0)
    two = SpriteTemplate(142.5, 100.0, 40.0, 40.0)
    three = SpriteTemplate(100.0, 142.5, 40.0, 40.0)
    world = make_world([[one], [two], [three]], [AnyPair(StatusProbe())])

    assert world.step(16.0) == []


def test_immovable_sprites_are_never_paired():
    one = PlatformBlock(100.0, 100.0, 40.0, 40.0)
    two = PlatformBlock(120.0, 120.0, 40.0, 40.0)
    world = make_world([[one], [two]], [AnyPair(StatusProbe())])

    assert world.step(16.0) == []
    assert world.collision.candidate_pairs() == []


# --- no tunnelling ----------------------------------------------------------------------------


def test_fighter_falling_at_5px_per_ms_lands_on_a_10px_block():
    gravity, dt = 0.002, 16.0
    block = PlatformBlock(0.0, 300.0, 1000.0, 10.0)
    fighter = FighterBody(100.0, 240.0, 30.0, 50.0, group_id=1, vy=5.0)  # bottom 10 px above
    world = make_world(
        [[block], [fighter]], [CollisionKindNeutral(ReactionRebound())], gravity=gravity
    )
    fall = (5.0 + gravity * dt) * dt  # this frame's increment: 80.5 px
    assert fighter.top + fall > block.bottom  # a test of end positions only would miss the block

    contacts = world.step(dt)

    assert [c.edge for c in contacts] == ["up"]
    assert fighter.bottom == block.top
    assert fighter.vy == 0.0
    for _ in range(50):  # and it stays there
        world.step(dt)
        assert fighter.bottom == block.top
        assert fighter.vy == 0.0


def test_fast_fighter_stops_at_a_thin_fighter():
    dt, distance = 16.0, 0.5
    fast = FighterBody(0.0, 100.0, 20.0, 20.0, group_id=1, vx=5.0)  # 80 px this frame
    thin = FighterBody(50.0, 100.0, 2.0, 20.0, group_id=2)
    world = make_world([[fast], [thin]], [CollisionKindEnemy(ReactionStop(distance=distance))])
    assert fast.left + 5.0 * dt > thin.right  # it would jump clean over the thin one
    toi = (thin.left - fast.right) / (5.0 * dt)  # 0.375: they meet at x = 30
    meet = fast.x + toi * 5.0 * dt

    world.step(dt)

    # equal masses: each backs off half of the distance
    assert fast.x == pytest.approx(meet - distance / 2, abs=1e-12)
    assert thin.x == pytest.approx(50.0 + distance / 2, abs=1e-12)
    assert thin.left - fast.right == pytest.approx(distance, abs=1e-12)
    assert (fast.vx, thin.vx) == (0.0, 0.0)


def test_fast_pusher_never_passes_a_thin_fighter():
    fast = FighterBody(0.0, 100.0, 20.0, 20.0, group_id=1, vx=5.0)
    thin = FighterBody(50.0, 100.0, 2.0, 20.0, group_id=2)
    world = make_world([[fast], [thin]], [CollisionKindEnemy(ReactionPush())], width=100000.0)

    for _ in range(100):
        world.step(16.0)
        assert fast.right <= thin.left + 1e-9
    assert fast.vx == pytest.approx(2.5) and thin.vx == pytest.approx(2.5)


def test_fighters_crossing_fast_bounce_instead_of_passing():
    left = FighterBody(100.0, 100.0, 10.0, 20.0, group_id=1, vx=5.0)
    right = FighterBody(160.0, 100.0, 10.0, 20.0, group_id=2, vx=-5.0)
    world = make_world([[left], [right]], [CollisionKindEnemy(ReactionMomentumConservation())])
    assert left.x + 80.0 > right.x - 80.0 + right.width  # without a swept test they swap sides

    contacts = world.step(16.0)

    assert len(contacts) == 1
    assert (left.vx, right.vx) == (-5.0, 5.0)
    assert left.right <= right.left
