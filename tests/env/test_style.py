"""Style counts from recorded games: endings, actions, punches and kicks attempted and landed."""

from __future__ import annotations

import pytest

from vooga_env.tools.match import run_match
from vooga_env.tools.style import StyleStats


def styles(a: str, b: str, episodes: int, **overrides) -> tuple:
    match = run_match(
        a, b, episodes, seed=1, record_actions=True, record_observations=True, **overrides
    )
    stats = (StyleStats(), StyleStats())
    for record, seats in zip(match.episodes, match.seats, strict=True):
        for side, seat in enumerate(seats):
            stats[side].add(record, seat)
    return match, stats


def test_counts_agree_with_the_match_and_with_each_fighters_script():
    match, (rush, zoner) = styles("rush", "zoner", 6, config="small")
    for side, style in zip(match.sides, (rush, zoner), strict=True):
        assert style.games == 6 and sum(style.endings.values()) == 6
        assert sum(style.actions) == style.steps == sum(e.steps for e in match.episodes)
        assert sum(style.landed.values()) == side.hits_landed  # every hit credited once
        for attack in ("punch", "kick"):
            assert 0 <= style.landed[attack] <= style.attempted[attack]  # an attack hits once
    assert zoner.attempted["punch"] == 0 and zoner.attempted["kick"] > 0  # zoner only kicks
    assert rush.attempted["punch"] > 0
    assert match.sides[0].ring_outs + match.sides[1].ring_outs >= rush.endings["ring_out"]


def test_a_game_nobody_wins_ends_on_time():
    _, (idle, _) = styles("idle", "idle", 2, max_cycles=20)
    assert idle.endings == {"ring_out": 0, "ko": 0, "time": 2}
    assert idle.to_dict()["actions"]["idle"] == 1.0
    assert idle.attempted == {"punch": 0, "kick": 0}


def test_games_without_observations_are_refused():
    match = run_match("rush", "idle", 1, max_cycles=20, record_actions=True)
    with pytest.raises(ValueError, match="record_observations=True"):
        StyleStats().add(match.episodes[0], 0)
