"""Invariants over random scenes (hypothesis): finite state, no tunnelling, momentum, determinism,
order independence, and a broad phase that never drops a contact."""

from __future__ import annotations

import itertools
import math
import random
from dataclasses import dataclass

import pytest
from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st

from vooga_env.physics import (
    CollisionKindCustom,
    CollisionKindEnemy,
    CollisionKindFriends,
    CollisionKindNeutral,
    FighterBody,
    MotionAction,
    PlatformBlock,
    ReactionForce,
    ReactionMomentumConservation,
    ReactionPunch,
    ReactionPush,
    ReactionRebound,
    ReactionStop,
    SpriteTemplate,
)
from vooga_env.physics.contact import find_contact

from .helpers import all_finite, exact_state, make_world

SETTINGS = settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.too_slow])
WIDTH, HEIGHT = 800.0, 600.0


def finite(low: float, high: float) -> st.SearchStrategy[float]:
    return st.floats(low, high, allow_nan=False, allow_infinity=False)


@dataclass(frozen=True)
class Spec:
    kind: str  # "fighter", "block" or "plain"
    x: float
    y: float
    width: float
    height: float
    mass: float
    vx: float
    vy: float
    team: int
    group_id: int

    def make(self):
        if self.kind == "block":
            return PlatformBlock(self.x, self.y, self.width, self.height)
        if self.kind == "fighter":
            return FighterBody(
                self.x,
                self.y,
                self.width,
                self.height,
                group_id=self.group_id,
                mass=self.mass,
                vx=self.vx,
                vy=self.vy,
            )
        return SpriteTemplate(
            self.x, self.y, self.width, self.height, mass=self.mass, vx=self.vx, vy=self.vy
        )


specs = st.builds(
    Spec,
    kind=st.sampled_from(["fighter", "fighter", "fighter", "block", "plain"]),
    x=finite(-20.0, WIDTH),
    y=finite(-20.0, HEIGHT),
    width=finite(0.5, 120.0),
    height=finite(0.5, 120.0),
    mass=finite(1.0, 1000.0),
    vx=finite(-3.0, 3.0),
    vy=finite(-3.0, 3.0),
    team=st.integers(0, 3),
    group_id=st.integers(0, 1),
)
scenes = st.lists(specs, min_size=2, max_size=9)

# Reactions that treat their two sprites alike, so a scene's outcome may not depend on order.
SYMMETRIC = {
    "momentum": lambda: [ReactionMomentumConservation()],
    "push": lambda: [ReactionPush()],
    "stop": lambda: [ReactionStop(distance=0.4)],
    "punch": lambda: [ReactionPunch()],
    "rebound": lambda: [ReactionRebound(up=True, right=True, distance=1.5, friction=1e-3)],
    "rebound_stop": lambda: [ReactionRebound()],
    "push_and_rebound": lambda: [ReactionPush(), ReactionRebound()],
}
ALL = {**SYMMETRIC, "force": lambda: [ReactionForce(30.0, -20.0, -45.0, 10.0)]}


def kinds_from(names: tuple[str, str, str, str], table: dict):
    friends, enemy, neutral, custom_name = names
    custom = CollisionKindCustom(table[custom_name]())
    custom.set_type(
        FighterBody,
        CollisionKindCustom.Type.SUB,
        CollisionKindCustom.Relation.AND,
        SpriteTemplate,
        CollisionKindCustom.Type.IS,
    )
    return [
        CollisionKindFriends(table[friends]()),
        CollisionKindEnemy(table[enemy]()),
        CollisionKindNeutral(table[neutral]()),
        custom,
    ]


def kind_names(table: dict):
    return st.tuples(*(st.sampled_from(sorted(table)) for _ in range(4)))


def build(
    scene, names, table, *, team_order=None, reverse_members=False, reverse_kinds=False, **engine
):
    sprites = [spec.make() for spec in scene]
    teams = [
        [s for s, spec in zip(sprites, scene, strict=True) if spec.team == t] for t in range(4)
    ]
    if reverse_members:
        teams = [team[::-1] for team in teams]
    if team_order is not None:
        teams = [teams[i] for i in team_order]
    kinds = kinds_from(names, table)
    world = make_world(
        teams, kinds[::-1] if reverse_kinds else kinds, width=WIDTH, height=HEIGHT, **engine
    )
    return world, sprites


