"""Matches: a consistent table, seats swapped, neither argument order favoured, repeatable."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from vooga_env.tools.match import episode_seeds, run_match, wilson_interval


def test_table_is_consistent_and_seats_alternate():
    result = run_match("rush", "turtle", episodes=6, seed=3, max_cycles=200)
    result.check()
    a, b = result.sides
    assert result.games == 6
    for side in result.sides:
        assert side.wins + side.losses + side.draws == 6
    assert (a.wins, a.losses, a.draws) == (b.losses, b.wins, b.draws)
    assert result.seats == [(0, 1), (1, 0)] * 3
    for episode, seats in zip(result.episodes, result.seats, strict=True):
        assert episode.names[seats[0]] == "rush" and episode.names[seats[1]] == "turtle"
    assert result.mean_length == pytest.approx(np.mean([e.steps for e in result.episodes]))
    assert 0 < result.mean_length <= 200


def test_both_games_of_a_pair_share_their_seeds():
    result = run_match("random", "random", episodes=4, seed=5, max_cycles=30)
    first, second = result.episodes[0], result.episodes[1]
    assert first.seed == second.seed == episode_seeds(5, 0)[0]
    assert first.policy_seeds == second.policy_seeds[::-1]
    assert result.episodes[2].seed == episode_seeds(5, 1)[0] != first.seed


def test_argument_order_does_not_matter():
    # zoner and edge_guard use no randomness, so with seats swapped every game, B-vs-A plays the
    # very games A-vs-B played: the tables must be mirror images.
    ab = run_match("zoner", "edge_guard", episodes=4, seed=0, max_cycles=250)
    ba = run_match("edge_guard", "zoner", episodes=4, seed=0, max_cycles=250)
    assert dataclasses.asdict(ab.sides[0]) == dataclasses.asdict(ba.sides[1])
    assert dataclasses.asdict(ab.sides[1]) == dataclasses.asdict(ba.sides[0])
    assert ab.mean_length == ba.mean_length


def test_rush_beats_idle_in_a_clear_majority():
    result = run_match("rush", "idle", episodes=10, seed=0, max_cycles=300)
    rush, idle = result.sides
    assert rush.wins >= 8, rush
    assert rush.mean_damage > 0 and idle.mean_damage == 0 and idle.hits_landed == 0


def test_same_seed_same_match_different_seed_different_games():
    one = run_match("rush", "random", episodes=4, seed=11, max_cycles=120, record_actions=True)
    two = run_match("rush", "random", episodes=4, seed=11, max_cycles=120, record_actions=True)
    other = run_match("rush", "random", episodes=4, seed=12, max_cycles=120, record_actions=True)
    assert one.to_dict() == two.to_dict()
    assert [e.actions for e in one.episodes] == [e.actions for e in two.episodes]
    assert [e.actions for e in one.episodes] != [e.actions for e in other.episodes]


def test_frames_are_recorded_for_the_first_games_only():
    result = run_match("rush", "idle", episodes=2, seed=0, max_cycles=15, record_frames=1)
    first, second = result.episodes
    assert len(first.frames) == first.steps + 1
    assert first.frames[0].shape == (480, 800, 3) and first.frames[0].dtype == np.uint8
    assert not np.array_equal(first.frames[0], first.frames[-1])
    assert second.frames is None


@pytest.mark.parametrize("episodes", [0, -2, 1.5, True])
def test_bad_episode_counts_are_refused(episodes):
    with pytest.raises(ValueError, match="episodes"):
        run_match("rush", "idle", episodes=episodes)


def test_wilson_interval_known_value():
    low, high = wilson_interval(5, 10)
    assert low == pytest.approx(0.2366, abs=1e-4)
    assert high == pytest.approx(0.7634, abs=1e-4)
    assert wilson_interval(0, 0) == (0.0, 1.0)


@given(st.integers(1, 2000).flatmap(lambda n: st.tuples(st.integers(0, n), st.just(n))))
def test_wilson_interval_contains_the_estimate(case):
    successes, trials = case
    low, high = wilson_interval(successes, trials)
    assert 0.0 <= low <= successes / trials <= high <= 1.0
    assert high - low < 1.0
