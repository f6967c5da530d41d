"""Mirroring the world left-right swaps the two observations exactly, and leaves them as they
are in the opponent-facing frame."""

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

import vooga_env
from vooga_env.game.facing import MIRROR_INDEX, MIRROR_SIGN, OPPONENT_X, face_opponent
from vooga_env.game.observations import observe

# Dyadic values keep x' = width - x - w exact in floating point.
coordinate = st.integers(0, 2000).map(lambda n: n / 4)
speed = st.integers(-64, 64).map(lambda n: n / 32)
fighter_state = st.fixed_dictionaries(
    {
        "x": coordinate.filter(lambda x: x <= 700),
        "y": coordinate.filter(lambda y: y <= 400),
        "vx": speed,
        "vy": speed,
        "facing": st.sampled_from([-1.0, 1.0]),
        "health": st.integers(1, 100).map(float),
        "on_ground": st.booleans(),
        "jumps_left": st.integers(0, 1),
        "move": st.sampled_from([None, "punch", "kick"]),
        "move_frame": st.integers(0, 5),
        "hitstun": st.integers(0, 10),
        "blocking": st.booleans(),
        "crouching": st.booleans(),
    }
)


def place(fighter, state, width, mirrored):
    for key, value in state.items():
        setattr(fighter, key, value)
    if mirrored:
        fighter.x = width - state["x"] - fighter.width
        fighter.vx = -state["vx"]
        fighter.facing = -state["facing"]


def observations(first, second, steps, mirrored):
    """Both fighters' observations (2, 41), fighter_0 in state `first`, at step `steps`."""
    env = vooga_env.parallel_env(backend="engine")
    env.reset(seed=0)
    fight = env.fight
    fight.steps = steps
    width = fight.config.arena.width
    place(fight.fighters[0], first, width, mirrored)
    place(fight.fighters[1], second, width, mirrored)
    return np.stack([observe(fight, 0), observe(fight, 1)])


@settings(max_examples=200, deadline=None)
@given(fighter_state, fighter_state, st.integers(0, 899))
def test_mirrored_world_swaps_observations(first, second, steps):
    before = observations(first, second, steps, mirrored=False)
    after = observations(second, first, steps, mirrored=True)
    # Equal values (0.0 == -0.0: a fighter at the exact centre is at -0.0 from the other side).
    assert np.array_equal(after[0], before[1])
    assert np.array_equal(after[1], before[0])


@settings(max_examples=200, deadline=None)
@given(fighter_state, fighter_state, st.integers(0, 899))
def test_facing_the_opponent_a_world_and_its_mirror_look_the_same(first, second, steps):
    """In the opponent-facing frame a fighter sees a fight and its mirror image as one fight, so a
    policy that plays in it knows a crossed-over fight as the usual one."""
    plain = observations(first, second, steps, mirrored=False)
    mirror = observations(first, second, steps, mirrored=True)
    assert np.array_equal(mirror, plain[:, MIRROR_INDEX] * MIRROR_SIGN)  # the mirror, by seat
    (faced, turned), (faced_mirror, turned_mirror) = face_opponent(plain), face_opponent(mirror)
    apart = plain[:, OPPONENT_X] != 0
    assert np.array_equal(faced[apart], faced_mirror[apart])
    assert np.array_equal(turned[apart], ~turned_mirror[apart])
    assert not np.any(faced[:, OPPONENT_X] < 0)
