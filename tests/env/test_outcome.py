"""`Outcome`: one encoding of winner / draw / going on, from the kernel's codes to the infos."""

import numpy as np
import pytest

import vooga_env
from vooga_env.game.outcome import Outcome


def test_every_outcome_round_trips_through_its_info_string():
    assert [outcome.info for outcome in Outcome] == [None, "draw", "fighter_0", "fighter_1"]
    for outcome in Outcome:
        assert Outcome.from_info(outcome.info) is outcome
        assert Outcome(int(outcome)) is outcome  # the kernel's int64 code
    assert [outcome.over for outcome in Outcome] == [False, True, True, True]
    assert Outcome.of_leader(None) is Outcome.DRAW
    assert Outcome.of_leader(1) is Outcome.FIGHTER_1


def test_each_seat_sees_the_mirror_result_and_a_going_on_fight_has_none():
    mirror = {"win": "loss", "loss": "win", "draw": "draw"}
    for outcome in (Outcome.DRAW, Outcome.FIGHTER_0, Outcome.FIGHTER_1):
        assert mirror[outcome.for_seat(0)] == outcome.for_seat(1)
    assert Outcome.FIGHTER_1.for_seat(1) == "win"
    assert Outcome.DRAW.for_seat(0) == "draw"
    with pytest.raises(ValueError, match="the fight goes on"):
        Outcome.GOING_ON.for_seat(0)


def test_an_unknown_winner_string_names_the_allowed_ones():
    with pytest.raises(ValueError, match="winner = 'fighter_2' is not one of None, 'draw'"):
        Outcome.from_info("fighter_2")


@pytest.mark.parametrize("backend", ["engine", "compiled"])
def test_the_env_reports_the_outcome_string_only_at_the_end(backend):
    env = vooga_env.parallel_env(backend=backend, max_cycles=30)
    env.reset(seed=3)
    rng = np.random.default_rng(3)
    for _ in range(30):
        actions = {agent: int(rng.integers(10)) for agent in env.agents}
        _, _, terminated, truncated, infos = env.step(actions)
        done = terminated["fighter_0"] or truncated["fighter_0"]
        assert ("winner" in infos["fighter_0"]) == done
        if done:
            assert Outcome.from_info(infos["fighter_0"]["winner"]).over
            break
    else:
        raise AssertionError("max_cycles=30 did not end the episode")


@pytest.mark.parametrize("backend", ["engine", "compiled"])
def test_a_fight_started_part_way_ends_on_its_clock_and_the_healthier_wins(backend):
    env = vooga_env.parallel_env(backend=backend, start={"damage": 60.0, "steps": 880})
    for seed in range(4):
        env.reset(seed=seed)
        health = [status["health"] for status in env.fighter_status()]
        assert all(40.0 < value <= 100.0 for value in health) and health[0] != health[1]
        steps_left = round(float(env.state()[-1]) * 900)  # fighter_1's time_left
        assert 20 <= steps_left <= 900
        for step in range(1, steps_left + 1):  # both stand still: no hit, no ring-out
            _, _, terminated, truncated, infos = env.step({"fighter_0": 0, "fighter_1": 0})
            assert not terminated["fighter_0"] and truncated["fighter_0"] == (step == steps_left)
        leader = "fighter_0" if health[0] > health[1] else "fighter_1"
        assert infos["fighter_0"]["winner"] == leader