def action_plan(seed: int, count: int, frames: int):
    """Per frame, a few (sprite index, vector) pairs, from a seed."""
    rng = random.Random(seed)
    return [
        [
            (rng.randrange(count), rng.uniform(-1.5, 1.5), rng.uniform(-1.5, 1.5))
            for _ in range(rng.randrange(3))
        ]
        for _ in range(frames)
    ]


def run(world, sprites, plan, dt):
    trace = []
    for frame_actions in plan:
        actions = [MotionAction(sprites[i], vx, vy) for i, vx, vy in frame_actions]
        world.step(dt, actions)
        trace.append(exact_state(sprites))
    return trace


@SETTINGS
@given(
    scene=scenes,
    names=kind_names(ALL),
    seed=st.integers(0, 2**32 - 1),
    dt=finite(1.0, 40.0),
    gravity=finite(0.0, 0.01),
    background=finite(0.5, 1.5),
)
def test_state_stays_finite(scene, names, seed, dt, gravity, background):
    world, sprites = build(scene, names, ALL, gravity=gravity, background_factor=background)
    for frame_actions in action_plan(seed, len(sprites), 40):
        world.step(dt, [MotionAction(sprites[i], vx, vy) for i, vx, vy in frame_actions])
        assert all_finite(sprites)


@SETTINGS
@given(
    scene=scenes,
    names=kind_names(ALL),
    seed=st.integers(0, 2**32 - 1),
    dt=finite(1.0, 40.0),
    gravity=finite(0.0, 0.01),
)
def test_same_setup_same_calls_bit_identical(scene, names, seed, dt, gravity):
    plan = action_plan(seed, len(scene), 30)
    first = run(*build(scene, names, ALL, gravity=gravity), plan, dt)
    second = run(*build(scene, names, ALL, gravity=gravity), plan, dt)
    assert first == second


@SETTINGS
@given(
    scene=scenes,
    names=kind_names(SYMMETRIC),
    seed=st.integers(0, 2**32 - 1),
    dt=finite(1.0, 40.0),
    gravity=finite(0.0, 0.01),
    order=st.permutations(range(4)),
    reverse_members=st.booleans(),
    reverse_kinds=st.booleans(),
)
def test_order_of_teams_sprites_and_kinds_does_not_matter(
    scene, names, seed, dt, gravity, order, reverse_members, reverse_kinds
):
    plan = action_plan(seed, len(scene), 30)
    reference = run(*build(scene, names, SYMMETRIC, gravity=gravity), plan, dt)
    permuted = run(
        *build(
            scene,
            names,
            SYMMETRIC,
            gravity=gravity,
            team_order=list(order),
            reverse_members=reverse_members,
            reverse_kinds=reverse_kinds,
        ),
        plan,
        dt,
    )
    assert permuted == reference


@SETTINGS
@given(scene=scenes, dt=finite(1.0, 40.0))
def test_broad_phase_never_drops_a_contact(scene, dt):
    world, sprites = build(scene, ("push",) * 4, SYMMETRIC)
    for sprite in sprites:
        world.engine.integrate(sprite, dt)
    candidates = {frozenset((id(a), id(b))) for a, b in world.collision.candidate_pairs()}
    group = world.group
    for one, two in itertools.combinations(sprites, 2):
        if group.team_of(one) == group.team_of(two) or not (one.movable or two.movable):
            continue
        if find_contact(one, two, dt) is not None:
            assert frozenset((id(one), id(two))) in candidates


# --- no tunnelling ----------------------------------------------------------------------------


@SETTINGS
@given(
    speed=finite(0.05, 50.0),
    thickness=finite(0.1, 30.0),
    height=finite(0.5, 100.0),
    gap=finite(0.0, 400.0),
    dt=finite(1.0, 50.0),
    gravity=finite(0.0, 0.01),
    offset=finite(-29.0, 199.0),
)
def test_a_falling_fighter_never_passes_through_a_block(
    speed, thickness, height, gap, dt, gravity, offset
):
    block = PlatformBlock(400.0, 1000.0, 200.0, thickness)
    fighter = FighterBody(400.0 + offset, 1000.0 - gap - height, 30.0, height, group_id=1, vy=speed)
    world = make_world(
        [[block], [fighter]],
        [CollisionKindNeutral(ReactionRebound())],
        width=2000.0,
        height=100_000.0,
        gravity=gravity,
    )
    frames = math.ceil(gap / (speed * dt)) + 2
    for _ in range(frames):
        world.step(dt)
        assert fighter.bottom <= block.top + 1e-9
    assert fighter.bottom == pytest.approx(block.top, abs=1e-9)
    assert fighter.vy == 0.0


