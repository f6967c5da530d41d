"""The scripted styles (aerial, punisher, spacer, edge_grappler, mixup, shover, staller): competent,
registered, and quick to play on the batched engine (`vooga_env.tools.batch_match.batch_match`)."""

from __future__ import annotations

import pytest

from vooga_env.game.actions import Action
from vooga_env.policies import SCRIPTED
from vooga_env.tools.batch_match import batch_match
from vooga_env.tools.match import run_match

STYLES = ("aerial", "punisher", "spacer", "edge_grappler", "mixup", "shover", "staller")


@pytest.mark.parametrize("name", STYLES)
def test_each_style_beats_idle_and_random_nine_times_in_ten(name):
    assert name in SCRIPTED
    for weak in ("idle", "random"):
        result = batch_match(name, weak, 40, seed=5)
        assert result["win_rate"] >= 0.9, (name, weak, result)


def test_the_styles_are_not_one_fighter():
    """Each style wins some and loses some among the others: distinct, none a pushover."""
    scores = {
        name: sum(batch_match(name, other, 20, seed=1)["wins"] for other in STYLES if other != name)
        for name in STYLES
    }
    assert len(set(scores.values())) > 1
    games = 20 * (len(STYLES) - 1)
    assert all(0 < score < games for score in scores.values()), scores


def test_a_batch_match_repeats_from_its_seed_and_counts_every_game():
    first = batch_match("punisher", "rush", 12, seed=3, max_cycles=200)
    assert first == batch_match("punisher", "rush", 12, seed=3, max_cycles=200)
    assert first["wins"] + first["draws"] + first["losses"] == 12
    with pytest.raises(ValueError, match="games must be a positive int, got 0"):
        batch_match("rush", "idle", 0)


@pytest.mark.parametrize("name", STYLES)
def test_the_single_env_plays_each_style_too(name):
    result = run_match(name, "idle", 2, seed=0, config="small", max_cycles=300)
    assert result.sides[0].wins == 2


def crouch(observation):
    return Action.DOWN


def test_the_shover_walks_a_crouching_fighter_off_without_a_blow():
    """Its one weapon is its body: a fighter that only crouches is pushed off the stage."""
    result = run_match("shover", crouch, 4, seed=0, record_actions=True)
    assert result.sides[0].wins == 4
    for record, seats in zip(result.episodes, result.seats, strict=True):
        assert record.ended_by == "ring_out"
        assert record.damage_dealt[seats[0]] == 0.0
        assert {Action.PUNCH, Action.KICK}.isdisjoint(pair[seats[0]] for pair in record.actions)


def test_the_staller_waits_crouched_then_takes_a_lead_and_plays_for_time():
    """Level, it crouches and jabs where it stands for the first half of the clock; then it walks
    in, lands a hit, and crouches and jabs again until the time runs out with it ahead."""
    stall = {Action.DOWN, Action.PUNCH}
    result = run_match("staller", "idle", 2, seed=0, record_actions=True)
    assert result.sides[0].wins == 2
    for record, seats in zip(result.episodes, result.seats, strict=True):
        assert record.ended_by == "time"
        actions = [pair[seats[0]] for pair in record.actions]
        half = len(actions) // 2
        assert set(actions[: half - 1]) <= stall
        assert not set(actions[half + 1 :]) <= stall  # it went in to attack
        assert set(actions[-100:]) <= stall
