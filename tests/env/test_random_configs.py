"""Validation is complete: any config `load_config` accepts runs on both backends, bit for bit.

Hypothesis draws configs over wide ranges (stage shapes, spawns, jitter, physics, attacks,
frame_skip, stocks) and keeps those that validate; each is played by the "engine" and the
"compiled" backend side by side with random actions, every output compared at every step. A
config that crashes either backend or makes them differ is a bug: fixed, or refused at load.
"""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st

import vooga_env
from vooga_env.game.config import ConfigError, load_config

from .test_backends import assert_same

pytest.importorskip("numba")

STEPS = 300


def _number(low: float, high: float) -> st.SearchStrategy[float]:
    return st.floats(low, high, allow_nan=False, allow_infinity=False)


@st.composite
def blocks(draw, width: float, height: float) -> list[dict]:
    """One to four blocks inside the arena; the first is the main stage, low and wide."""
    main_w = draw(_number(80.0, width * 0.9))
    main_x = draw(_number(0.0, width - main_w))
    main_y = draw(_number(height * 0.3, height - 10.0))
    stage = [{"x": main_x, "y": main_y, "width": main_w, "height": draw(_number(1.0, 10.0))}]
    for _ in range(draw(st.integers(0, 3))):
        w = draw(_number(5.0, width / 2))
        h = draw(_number(1.0, 60.0))
        stage.append(
            {
                "x": draw(_number(0.0, width - w)),
                "y": draw(_number(0.0, height - h)),
                "width": w,
                "height": h,
            }
        )
    return stage


def attacks() -> st.SearchStrategy[dict]:
    return st.fixed_dictionaries(
        {
            "startup": st.integers(0, 6),
            "active": st.integers(1, 5),
            "recovery": st.integers(0, 10),
            "damage": _number(0.0, 40.0),
            "knockback": _number(0.0, 1.5),
            "knockback_growth": _number(0.0, 0.03),
            "angle": _number(-90.0, 180.0),
            "hitstun": st.integers(0, 25),
            "hitbox_width": _number(1.0, 80.0),
            "hitbox_height": _number(1.0, 60.0),
            "offset_y": _number(-30.0, 90.0),
        }
    )


@st.composite
def configs(draw) -> dict:
    """Overrides for `load_config`: often invalid (the test then skips them), never one kind."""
    width, height = draw(_number(200.0, 1200.0)), draw(_number(150.0, 800.0))
    stage = draw(blocks(width, height))
    fighter_w = draw(_number(5.0, 80.0))
    fighter_h = draw(_number(10.0, 100.0))
    health, max_cycles = draw(_number(1.0, 200.0)), draw(st.integers(20, 200))
    main = stage[0]
    spawns = [draw(_number(main["x"] - fighter_w, main["x"] + main["width"])) for _ in range(2)]
    return {
        "arena": {
            "width": width,
            "height": height,
            "blocks": stage,
            "spawns": spawns,
            "spawn_jitter": draw(st.one_of(st.just(0.0), _number(0.0, 60.0))),
            "random_sides": draw(st.booleans()),
        },
        "physics": {
            "gravity": draw(_number(1e-5, 0.01)),
            "background_factor": draw(_number(0.2, 1.5)),
            "speed_factor": draw(_number(0.0, 2.0)),
            "out_bound_distance": draw(_number(0.0, 20.0)),
            "frame_time": draw(_number(2.0, 40.0)),
            "ground_friction": draw(_number(0.0, 0.01)),
        },
        "fighter": {
            "width": fighter_w,
            "height": fighter_h,
            "crouch_height": draw(_number(1.0, fighter_h)),
            "mass": draw(_number(1.0, 1000.0)),
            "speed": draw(_number(0.0, 1.5)),
            "health": health,
            "jump_speed": draw(_number(0.0, 1.5)),
            "air_jumps": draw(st.integers(0, 3)),
            "fast_fall_speed": draw(_number(0.0, 2.0)),
            "head_slide": draw(_number(0.0, 4.0)),
            "block_damage": draw(_number(0.0, 1.0)),
            "block_knockback": draw(_number(0.0, 1.0)),
            "punch": draw(attacks()),
            "kick": draw(attacks()),
        },
        "rewards": {
            "damage": draw(_number(0.0, 10.0)),
            "ring_out": draw(_number(0.0, 10.0)),
            "ko": draw(_number(0.0, 10.0)),
            "time_penalty": draw(_number(0.0, 0.1)),
            "edge": draw(_number(0.0, 5.0)),
            "time_out": draw(_number(0.0, 10.0)),
        },
        "max_cycles": max_cycles,
        "frame_skip": draw(st.integers(1, 4)),
        "stocks": draw(st.integers(1, 3)),
        "start": {
            "damage": draw(st.one_of(st.just(0.0), _number(0.0, 0.99 * health))),
            "steps": draw(st.one_of(st.just(0), st.integers(0, max_cycles - 1))),
        },
    }


def play_both(overrides: dict, seed: int, steps: int = STEPS) -> int:
    """Both backends on one config, random actions, every output compared; episodes played."""
    try:
        config = load_config("default", **overrides)
    except ConfigError:
        assume(False)
    envs = [vooga_env.parallel_env(config=config, backend=b) for b in ("engine", "compiled")]
    rng = np.random.default_rng(seed)
    episodes = 0
    for step in range(steps):
        if step == 0 or not envs[0].agents:
            reseed = seed + episodes if episodes % 2 == 0 else None
            results = [env.reset(seed=reseed) for env in envs]
            assert_same(*results)
            episodes += 1
        pair = rng.integers(10, size=2).tolist()
        actions = {"fighter_0": pair[0], "fighter_1": pair[1]}
        results = [env.step(actions) for env in envs]
        assert_same(*results)
        assert envs[0].fighter_status() == envs[1].fighter_status(), step
        assert envs[0].state().tobytes() == envs[1].state().tobytes(), step
        for observation in results[0][0].values():
            assert np.isfinite(observation).all(), step
    return episodes


_SETTINGS = dict(
    deadline=None,
    suppress_health_check=[HealthCheck.filter_too_much, HealthCheck.too_slow],
)


@settings(max_examples=40, **_SETTINGS)
@given(configs(), st.integers(0, 2**31))
def test_every_valid_config_runs_the_same_on_both_backends(overrides, seed):
    play_both(overrides, seed)


@pytest.mark.slow
@settings(max_examples=600, **_SETTINGS)
@given(configs(), st.integers(0, 2**31))
def test_every_valid_config_runs_the_same_on_both_backends_long(overrides, seed):
    play_both(overrides, seed)
