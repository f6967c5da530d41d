"""Rewards: zero-sum by default, and the edge shaping telescopes over an episode."""

import numpy as np
import pytest

import vooga_env
from vooga_env.game.rewards import HitAndRingOutReward


def rollout(seed, **overrides):
    env = vooga_env.parallel_env(backend="engine", **overrides)
    env.reset(seed=seed)
    rng = np.random.default_rng(seed)
    rewards = []
    while env.agents:
        _, reward, *_ = env.step({agent: int(rng.integers(10)) for agent in env.agents})
        rewards.append((reward["fighter_0"], reward["fighter_1"]))
    return env, rewards


@pytest.mark.parametrize("edge", [0.0, 2.0])
def test_rewards_are_zero_sum(edge):
    _, rewards = rollout(3, max_cycles=300, rewards={"edge": edge})
    assert all(a == -b for a, b in rewards)


def test_edge_shaping_telescopes_to_the_change_in_stage_room():
    env, shaped = rollout(5, max_cycles=200, rewards={"edge": 2.0})
    _, plain = rollout(5, max_cycles=200, rewards={"edge": 0.0})
    start_env = vooga_env.parallel_env(max_cycles=200, backend="engine")
    start_env.reset(seed=5)
    start = HitAndRingOutReward._edge_advantage(start_env.fight)
    end = HitAndRingOutReward._edge_advantage(env.fight)
    shaping = sum(a for a, _ in shaped) - sum(a for a, _ in plain)
    assert shaping == pytest.approx(2.0 * (end - start))
    assert end != start


def test_the_time_penalty_is_charged_to_both():
    _, rewards = rollout(1, max_cycles=10, rewards={"time_penalty": 0.01})
    assert all(a + b == pytest.approx(-0.02) for a, b in rewards)
