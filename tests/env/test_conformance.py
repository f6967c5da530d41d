"""PettingZoo's, Gymnasium's and SB3's own test utilities on our envs."""

import gymnasium
import numpy as np
import pytest
from gymnasium.utils.env_checker import check_env as gymnasium_check_env
from pettingzoo.test import (
    api_test,
    max_cycles_test,
    parallel_api_test,
    render_test,
    seed_test,
)
from stable_baselines3.common.env_checker import check_env as sb3_check_env

import vooga_env
from vooga_env.envs import parallel as parallel_module


def test_parallel_api(backend):
    parallel_api_test(vooga_env.parallel_env(backend=backend), num_cycles=1000)


@pytest.mark.parametrize("config", ["default", "water", "platforms", "small"])
def test_aec_api(config, backend):
    api_test(vooga_env.env(config=config, backend=backend), num_cycles=300)


def test_seed(backend):
    seed_test(lambda: vooga_env.env(arena={"spawn_jitter": 10.0}, backend=backend), num_cycles=300)


def test_max_cycles():
    max_cycles_test(parallel_module)
    max_cycles_test(vooga_env)


def test_render():
    render_test(lambda render_mode=None: vooga_env.env(render_mode=render_mode))


def test_state_is_inside_its_space(backend):
    env = vooga_env.parallel_env(backend=backend)
    env.reset(seed=0)
    rng = np.random.default_rng(0)
    for _ in range(200):
        env.step({agent: int(rng.integers(10)) for agent in env.agents})
        assert env.state_space.contains(env.state())
        if not env.agents:
            env.reset()


@pytest.mark.parametrize("env_id", sorted(vooga_env.GYM_IDS))
def test_gymnasium_check_env(env_id):
    env = gymnasium.make(env_id, opponent="rush")
    gymnasium_check_env(env.unwrapped)


def test_sb3_check_env():
    sb3_check_env(gymnasium.make("vooga_env/Fight-v0", opponent="random").unwrapped)


def test_sb3_ppo_trains_on_the_registered_env_as_is():
    from stable_baselines3 import PPO

    env = gymnasium.make("vooga_env/Fight-v0", opponent="idle", max_cycles=50)
    model = PPO("MlpPolicy", env, n_steps=64, batch_size=32, n_epochs=1, seed=0, device="cpu")
    model.learn(128)
    action, _ = model.predict(env.observation_space.sample(), deterministic=True)
    assert env.action_space.contains(int(action))
