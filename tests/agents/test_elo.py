"""Elo: the constants, the update rule, and a small round-robin whose order is sane."""

from __future__ import annotations

import pytest

from vooga_env.tools.elo import (
    DRAW_SCORE,
    K_FACTOR,
    START_RATING,
    EloTable,
    expected_score,
    round_robin,
    update,
)


def test_constants_are_ml_agents():
    assert (K_FACTOR, START_RATING, DRAW_SCORE) == (16.0, 1200.0, 0.5)


def test_expected_score():
    assert expected_score(1200, 1200) == 0.5
    assert expected_score(1600, 1200) == pytest.approx(10 / 11)
    assert expected_score(1300, 1250) + expected_score(1250, 1300) == pytest.approx(1.0)


def test_winner_gains_what_the_loser_loses():
    winner, loser = update(1200, 1200, 1.0)
    assert (winner, loser) == (1208.0, 1192.0)
    upset_winner, favourite = update(1000, 1400, 1.0)
    assert upset_winner - 1000 > 8 > 1400 - favourite - 8  # an upset moves more than K/2
    assert upset_winner + favourite == pytest.approx(2400)


def test_draws_count_half():
    assert update(1200, 1200, DRAW_SCORE) == (1200.0, 1200.0)
    low, high = update(1100, 1300, DRAW_SCORE)
    assert low > 1100 and high < 1300 and low + high == pytest.approx(2400)
    with pytest.raises(ValueError):
        update(1200, 1200, 1.5)


def test_table_records_and_ranks():
    table = EloTable(["a", "b", "c"])
    table.record("a", "b", 1.0)
    table.record("b", "c", 0.5)
    assert [name for name, _ in table.ranking()] == ["a", "c", "b"]
    assert table.entries["b"].games == 2 and table.entries["b"].draws == 1
    assert sum(e.rating for e in table.entries.values()) == pytest.approx(3 * START_RATING)
    with pytest.raises(ValueError):
        table.record("a", "a", 1.0)
    with pytest.raises(ValueError):
        table.add("a")


def test_round_robin_rates_the_ladder():
    tournament = round_robin(["rush", "idle", "turtle"], episodes=4, seed=0, max_cycles=300)
    ranking = [name for name, _ in tournament.table.ranking()]
    assert ranking == ["turtle", "rush", "idle"]
    assert set(tournament.matches) == {("rush", "idle"), ("rush", "turtle"), ("idle", "turtle")}
    for match in tournament.matches.values():
        match.check()
        assert match.games == 4
    for entry in tournament.table.entries.values():
        assert entry.games == 8
    ratings = [rating for _, rating in tournament.table.ranking()]
    assert sum(ratings) == pytest.approx(3 * START_RATING)
    data = tournament.to_dict()
    assert data["k_factor"] == 16.0 and data["start_rating"] == 1200.0
    assert [row["name"] for row in data["ratings"]] == ranking


def test_round_robin_names_duplicate_entrants_apart():
    tournament = round_robin(["idle", "idle"], episodes=2, seed=0, max_cycles=5)
    assert tournament.names == ["idle", "idle_2"]
    with pytest.raises(ValueError, match="two entrants"):
        round_robin(["idle"], episodes=1)
