"""Mirroring the world left-right swaps the two observations exactly."""

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

import vooga_env
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


@settings(max_examples=200, deadline=None)
@given(fighter_state, fighter_state, st.integers(0, 899))
def test_mirrored_world_swaps_observations(first, second, steps):
    env = vooga_env.parallel_env(backend="engine")
    env.reset(seed=0)
    fight = env.fight
    width = fight.config.arena.width
    fight.steps = steps
    one, two = fight.fighters
    place(one, first, width, mirrored=False)
    place(two, second, width, mirrored=False)
    before = (observe(fight, 0), observe(fight, 1))
    place(one, second, width, mirrored=True)
    place(two, first, width, mirrored=True)
    after = (observe(fight, 0), observe(fight, 1))
    # Equal values (0.0 == -0.0: a fighter at the exact centre is at -0.0 from the other side).
    assert np.array_equal(after[0], before[1])
    assert np.array_equal(after[1], before[0])
