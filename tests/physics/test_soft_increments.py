"""Behaviour 2: soft increments, each pair once per frame, results independent of listing order."""

from __future__ import annotations

import itertools
from collections import Counter

import pytest

from vooga_env.physics import (
    CollisionKindCustom,
    CollisionKindEnemy,
    CollisionKindFriends,
    CollisionKindNeutral,
    FighterBody,
    MotionAction,
    PlatformBlock,
    Reaction,
    ReactionMomentumConservation,
    ReactionPunch,
    ReactionPush,
    ReactionRebound,
    ReactionStop,
    SpriteTemplate,
)
from vooga_env.physics.engine import PhysicsEngine

from .helpers import exact_state, make_world

DT = 16.0  # ms


class CountingReaction(Reaction):
    """Counts how often each unordered pair is acted on."""

    def __init__(self) -> None:
        self.pairs: Counter[frozenset[int]] = Counter()

    def act(
        self, sprite_one: SpriteTemplate, sprite_two: SpriteTemplate, engine: PhysicsEngine
    ) -> None:
        self.pairs[frozenset((id(sprite_one), id(sprite_two)))] += 1


def test_collided_sprite_takes_the_reaction_result_the_other_its_motion():
    wall = PlatformBlock(100.0, 0.0, 20.0, 600.0)
    runner = FighterBody(75.0, 300.0, 20.0, 40.0, group_id=1, speed=1.0)  # right edge at 95
    free = FighterBody(500.0, 300.0, 20.0, 40.0, group_id=2, speed=1.0)
    world = make_world([[wall], [runner], [free]], [CollisionKindNeutral(ReactionRebound())])
    step = 1.0 * 20.0 * 1.0 * 0.5  # speed * elapsed * vector * speed_factor: 10 px

    world.step(20.0, [MotionAction.right(runner), MotionAction.right(free)])

    # the runner's motion would end at x = 85 (5 px into the wall); the reaction stops it
    assert runner.x == wall.left - runner.width
    assert runner.x != 75.0 + step
    assert free.x == 500.0 + step
    for sprite in (wall, runner, free):  # the update resets everything pending
        assert not sprite.status.collided
        assert sprite.status.contacts == {}
        assert (sprite.increment_x, sprite.increment_y) == (0.0, 0.0)


def test_motion_and_reaction_are_not_summed():
    """A reaction that stops a sprite replaces its motion instead of adding to it."""
    mover = FighterBody(0.0, 100.0, 20.0, 20.0, group_id=1, vx=1.0)
    target = FighterBody(30.0, 100.0, 20.0, 20.0, group_id=2)
    world = make_world([[mover], [target]], [CollisionKindEnemy(ReactionStop(distance=0.0))])

    world.step(20.0)  # 20 px of motion; they meet after 10 px, at half the frame

    assert mover.right == pytest.approx(target.left, abs=1e-12)
    assert mover.x == pytest.approx(10.0, abs=1e-12)  # not 0 + 20 + anything
    assert (mover.vx, target.vx) == (0.0, 0.0)


def test_contact_without_a_matching_kind_keeps_the_motion():
    one = FighterBody(0.0, 100.0, 20.0, 20.0, group_id=1, vx=1.0)
    two = FighterBody(30.0, 100.0, 20.0, 20.0, group_id=2)
    world = make_world([[one], [two]], [CollisionKindFriends(ReactionStop())])  # enemies: no match

    contacts = world.step(20.0)

    assert len(contacts) == 1
    assert one.x == 20.0
    assert one.vx == 1.0


def test_each_colliding_pair_is_handled_once_per_frame():
    counter_enemy, counter_neutral = CountingReaction(), CountingReaction()
    floor = PlatformBlock(0.0, 400.0, 1000.0, 20.0)
    # three fighters standing on the floor: a overlaps b, b overlaps c, a and c apart
    a = FighterBody(100.0, 360.0, 30.0, 40.0, group_id="a")
    b = FighterBody(125.0, 360.0, 30.0, 40.0, group_id="b")
    c = FighterBody(150.0, 360.0, 30.0, 40.0, group_id="c")
    world = make_world(
        [[floor], [a], [b], [c]],
        [CollisionKindEnemy(counter_enemy), CollisionKindNeutral(counter_neutral)],
        gravity=0.002,
    )

    for _ in range(5):
        counter_enemy.pairs.clear()
        counter_neutral.pairs.clear()
        contacts = world.step(DT)
        pairs = Counter(frozenset((id(k.sprite), id(k.other))) for k in contacts)
        assert set(pairs.values()) == {1}  # each contact reported once
        assert counter_enemy.pairs == Counter(
            {frozenset((id(a), id(b))): 1, frozenset((id(b), id(c))): 1}
        )
        assert counter_neutral.pairs == Counter(
            {frozenset((id(floor), id(s))): 1 for s in (a, b, c)}
        )
        assert len(contacts) == 5


