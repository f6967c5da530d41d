"""`gymnasium.make_vec(..., vectorization_mode="vector_entry_point")`: the batched engine."""

from __future__ import annotations

import gymnasium
import numpy as np
import pytest
from gymnasium.vector import AutoresetMode, VectorEnv
from gymnasium.wrappers.vector import RecordEpisodeStatistics

import vooga_env
from vooga_env.envs.gym_vector import FightVectorEnv


def make(num_envs: int, **kwargs):
    return gymnasium.make_vec(
        "vooga_env/Fight-v0", num_envs=num_envs, vectorization_mode="vector_entry_point", **kwargs
    )


def test_make_vec_gives_the_batched_engine_as_a_vector_env():
    envs = make(16, opponent="rush", config="water")
    assert isinstance(envs, VectorEnv) and isinstance(envs.unwrapped, FightVectorEnv)
    assert envs.metadata["autoreset_mode"] == AutoresetMode.SAME_STEP
    assert envs.unwrapped.fights.config.name == "water"
    assert envs.single_observation_space == vooga_env.parallel_env().observation_space("fighter_0")
    assert envs.observation_space.shape == (16, 41)
    assert envs.action_space.shape == (16,)
    observations, infos = envs.reset(seed=0)
    assert observations.shape == (16, 41) and observations.dtype == np.float32
    assert envs.observation_space.contains(observations)


def test_each_fight_is_a_seeded_single_env_with_same_step_autoreset():
    envs = make(3, opponent="idle", max_cycles=12)  # idle always stands: action 0
    singles = [vooga_env.parallel_env(max_cycles=12) for _ in range(3)]
    observations, _ = envs.reset(seed=5)
    expected = [single.reset(seed=5 + i)[0]["fighter_0"] for i, single in enumerate(singles)]
    assert np.array_equal(observations, np.stack(expected))
    rng = np.random.default_rng(0)
    ended = 0
    for _ in range(30):
        actions = rng.integers(0, 10, 3)
        observations, rewards, terminated, truncated, infos = envs.step(actions)
        for i, single in enumerate(singles):
            obs, reward, term, trunc, info = single.step(
                {"fighter_0": int(actions[i]), "fighter_1": 0}
            )
            assert rewards[i] == reward["fighter_0"]
            assert (terminated[i], truncated[i]) == (term["fighter_0"], trunc["fighter_0"])
            assert infos["health"][i] == info["fighter_0"]["health"]
            if single.agents:
                assert np.array_equal(observations[i], obs["fighter_0"])
                continue
            ended += 1
            assert infos["_final_obs"][i]
            assert np.array_equal(infos["final_obs"][i], obs["fighter_0"])
            assert infos["final_info"]["winner"][i] == info["fighter_0"]["winner"]
            fresh, _ = single.reset()  # the batch resets it in the same step
            assert np.array_equal(observations[i], fresh["fighter_0"])
    assert ended == 6  # each fight truncated at steps 12 and 24


def test_gymnasium_episode_statistics_wrapper_counts_the_episodes():
    envs = RecordEpisodeStatistics(make(4, opponent="random", max_cycles=10))
    envs.reset(seed=1)
    for _ in range(10):
        *_, infos = envs.step(envs.action_space.sample())
    assert infos["_episode"].all() and np.array_equal(infos["episode"]["l"], np.full(4, 10))


def test_render_shows_fight_zero():
    envs = make(2, opponent="idle", render_mode="rgb_array")
    single = vooga_env.parallel_env(render_mode="rgb_array")
    envs.reset(seed=3)
    single.reset(seed=3)
    for action in (2, 2, 3, 8, 8):
        envs.step(np.array([action, 0]))
        single.step({"fighter_0": action, "fighter_1": 0})
    assert np.array_equal(envs.render(), single.render())


def test_bad_arguments_name_themselves():
    with pytest.raises(ValueError, match="seat must be 0 or 1, got 2"):
        make(2, seat=2)
    with pytest.raises(ValueError, match="render_mode must be None or 'rgb_array', got 'human'"):
        make(2, render_mode="human")
    envs = make(2)
    envs.reset(seed=0)
    with pytest.raises(ValueError, match=r"actions must have shape \(2,\), got \(3,\)"):
        envs.step(np.zeros(3, dtype=int))


def test_a_list_of_seeds_seeds_each_fight():
    envs = make(3, opponent="rush")
    observations, _ = envs.reset(seed=[None, 4, None])
    single, _ = vooga_env.parallel_env().reset(seed=4)
    assert np.array_equal(observations[1], single["fighter_0"])
