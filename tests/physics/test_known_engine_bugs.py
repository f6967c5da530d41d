"""Engine defects these tests found and that need a design decision, not a one-line fix.

Each test states the behaviour the issue asks for and fails today; they are marked strict xfail
so that the suite stays green while the defect is open and turns red the day it is fixed (then
drop the mark). The open defects share one root cause: contacts are found once per frame from the
pending increments and each pair's reaction is worked out on its own, so what one reaction does to
a sprite is never checked against that sprite's other contacts (no iteration, no axis ordering).
"""

from __future__ import annotations

import pytest

from vooga_env.physics import (
    CollisionKindEnemy,
    CollisionKindNeutral,
    FighterBody,
    MotionAction,
    PlatformBlock,
    ReactionPush,
    ReactionRebound,
)

from .helpers import make_world

GRAVITY, DT = 0.002, 16.0


@pytest.mark.xfail(
    strict=True,
    raises=AssertionError,
    reason="ghost edge: a fighter walking over the seam of two floor blocks hits the second "
    "block's side face (swept test: the side is crossed after the top, which it was already "
    "touching): a walking fighter loses a frame's step, a sliding one stops dead (vx zeroed)",
)
@pytest.mark.parametrize("how", ["walking", "sliding"])
def test_crossing_the_seam_between_two_floor_blocks(how):
    left = PlatformBlock(0.0, 400.0, 133.0, 20.0)
    right = PlatformBlock(133.0, 400.0, 300.0, 20.0)
    fighter = FighterBody(
        90.0, 350.0, 30.0, 50.0, group_id=1, speed=0.3, vx=0.2 if how == "sliding" else 0.0
    )
    world = make_world(
        [[left, right], [fighter]], [CollisionKindNeutral(ReactionRebound())], gravity=GRAVITY
    )
    step = 0.3 * DT * 0.5 if how == "walking" else 0.2 * DT

    for _ in range(20):
        x = fighter.x
        world.step(DT, [MotionAction.right(fighter)] if how == "walking" else [])
        assert fighter.x - x == pytest.approx(step)
        assert fighter.bottom == left.top
    assert fighter.left > right.left  # it got across


def test_friction_on_two_blocks_never_reverses_sliding():
    left = PlatformBlock(0.0, 400.0, 133.0, 20.0)
    right = PlatformBlock(133.0, 400.0, 300.0, 20.0)
    fighter = FighterBody(120.0, 350.0, 30.0, 50.0, group_id=1, vx=0.01)  # on both blocks
    world = make_world(
        [[left, right], [fighter]],
        [CollisionKindNeutral(ReactionRebound(friction=0.001))],
        gravity=GRAVITY,
    )

    for _ in range(10):
        world.step(DT)
        assert fighter.vx >= 0.0
    assert fighter.vx == 0.0


@pytest.mark.xfail(
    strict=True,
    raises=AssertionError,
    reason="a sprite pushed into a wall: the push's shift is never checked against the wall "
    "(the pushed sprite had no motion of its own, so no wall contact was found), so it ends "
    "inside the wall on alternate frames and the pair jitters",
)
def test_pushing_a_fighter_into_a_wall_block():
    floor = PlatformBlock(0.0, 500.0, 1000.0, 20.0)
    wall = PlatformBlock(600.0, 300.0, 20.0, 200.0)
    a = FighterBody(400.0, 450.0, 40.0, 50.0, group_id=1)
    b = FighterBody(500.0, 450.0, 40.0, 50.0, group_id=2)
    world = make_world(
        [[floor, wall], [a], [b]],
        [CollisionKindEnemy(ReactionPush()), CollisionKindNeutral(ReactionRebound())],
        gravity=GRAVITY,
    )
    for _ in range(150):
        world.step(DT, [MotionAction.right(a)])
        assert b.right <= wall.left + 1e-9  # never inside the wall

    settled = (a.x, b.x)
    for _ in range(10):  # pinned: nothing moves any more
        world.step(DT, [MotionAction.right(a)])
        assert (a.x, b.x) == settled
    assert b.right == pytest.approx(wall.left)
    assert a.right == pytest.approx(b.left, abs=1e-6)


@pytest.mark.xfail(
    strict=True,
    raises=AssertionError,
    reason="a fighter standing on a grounded fighter sinks into it: the contact counts the lower "
    "one's gravity increment that the floor cancels, and separation gives the grounded one half "
    "of the overlap, so the upper one jitters 0.3-0.8 px deep",
)
def test_fighter_rests_on_a_grounded_fighter_without_sinking():
    floor = PlatformBlock(0.0, 500.0, 1000.0, 20.0)
    below = FighterBody(100.0, 450.0, 40.0, 50.0, group_id=2)
    above = FighterBody(100.0, 380.0, 40.0, 46.0, group_id=1)
    world = make_world(
        [[floor], [above], [below]],
        [CollisionKindEnemy(ReactionPush()), CollisionKindNeutral(ReactionRebound())],
        gravity=GRAVITY,
    )
    for _ in range(100):
        world.step(DT)
    for _ in range(20):
        world.step(DT)
        assert below.bottom == floor.top
        assert above.bottom == pytest.approx(below.top, abs=1e-9)
        assert above.vy == 0.0
