"""The batched engine's parts: exact sums, RNG streams, refusals, memory, numba required."""

from __future__ import annotations

import math
import struct
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from gymnasium.utils import seeding
from hypothesis import given, settings
from hypothesis import strategies as st

from vooga_env.kernel import UnsupportedConfig, VectorFight
from vooga_env.kernel.layout import OBS_HEALTH, OBS_TIME_LEFT
from vooga_env.kernel.parts import Streams, _fsum, _next_double
from vooga_env.kernel.rng import PCG64Streams

REPO = Path(__file__).resolve().parents[2]
floats = st.one_of(
    st.floats(allow_nan=False, allow_infinity=False, min_value=-1e200, max_value=1e200),
    st.sampled_from([0.0, -0.0, 1.0, -1.0, 2.0**-53, 2.0**-1074, 1e16, 0.1]),
)


def bits(value: float) -> bytes:
    return struct.pack("<d", value)


@settings(max_examples=300, deadline=None)
@given(st.lists(st.lists(floats, min_size=7, max_size=7), min_size=1, max_size=40))
def test_the_kernels_fsum_is_math_fsum_bit_for_bit(rows):
    terms = np.array(rows).T.copy()
    for j in range(terms.shape[1]):
        assert bits(kernel_fsum(terms[:, j])) == bits(math.fsum(terms[:, j].tolist()))


def kernel_fsum(column: np.ndarray) -> float:
    """`kernel_parts._fsum` of one column, laid out as the kernel's (fighter, kind, axis) terms."""
    terms = np.zeros((2, 2, 2, len(column)))
    terms[1, 0, 1] = column
    return _fsum(terms, 1, 0, 1, len(column), np.empty(len(column) + 1))


def test_the_kernels_fsum_on_half_way_cases():
    # exactly half an ulp above 1.0, then a hair more or less: the partials decide the rounding
    ulp = math.ulp(1.0)
    columns = [
        [1.0, ulp / 2, 0.0],
        [1.0, ulp / 2, 2.0**-80],
        [1.0, ulp / 2, -(2.0**-80)],
        [1.0 + ulp, ulp / 2, 0.0],
        [-0.0, -0.0, -0.0],
        [1e16, 1.0, -1e16],
        [0.1, 0.2, 0.3],
    ]
    for column in columns:
        assert bits(kernel_fsum(np.array(column))) == bits(math.fsum(column))


def test_pcg64_streams_draw_what_the_single_env_draws():
    seeds = [0, 1, 7, 12345, 2**40]
    streams = PCG64Streams(len(seeds))
    streams.seed(np.arange(len(seeds)), seeds)
    generators = [seeding.np_random(seed)[0] for seed in seeds]
    arrays = Streams(streams.state_hi, streams.state_lo, streams.inc_hi, streams.inc_lo)
    for k in range(50):
        index = [i for i in range(len(seeds)) if (i + k) % 3]  # not every stream draws
        got = [_next_double(arrays, i) for i in index]
        assert got == [generators[i].random() for i in index]
    assert streams.get_state(3) == generators[3].bit_generator.state


@pytest.mark.parametrize(
    ("overrides", "option"),
    [
        ({"collisions": {"enemy": "momentum"}}, "collisions.enemy"),
        ({"collisions": {"neutral": "stop"}}, "collisions.neutral"),
    ],
)
def test_options_the_batched_engine_cannot_run_are_refused_by_name(overrides, option):
    with pytest.raises(UnsupportedConfig, match=option):
        VectorFight(2, **overrides)


def test_a_custom_reward_is_refused():
    with pytest.raises(UnsupportedConfig, match="reward_fn"):
        VectorFight(2, reward_fn=lambda fight, events: (0.0, 0.0))


