"""Rewards: zero-sum by default, and the edge shaping telescopes over an episode."""

import numpy as np
import pytest

import vooga_env
from vooga_env.game.rewards import HitAndRingOutReward
from vooga_env.policies import make_policy


def rollout(seed, **overrides):
    env = vooga_env.parallel_env(backend="engine", **overrides)
    env.reset(seed=seed)
    rng = np.random.default_rng(seed)
    rewards = []
    while env.agents:
        _, reward, *_ = env.step({agent: int(rng.integers(10)) for agent in env.agents})
        rewards.append((reward["fighter_0"], reward["fighter_1"]))
    return env, rewards


def scripted_rollout(seed, backend, **overrides):
    """rush against turtle, seats swapped on odd seeds: (every step's rewards, the winner)."""
    env = vooga_env.parallel_env(backend=backend, **overrides)
    observations, _ = env.reset(seed=seed)
    styles = ("rush", "turtle")[:: 1 if seed % 2 == 0 else -1]
    fighters = {agent: make_policy(style, seed) for agent, style in zip(env.agents, styles)}
    rewards = []
    while env.agents:
        actions = {agent: fighters[agent].act(observations[agent]) for agent in env.agents}
        observations, reward, _, _, infos = env.step(actions)
        rewards.append((reward["fighter_0"], reward["fighter_1"]))
    return rewards, infos["fighter_0"]["winner"]


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


@pytest.mark.parametrize("backend", ["engine", "compiled"])
def test_a_win_on_time_is_paid_to_the_leader_on_the_last_step(backend):
    """`time_out` moves only the last step's rewards of a fight that ran out of time with a
    leader, by + time_out to it and - time_out to the other; a fight that ended (ring-out, KO)
    or was drawn is paid as without it."""
    kinds = []
    for seed, max_cycles in [(seed, 90) for seed in range(8)] + [(0, 10)]:
        paid, winner = scripted_rollout(
            seed, backend, max_cycles=max_cycles, rewards={"time_out": 3.0}
        )
        plain, _ = scripted_rollout(seed, backend, max_cycles=max_cycles)
        assert all(a == -b for a, b in paid)
        if len(paid) < max_cycles or winner == "draw":
            kinds.append("ended" if len(paid) < max_cycles else "draw")
            assert paid == plain
            continue
        kinds.append(winner)
        assert paid[:-1] == plain[:-1]
        sign = 1.0 if winner == "fighter_0" else -1.0
        assert paid[-1][0] == pytest.approx(plain[-1][0] + sign * 3.0)
    assert set(kinds) == {"ended", "draw", "fighter_0", "fighter_1"}, kinds
