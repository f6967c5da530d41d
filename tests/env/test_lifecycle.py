"""Envs are freed when dropped, copy and pickle mid-game, and say when a window goes nowhere."""

from __future__ import annotations

import copy
import gc
import pickle
import warnings
import weakref

import numpy as np
import pytest

import vooga_env


def play(env, steps: int, seed: int = 0) -> list[np.ndarray]:
    """Random actions from a fixed stream; every observation on the way."""
    rng = np.random.default_rng(seed)
    seen = []
    for _ in range(steps):
        if not env.agents:
            env.reset()
        actions = {agent: int(rng.integers(10)) for agent in env.possible_agents}
        observations, *_ = env.step(actions)
        seen.append(np.concatenate([observations[agent] for agent in env.possible_agents]))
    return seen


def test_dropped_envs_are_freed(backend):
    refs = []
    for _ in range(20):
        env = vooga_env.parallel_env(backend=backend)
        env.observation_space("fighter_0")  # the spaces were once cached per class: never freed
        env.action_space("fighter_1")
        refs.append(weakref.ref(env))
    del env
    gc.collect()
    assert sum(ref() is not None for ref in refs) == 0


def test_the_spaces_are_the_same_object_every_call_and_per_env():
    one, two = vooga_env.parallel_env(), vooga_env.parallel_env()
    assert one.observation_space("fighter_0") is one.observation_space("fighter_1")
    assert one.action_space("fighter_0") is one.action_space("fighter_0")
    assert one.observation_space("fighter_0") is not two.observation_space("fighter_0")


@pytest.mark.parametrize("clone", [copy.deepcopy, lambda env: pickle.loads(pickle.dumps(env))])
def test_a_copy_mid_game_plays_on_as_the_original(backend, clone):
    render_mode = "rgb_array" if backend == "engine" else None
    env = vooga_env.parallel_env(backend=backend, render_mode=render_mode, max_cycles=40)
    env.reset(seed=4)
    play(env, 25)
    if render_mode:
        env.render()  # a viewer with pygame surfaces: the copy leaves it behind
    twin = clone(env)
    same = [np.array_equal(a, b) for a, b in zip(play(env, 30, 1), play(twin, 30, 1))]
    assert same == [True] * 30
    if render_mode:
        assert np.array_equal(env.render(), twin.render())


def test_render_ignores_an_argument_as_rllib_passes_one():
    env = vooga_env.parallel_env(render_mode="rgb_array")
    env.reset(seed=0)
    assert env.render(None).shape == (480, 800, 3)
    assert vooga_env.parallel_env().render("rgb_array") is None  # no render_mode: nothing


def test_a_human_window_without_a_display_says_so(monkeypatch):
    monkeypatch.setenv("SDL_VIDEODRIVER", "dummy")
    env = vooga_env.parallel_env(render_mode="human")
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        env.reset(seed=0)
        env.step({"fighter_0": 0, "fighter_1": 0})
    env.close()
    messages = [str(w.message) for w in caught if issubclass(w.category, RuntimeWarning)]
    assert len(messages) == 1 and "no display" in messages[0] and "xvfb-run" in messages[0]
