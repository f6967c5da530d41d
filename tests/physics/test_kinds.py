"""Collision kinds: which pairs a list of reactions applies to, and in which order it gets them."""

from __future__ import annotations

import pytest

from vooga_env.physics import (
    CollisionKindCustom,
    CollisionKindEnemy,
    CollisionKindFriends,
    CollisionKindNeutral,
    FighterBody,
    PlatformBlock,
    Reaction,
    ReactionPush,
    ReactionStop,
    SpriteTemplate,
)
from vooga_env.physics.engine import PhysicsEngine

from .helpers import make_world

IS = CollisionKindCustom.Type.IS
SUB = CollisionKindCustom.Type.SUB
SUPER = CollisionKindCustom.Type.SUPER
AND = CollisionKindCustom.Relation.AND
OR = CollisionKindCustom.Relation.OR


class Hero(FighterBody):
    pass


class Villain(FighterBody):
    pass


class Boulder(SpriteTemplate):
    pass


def fighter(cls=FighterBody, group_id=1):
    return cls(0.0, 0.0, 10.0, 10.0, group_id=group_id)


def block():
    return PlatformBlock(0.0, 0.0, 10.0, 10.0)


def boulder():
    return Boulder(0.0, 0.0, 10.0, 10.0)


class Recorder(Reaction):
    """Remembers the order in which it was handed each pair."""

    def __init__(self, log: list, name: str = "") -> None:
        self.log, self.name = log, name

    def act(
        self, sprite_one: SpriteTemplate, sprite_two: SpriteTemplate, engine: PhysicsEngine
    ) -> None:
        self.log.append((self.name, sprite_one, sprite_two))


def test_friends_enemy_neutral():
    red, red2, blue = fighter(group_id="red"), fighter(group_id="red"), fighter(group_id="blue")
    friends, enemy, neutral = CollisionKindFriends(), CollisionKindEnemy(), CollisionKindNeutral()

    assert friends.is_this_kind(red, red2) and not friends.is_this_kind(red, blue)
    assert enemy.is_this_kind(red, blue) and not enemy.is_this_kind(red, red2)
    for kind in (friends, enemy):
        assert not kind.is_this_kind(red, block()) and not kind.is_this_kind(boulder(), red)
    assert neutral.is_this_kind(red, block()) and neutral.is_this_kind(block(), blue)
    assert neutral.is_this_kind(boulder(), red) and neutral.is_this_kind(boulder(), block())
    assert not neutral.is_this_kind(red, blue) and not neutral.is_this_kind(red, red2)


@pytest.mark.parametrize(
    ("spec", "pair", "expected"),
    [
        # IS: exactly that class
        ((FighterBody, IS, AND, PlatformBlock, IS), (fighter, block), True),
        ((FighterBody, IS, AND, PlatformBlock, IS), (lambda: fighter(Hero), block), False),
        ((FighterBody, IS, AND, PlatformBlock, IS), (fighter, boulder), False),
        # SUB: that class or a subclass
        ((FighterBody, SUB, AND, PlatformBlock, IS), (lambda: fighter(Hero), block), True),
        ((FighterBody, SUB, AND, PlatformBlock, IS), (fighter, block), True),
        ((SpriteTemplate, SUB, AND, SpriteTemplate, SUB), (boulder, block), True),
        ((Hero, SUB, AND, PlatformBlock, IS), (fighter, block), False),
        # SUPER: that class or a superclass
        ((Hero, SUPER, AND, PlatformBlock, IS), (fighter, block), True),
        ((Hero, SUPER, AND, PlatformBlock, IS), (lambda: fighter(Hero), block), True),
        ((Hero, SUPER, AND, PlatformBlock, IS), (lambda: fighter(Villain), block), False),
        (
            (Boulder, SUPER, AND, FighterBody, IS),
            (lambda: SpriteTemplate(0, 0, 1, 1), fighter),
            True,
        ),
        # AND needs both, OR either
        ((FighterBody, IS, AND, PlatformBlock, IS), (fighter, fighter), False),
        ((FighterBody, IS, OR, PlatformBlock, IS), (fighter, lambda: fighter(group_id=2)), True),
        ((FighterBody, IS, OR, PlatformBlock, IS), (boulder, block), True),
        ((FighterBody, IS, OR, PlatformBlock, IS), (boulder, boulder), False),
        ((Hero, IS, OR, Villain, IS), (fighter, fighter), False),
    ],
)
def test_custom_kind_types_and_relations(spec, pair, expected):
    kind = CollisionKindCustom()
    kind.set_type(*spec)
    one, two = pair[0](), pair[1]()

    assert kind.is_this_kind(one, two) is expected
    assert kind.is_this_kind(two, one) is expected  # symmetric in the pair's order


@pytest.mark.parametrize("block_team_first", [True, False])
def test_custom_kind_hands_the_sprites_over_in_the_order_of_its_spec(block_team_first):
    log: list = []
    kind = CollisionKindCustom(Recorder(log))
    kind.set_type(FighterBody, SUB, AND, PlatformBlock, IS)
    hero = Hero(100.0, 100.0, 20.0, 20.0, group_id=1, vy=1.0)
    floor = PlatformBlock(0.0, 130.0, 1000.0, 20.0)
    teams = [[floor], [hero]] if block_team_first else [[hero], [floor]]
    world = make_world(teams, [kind])

    world.step(20.0)

    assert log == [("", hero, floor)]


def test_custom_kind_without_set_type_raises_a_clear_error():
    kind = CollisionKindCustom(ReactionPush())
    with pytest.raises(RuntimeError, match=r"set_type"):
        kind.is_this_kind(fighter(), block())

    a = FighterBody(100.0, 100.0, 20.0, 20.0, group_id=1)
    b = FighterBody(110.0, 100.0, 20.0, 20.0, group_id=2)
    world = make_world([[a], [b]], [kind])
    with pytest.raises(RuntimeError, match=r"set_type"):
        world.step(16.0)


def test_reactions_run_in_list_order_and_can_be_edited():
    log: list = []
    first, second, third = Recorder(log, "first"), Recorder(log, "second"), Recorder(log, "third")
    kind = CollisionKindEnemy([first, second])
    a = FighterBody(100.0, 100.0, 20.0, 20.0, group_id=1)
    b = FighterBody(110.0, 100.0, 20.0, 20.0, group_id=2)
    world = make_world([[a], [b]], [kind])

    world.step(1.0)
    assert [name for name, _, _ in log] == ["first", "second"]

    log.clear()
    kind.add_reaction(third)
    kind.remove_reaction(first)
    assert kind.reactions == (second, third)
    world.step(1.0)
    assert [name for name, _, _ in log] == ["second", "third"]

    log.clear()
    kind.set_reaction(first)
    assert kind.reactions == (first,)
    world.step(1.0)
    assert [name for name, _, _ in log] == ["first"]

    with pytest.raises(ValueError, match="not in"):
        kind.remove_reaction(ReactionStop())


def test_several_matching_kinds_all_run():
    log: list = []
    a = FighterBody(100.0, 100.0, 20.0, 20.0, group_id=1)
    rock = PlatformBlock(110.0, 100.0, 20.0, 20.0)
    custom = CollisionKindCustom(Recorder(log, "custom"))
    custom.set_type(FighterBody, IS, AND, PlatformBlock, IS)
    world = make_world(
        [[a], [rock]],
        [
            CollisionKindNeutral(Recorder(log, "neutral")),
            custom,
            CollisionKindEnemy(Recorder(log, "enemy")),
        ],
    )

    world.step(1.0)

    assert sorted(name for name, _, _ in log) == ["custom", "neutral"]