def test_bad_arguments_fail_clearly():
    with pytest.raises(ValueError, match="num_fights"):
        VectorFight(0)
    with pytest.raises(ValueError, match="backend"):
        VectorFight(1, backend="cuda")
    fights = VectorFight(2)
    with pytest.raises(RuntimeError, match="reset"):
        fights.step(np.zeros((2, 2), dtype=int))
    fights.reset(seed=0)
    with pytest.raises(ValueError, match="shape"):
        fights.step(np.zeros((3, 2), dtype=int))
    with pytest.raises(ValueError, match="0..9"):
        fights.step(np.full((2, 2), 10))
    with pytest.raises(ValueError, match="threads must be >= 1, got 0"):
        VectorFight(2, threads=0)
    with pytest.raises(TypeError, match="threads must be an int"):
        VectorFight(2, threads=1.5)
    with pytest.raises(ValueError, match="numpy backend is gone"):
        VectorFight(2, backend="numpy")


def test_one_thread_unless_more_are_asked_for():
    assert VectorFight(4096, backend="numba").threads == 1
    assert VectorFight(4096, threads=2).threads == 2
    assert VectorFight(8, threads=32).threads == 8  # never more than fights


def test_a_4096_fight_batch_holds_its_state_in_under_64_mib():
    fights = VectorFight(4096)
    assert fights.state.nbytes < 64 * 2**20
    assert fights.state.nbytes == sum(a.nbytes for a in fights.state.arrays().values()) + (
        fights.state.rng.nbytes
    )


def test_seeding_matches_the_single_env_and_continues_its_stream():
    import vooga_env

    fights = VectorFight(3, arena={"spawn_jitter": 20.0})
    first = fights.reset(seed=5)
    again = fights.reset()  # no seed: the streams go on, as env.reset() does
    for i in range(3):
        env = vooga_env.parallel_env(arena={"spawn_jitter": 20.0})
        obs, _ = env.reset(seed=5 + i)
        assert np.array_equal(first[i, 0], obs["fighter_0"])
        obs, _ = env.reset()
        assert np.array_equal(again[i, 0], obs["fighter_0"])
    assert not np.array_equal(first[0], first[1])


def test_random_sides_swaps_the_spawns_on_a_seeded_coin_as_the_engine_does():
    import vooga_env

    sides = {"random_sides": True}
    first = VectorFight(16, arena=sides).reset(seed=0)
    swapped = first[:, 0, 0] > 0  # fighter_0's own x: right of the centre
    assert 0 < swapped.sum() < 16
    for i in range(16):
        env = vooga_env.parallel_env(arena=sides, backend="engine")
        obs, _ = env.reset(seed=i)
        assert np.array_equal(first[i, 0], obs["fighter_0"])
    assert (VectorFight(16).reset(seed=0)[:, 0, 0] < 0).all()


def test_the_start_damage_and_clock_are_drawn_as_the_engine_draws_them():
    import vooga_env

    overrides = {"start": {"damage": 40.0, "steps": 600}, "arena": {"spawn_jitter": 8.0}}
    first = VectorFight(16, **overrides).reset(seed=0)
    health, time_left = first[:, :, OBS_HEALTH], first[:, 0, OBS_TIME_LEFT]
    assert ((health > 0.6) & (health <= 1.0)).all() and len(np.unique(health)) == 32
    assert ((time_left > 0.3) & (time_left <= 1.0)).all() and len(np.unique(time_left)) > 8
    for i in range(16):
        env = vooga_env.parallel_env(**overrides, backend="engine")
        obs, _ = env.reset(seed=i)
        assert np.array_equal(first[i, 0], obs["fighter_0"])
        assert np.array_equal(first[i, 1], obs["fighter_1"])


def test_without_numba_the_batch_says_how_to_install_it():
    script = """
import sys
sys.modules["numba"] = None  # as if not installed
from vooga_env.kernel import VectorFight, numba_available
assert not numba_available()
try:
    VectorFight(3)
except ImportError as error:
    assert "pip install numba" in str(error), error
else:
    raise AssertionError("VectorFight ran without numba")
print("ok")
"""
    result = subprocess.run(
        [sys.executable, "-c", script], cwd=REPO, capture_output=True, text=True, timeout=120
    )
    assert result.returncode == 0, result.stdout + result.stderr
    assert result.stdout.strip() == "ok"
