"""Behaviour 6: teams (one call to add or remove a sprite) and the sort-and-sweep broad phase."""

from __future__ import annotations

import itertools
import random

import pytest

from vooga_env.physics import (
    Collision,
    CollisionKindEnemy,
    CollisionKindNeutral,
    FighterBody,
    FightPhysicsEngine,
    MotionAction,
    PlatformBlock,
    ReactionStop,
    SpriteGroupTemplate,
    SpriteTemplate,
    World,
)
from vooga_env.physics.contact import find_contact

from .helpers import AnyPair, StatusProbe, make_world


def test_the_original_team_layout():
    group = SpriteGroupTemplate()
    blocks = [PlatformBlock(0.0, 500.0, 400.0, 20.0), PlatformBlock(400.0, 500.0, 400.0, 20.0)]
    fighters = [FighterBody(100.0, 450.0, 30.0, 50.0, group_id=i) for i in range(3)]
    others = [SpriteTemplate(10.0 * i, 0.0, 5.0, 5.0) for i in range(2)]

    assert group.add_platform_block_array(blocks) == 0
    assert group.add_fighter_sprite_array(fighters) == [1, 2, 3]  # one team per fighter
    assert group.add_sprite_array(others) == 4
    assert group.teams == (tuple(blocks), *((f,) for f in fighters), tuple(others))
    assert len(group) == 7
    assert list(group.sprites()) == [*blocks, *fighters, *others]
    assert [group.team_of(f) for f in fighters] == [1, 2, 3]


def test_spawning_a_projectile_is_one_call():
    fighter = FighterBody(100.0, 100.0, 30.0, 30.0, group_id=1)
    world = make_world([[fighter]], [AnyPair(StatusProbe())])
    projectile = SpriteTemplate(200.0, 105.0, 10.0, 10.0, vx=-1.0, gravity_scale=0.0)

    world.group.add_sprite(projectile, len(world.group.teams))  # a new team

    contacts = world.step(80.0)
    assert [(c.sprite, c.other) for c in contacts] == [(fighter, projectile)]


def test_a_sprite_added_to_an_existing_team_is_a_teammate():
    a = FighterBody(100.0, 100.0, 30.0, 30.0, group_id=1)
    b = FighterBody(300.0, 100.0, 30.0, 30.0, group_id=2)
    world = make_world([[a], [b]], [AnyPair(StatusProbe())])
    clone = FighterBody(110.0, 100.0, 30.0, 30.0, group_id=1)  # overlaps a

    world.group.add_sprite(clone, world.group.team_of(a))

    assert world.group.teams[0] == (a, clone)
    assert world.step(16.0) == []


def test_removing_a_sprite_is_one_call_and_it_no_longer_collides():
    a = FighterBody(100.0, 100.0, 30.0, 30.0, group_id=1)
    b = FighterBody(120.0, 100.0, 30.0, 30.0, group_id=2)
    world = make_world([[a], [b]], [AnyPair(StatusProbe())])
    assert len(world.step(1.0)) == 1

    world.group.remove_sprite(b)

    assert b not in world.group
    assert world.group.teams == ((a,), ())  # the team stays, so indices hold
    assert world.step(1.0) == []
    x_before = b.x
    world.step(1.0)
    assert b.x == x_before  # no longer stepped
    with pytest.raises(ValueError, match="not in this world"):
        world.step(1.0, [MotionAction.left(b)])


def test_a_fighter_splitting_in_two():
    enemy = FighterBody(200.0, 100.0, 30.0, 30.0, group_id="enemy")
    whole = FighterBody(100.0, 100.0, 60.0, 30.0, group_id="hero")
    world = make_world([[enemy], [whole]], [AnyPair(StatusProbe())])
    team = world.group.team_of(whole)

    world.group.remove_sprite(whole)
    left = FighterBody(100.0, 100.0, 30.0, 30.0, group_id="hero", vx=-0.1)
    right = FighterBody(130.0, 100.0, 30.0, 30.0, group_id="hero", vx=1.0)
    world.group.add_sprite(left, team)
    world.group.add_sprite(right, team)

    contacts = world.step(60.0)  # the halves touch each other (same team) and right hits enemy
    assert [(c.sprite, c.other) for c in contacts] == [(enemy, right)]


def test_collision_group_and_kinds_can_be_changed():
    a = FighterBody(100.0, 100.0, 30.0, 30.0, group_id=1)
    b = FighterBody(120.0, 100.0, 30.0, 30.0, group_id=2)
    world = make_world([[a, b]])
    assert world.step(1.0) == []  # teammates

    group = SpriteGroupTemplate()
    group.add_fighter_sprite_array([a, b])
    world.collision.collision_group = group
    assert world.group is group
    probe = StatusProbe()
    kind = AnyPair(probe)
    world.collision.add_collision_kind(kind)
    assert world.collision.kinds == (kind,)
    assert len(world.step(1.0)) == 1
    assert len(probe.calls) == 1

    world.collision.remove_collision_kind(kind)
    assert world.collision.kinds == ()
    world.step(1.0)
    assert len(probe.calls) == 1