@SETTINGS
@given(
    speed=finite(0.05, 50.0),
    other_speed=finite(-50.0, 0.0),
    thin=finite(0.1, 10.0),
    wide=finite(0.5, 80.0),
    gap=finite(0.0, 300.0),
    dt=finite(1.0, 50.0),
    masses=st.tuples(finite(1.0, 1000.0), finite(1.0, 1000.0)),
    reaction=st.sampled_from(["stop", "push", "momentum"]),
)
def test_fast_fighters_never_pass_through_each_other(
    speed, other_speed, thin, wide, gap, dt, masses, reaction
):
    fast = FighterBody(10_000.0, 100.0, wide, 20.0, group_id=1, mass=masses[0], vx=speed)
    thin_one = FighterBody(
        10_000.0 + wide + gap, 100.0, thin, 20.0, group_id=2, mass=masses[1], vx=other_speed
    )
    world = make_world(
        [[fast], [thin_one]],
        [CollisionKindEnemy(SYMMETRIC[reaction]())],
        width=100_000.0,
        height=1000.0,
    )
    frames = math.ceil(gap / ((speed - other_speed) * dt)) + 3
    touched = False
    for _ in range(frames):
        touched |= bool(world.step(dt))
        assert fast.right <= thin_one.left + 1e-6
    assert touched


# --- momentum -----------------------------------------------------------------------------------


@SETTINGS
@given(
    m1=finite(1.0, 1000.0),
    m2=finite(1.0, 1000.0),
    v1=finite(-2.0, 2.0),
    v2=finite(-2.0, 2.0),
    gap=finite(0.0, 20.0),
    dt=finite(1.0, 40.0),
    axis=st.sampled_from([0, 1]),
    reaction=st.sampled_from(["momentum", "push"]),
)
def test_momentum_is_conserved_in_free_space(m1, m2, v1, v2, gap, dt, axis, reaction):
    assume(v1 - v2 >= 0.01)
    size = 20.0
    if axis == 0:
        one = FighterBody(40_000.0, 40_000.0, size, size, group_id=1, mass=m1, vx=v1)
        two = FighterBody(40_000.0 + size + gap, 40_000.0, size, size, group_id=2, mass=m2, vx=v2)
    else:
        one = FighterBody(40_000.0, 40_000.0, size, size, group_id=1, mass=m1, vy=v1)
        two = FighterBody(40_000.0, 40_000.0 + size + gap, size, size, group_id=2, mass=m2, vy=v2)
    world = make_world(
        [[one], [two]],
        [CollisionKindEnemy(SYMMETRIC[reaction]())],
        width=100_000.0,
        height=100_000.0,
        gravity=0.0,
    )

    def along(sprite):
        return sprite.vx if axis == 0 else sprite.vy

    momentum = m1 * v1 + m2 * v2
    energy = m1 * v1 * v1 + m2 * v2 * v2
    for _ in range(math.ceil(gap / ((v1 - v2) * dt)) + 2):
        if world.step(dt):
            break
    else:
        pytest.fail("the two fighters never met")

    assert m1 * along(one) + m2 * along(two) == pytest.approx(momentum, rel=1e-9, abs=1e-9)
    assert along(one) - along(two) <= 1e-12  # no longer closing
    across = (one.vy, two.vy) if axis == 0 else (one.vx, two.vx)
    assert across == (0.0, 0.0)
    if reaction == "momentum":
        got = m1 * along(one) ** 2 + m2 * along(two) ** 2
        assert got == pytest.approx(energy, rel=1e-9, abs=1e-9)
    else:  # one common velocity (to rounding)
        assert along(one) == pytest.approx(along(two), rel=1e-12, abs=1e-15)