def test_sprites_of_one_team_are_never_paired():
    counter = CountingReaction()
    a = FighterBody(100.0, 100.0, 30.0, 30.0, group_id=1, vx=0.5)
    b = FighterBody(110.0, 100.0, 30.0, 30.0, group_id=1)
    world = make_world([[a, b]], [CollisionKindFriends(counter), CollisionKindEnemy(counter)])

    contacts = world.step(DT)

    assert contacts == []
    assert counter.pairs == Counter()
    assert a.x == 100.0 + 0.5 * DT  # passes through its teammate


# --- order independence -----------------------------------------------------------------------


def three_body_scene():
    """Fighter `a`, on the floor, walks right and pushes fighter `b` into a wall block."""
    sprites = {
        "floor": PlatformBlock(0.0, 500.0, 1000.0, 20.0),
        "wall": PlatformBlock(600.0, 300.0, 20.0, 200.0),
        "a": FighterBody(400.0, 450.0, 40.0, 50.0, group_id=1, mass=150.0),
        "b": FighterBody(500.0, 450.0, 40.0, 50.0, group_id=2, mass=250.0),
    }
    teams = [["floor", "wall"], ["a"], ["b"]]

    def kinds():
        return [CollisionKindEnemy(ReactionPush()), CollisionKindNeutral(ReactionRebound())]

    def actions(frame, s):
        return [MotionAction.right(s["a"])]

    return sprites, teams, kinds, actions