def test_group_rejects_duplicates_and_unknown_sprites():
    group = SpriteGroupTemplate()
    sprite = SpriteTemplate(0.0, 0.0, 1.0, 1.0)
    group.add_sprite_array([sprite])
    with pytest.raises(ValueError, match="already in team 0"):
        group.add_sprite(sprite, 1)
    with pytest.raises(ValueError, match="same sprite twice"):
        group.add_sprite_array([SpriteTemplate(0.0, 0.0, 1.0, 1.0)] * 2)
    with pytest.raises(ValueError, match="not in this group"):
        group.remove_sprite(SpriteTemplate(0.0, 0.0, 1.0, 1.0))
    with pytest.raises(IndexError, match=r"team_index must be in 0\.\.1.*got 5"):
        group.add_sprite(SpriteTemplate(0.0, 0.0, 1.0, 1.0), 5)
    with pytest.raises(TypeError, match="fighters must hold FighterBody"):
        group.add_fighter_sprite_array([SpriteTemplate(0.0, 0.0, 1.0, 1.0)])
    with pytest.raises(TypeError, match="blocks must hold PlatformBlock"):
        group.add_platform_block_array([FighterBody(0.0, 0.0, 1.0, 1.0, group_id=1)])


# --- broad phase ------------------------------------------------------------------------------


def random_scene(n: int, seed: int, width: float, teams: int = 4):
    rng = random.Random(seed)
    group = SpriteGroupTemplate()
    blocks = [
        PlatformBlock(
            rng.uniform(0, width), rng.uniform(0, 560), rng.uniform(10, 120), rng.uniform(5, 30)
        )
        for _ in range(max(1, n // 10))
    ]
    group.add_platform_block_array(blocks)
    movers = [
        FighterBody(
            rng.uniform(0, width),
            rng.uniform(0, 560),
            rng.uniform(5, 40),
            rng.uniform(5, 40),
            group_id=i % teams,
            vx=rng.uniform(-2, 2),
            vy=rng.uniform(-2, 2),
        )
        for i in range(n - len(blocks))
    ]
    for team in range(teams):
        group.add_sprite_array([m for m in movers if m.group_id == team])
    engine = FightPhysicsEngine(width, 600.0, gravity=0.002)
    return World(
        engine, group, [CollisionKindEnemy(ReactionStop()), CollisionKindNeutral(ReactionStop())]
    )


def brute_force_pairs(world: World, dt: float) -> set[tuple[int, int]]:
    """Every pair of sprites of different teams, one movable, whose swept x ranges meet."""
    group = world.group
    sprites = [s for s in group.sprites() if s.active]
    pairs = set()
    for one, two in itertools.combinations(sprites, 2):
        if group.team_of(one) == group.team_of(two) or not (one.movable or two.movable):
            continue
        lo1, hi1 = one.x + min(one.increment_x, 0.0), one.right + max(one.increment_x, 0.0)
        lo2, hi2 = two.x + min(two.increment_x, 0.0), two.right + max(two.increment_x, 0.0)
        if lo1 <= hi2 and lo2 <= hi1:
            pairs.add((id(one), id(two)))
    return pairs


@pytest.mark.parametrize(("n", "seed"), [(10, 0), (60, 1), (200, 2)])
def test_candidate_pairs_are_exactly_the_swept_x_overlaps(n, seed):
    dt = 16.0
    world = random_scene(n, seed, width=6.0 * n + 100.0)
    for _ in range(5):
        for sprite in world.group.sprites():
            world.engine.integrate(sprite, dt)  # pending increments, as in a step
        candidates = world.collision.candidate_pairs()
        ids = [(id(a), id(b)) for a, b in candidates]
        assert len(ids) == len(set(ids))  # no pair twice
        assert set(ids) == brute_force_pairs(world, dt)
        order = {id(s): i for i, s in enumerate(world.group.sprites())}
        for a, b in candidates:  # each pair in team order
            assert world.group.team_of(a) < world.group.team_of(b)
        assert ids == sorted(ids, key=lambda p: (order[p[0]], order[p[1]]))
        # the broad phase never drops a pair that the narrow phase would find
        for one, two in itertools.combinations(world.group.sprites(), 2):
            if (
                find_contact(one, two, dt) is not None
                and world.group.team_of(one) != world.group.team_of(two)
                and (one.movable or two.movable)
            ):
                assert (id(one), id(two)) in set(ids) or (id(two), id(one)) in set(ids)
        for sprite in world.group.sprites():
            sprite.increment_x = sprite.increment_y = 0.0
        world.step(dt)


def test_broad_phase_is_far_below_quadratic_for_1000_spread_sprites():
    n = 1000
    world = random_scene(n, seed=3, width=50.0 * n)
    for sprite in world.group.sprites():
        world.engine.integrate(sprite, 16.0)

    candidates = len(world.collision.candidate_pairs())

    assert candidates < 0.01 * n * (n - 1) / 2


def test_collision_requires_its_parts():
    group = SpriteGroupTemplate()
    engine = FightPhysicsEngine(100.0, 100.0)
    with pytest.raises(TypeError, match="group must be a SpriteGroupTemplate"):
        Collision([], [], engine)
    with pytest.raises(TypeError, match="engine must be a PhysicsEngine"):
        Collision(group, [], "engine")