def brawl_scene():
    """A pit with three fighters and a rock: every symmetric reaction, many contacts a frame."""
    sprites = {
        "floor": PlatformBlock(0.0, 500.0, 1000.0, 20.0),
        "ledge": PlatformBlock(330.0, 400.0, 60.0, 10.0),
        "left_wall": PlatformBlock(200.0, 200.0, 20.0, 300.0),
        "right_wall": PlatformBlock(520.0, 200.0, 20.0, 300.0),
        "p": FighterBody(230.0, 380.0, 40.0, 60.0, group_id="red", vx=0.3, vy=-0.1),
        "q": FighterBody(340.0, 440.0, 40.0, 60.0, group_id="blue", mass=320.0, vx=-0.2),
        "r": FighterBody(460.0, 300.0, 30.0, 60.0, group_id="red", mass=90.0, vx=0.4),
        "rock": SpriteTemplate(350.0, 250.0, 15.0, 15.0, mass=50.0, vx=0.05, vy=0.3),
    }
    teams = [["floor", "ledge", "left_wall", "right_wall"], ["p"], ["q"], ["r"], ["rock"]]

    def kinds():
        custom = CollisionKindCustom(ReactionStop(distance=0.5))
        custom.set_type(
            SpriteTemplate,
            CollisionKindCustom.Type.IS,
            CollisionKindCustom.Relation.AND,
            FighterBody,
            CollisionKindCustom.Type.IS,
        )
        return [
            CollisionKindEnemy([ReactionPush(), ReactionMomentumConservation()]),
            CollisionKindFriends(ReactionPunch(left=220.0, right=520.0, up=100.0, down=500.0)),
            CollisionKindNeutral(ReactionRebound(up=False, left=True, distance=2.0, friction=5e-4)),
            custom,
        ]

    def actions(frame, s):
        phase = (frame // 25) % 4
        vectors = [(1.0, 0.0), (-1.0, -1.5), (-1.0, 0.0), (1.0, -1.5)]
        return [
            MotionAction(s["p"], *vectors[phase]),
            MotionAction(s["q"], *vectors[(phase + 2) % 4]),
            MotionAction(s["r"], *vectors[(phase + 1) % 4]),
        ]

    return sprites, teams, kinds, actions


def run_scene(scene, team_order, reverse_members, reverse_kinds, frames):
    sprites, teams, kinds, actions = scene()
    ordered_teams = []
    for index in team_order:
        members = [sprites[name] for name in teams[index]]
        ordered_teams.append(members[::-1] if reverse_members else members)
    kind_list = kinds()
    world = make_world(
        ordered_teams, kind_list[::-1] if reverse_kinds else kind_list, gravity=0.002
    )
    names = sorted(sprites)
    trace, contact_count = [], 0
    for frame in range(frames):
        frame_actions = actions(frame, sprites)
        contact_count += len(
            world.step(DT, frame_actions[::-1] if reverse_kinds else frame_actions)
        )
        trace.append(exact_state([sprites[name] for name in names]))
    return trace, contact_count, sprites


@pytest.mark.parametrize("scene", [three_body_scene, brawl_scene], ids=["three_body", "brawl"])
def test_outcome_does_not_depend_on_team_sprite_or_kind_order(scene):
    frames = 400
    teams = scene()[1]
    base_order = list(range(len(teams)))
    reference, contacts, sprites = run_scene(scene, base_order, False, False, frames)
    assert contacts > frames  # the scene really is full of contacts
    orders = list(itertools.permutations(base_order))
    # every team order for the small scene; a spread of them for the big one
    orders = orders if len(orders) <= 6 else orders[:: max(1, len(orders) // 12)]
    for order in orders:
        for reverse_members, reverse_kinds in ((False, False), (True, False), (False, True)):
            trace, _, _ = run_scene(scene, list(order), reverse_members, reverse_kinds, frames)
            for frame, (expected, got) in enumerate(zip(reference, trace, strict=True)):
                assert got == expected, (
                    f"team order {order}, reversed members {reverse_members}, "
                    f"reversed kinds {reverse_kinds}: differs at frame {frame}"
                )


def test_three_body_scene_pushes_b_to_the_wall():
    """The order-independence scene really does what it says: `a` drives `b` to the wall."""
    _, _, sprites = run_scene(three_body_scene, [0, 1, 2], False, False, 400)
    a, b, wall, floor = sprites["a"], sprites["b"], sprites["wall"], sprites["floor"]
    assert b.x > 540.0  # moved from 500 towards the wall at 600
    assert b.right >= wall.left - 1e-9  # and reached it
    assert a.x < b.x
    assert a.bottom == floor.top and b.bottom == floor.top  # both still stand on the floor


@pytest.mark.parametrize("size", [(40.0, 40.0), (10.0, 60.0)])
def test_coincident_sprites_separate_the_same_way_in_any_team_order(size):
    """Centres on top of each other and no motion: no geometry says who goes which way, yet the
    result may not depend on which team is listed first."""

    def run(order):
        one = FighterBody(300.0, 300.0, *size, group_id=1)
        two = FighterBody(300.0, 300.0, *size, group_id=2)
        teams = [[one], [two]]
        world = make_world([teams[i] for i in order], [CollisionKindEnemy(ReactionPush())])
        for _ in range(3):
            world.step(DT)
        return exact_state([one, two]), one, two

    first, one, two = run([0, 1])
    second, _, _ = run([1, 0])
    assert first == second
    assert abs(one.x - two.x) + abs(one.y - two.y) > 0.0  # they were pushed apart


def test_many_reaction_shifts_on_one_sprite_add_up_the_same_in_any_order():
    """A sprite pushed apart from four partners at once, where partial sums cross a power of two
    (x, y near 128 px): the shifts must be summed exactly, or their order (the order of teams)
    changes the last bit."""

    def run(order):
        bx, by = 127.95, 127.9
        sprites = [
            FighterBody(bx, by, 30.1, 30.3, group_id="m", mass=170.3),
            FighterBody(bx - 29.3, by + 1.1, 30.0, 30.0, group_id="a", mass=30.7, vx=0.011),
            FighterBody(bx + 29.3, by - 1.1, 30.0, 30.0, group_id="b", mass=1e-3, vx=-0.013),
            FighterBody(bx + 1.3, by - 29.1, 30.0, 30.0, group_id="c", mass=9.1e3, vy=0.017),
            FighterBody(bx - 0.9, by + 29.7, 30.0, 30.0, group_id="d", mass=0.37, vy=-0.019),
        ]
        teams = [[s] for s in sprites]
        world = make_world(
            [teams[i] for i in order],
            [CollisionKindEnemy([ReactionMomentumConservation(), ReactionPush()])],
        )
        contacts = 0
        for _ in range(3):
            contacts += len(world.step(7.3))
        return exact_state(sprites), contacts

    reference, contacts = run(range(5))
    assert contacts >= 4
    for order in itertools.permutations(range(5)):
        assert run(order)[0] == reference, order
