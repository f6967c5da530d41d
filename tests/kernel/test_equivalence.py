"""The batched engine against single envs: bit for bit, step by step, through hits, blocks,
ring-outs, KOs, truncations and auto-resets."""

from __future__ import annotations

import numpy as np
import pytest

import vooga_env
from tests.kernel.reference import INFO_KEYS, SCENARIOS, WINNERS, load, summary
from vooga_env.game.outcome import Outcome
from vooga_env.kernel import VectorFight
from vooga_env.policies import make_policy

STEPS = 2000  # the whole reference games
# the references' winner codes (reference.WINNERS) as the batched engine's Outcome codes
WINNER_CODES = {code: Outcome.from_info(winner) for winner, code in WINNERS.items()}


def same(got, expected, what: str) -> None:
    got, expected = np.asarray(got), np.asarray(expected)
    assert got.dtype == expected.dtype or got.dtype.kind == expected.dtype.kind == "b", what
    assert got.tobytes() == expected.tobytes(), f"{what}: {got!r} != {expected!r}"


def state(fights: VectorFight, i: int) -> np.ndarray:
    s = fights.state
    return np.array([[s.x[f, i], s.y[f, i], s.vx[f, i], s.vy[f, i]] for f in (0, 1)])


def replay(scenario, steps: int) -> dict[str, int]:
    """One fight of the batched engine plays a reference game's actions; every step compared."""
    expected = load(scenario)
    fights = VectorFight(1, config=scenario.config, **dict(scenario.overrides))
    same(fights.reset(seed=scenario.seed)[0], expected["reset_obs"][0], "first observation")
    resets = iter(range(1, len(expected["reset_steps"])))
    for t in range(steps):
        events, rewards, terminated, truncated, winner = fights.advance(
            expected["actions"][t : t + 1]
        )
        same(state(fights, 0), expected["state"][t], f"positions and velocities at step {t}")
        same(fights.observe()[0], expected["obs"][t], f"observations at step {t}")
        same(rewards[0], expected["rewards"][t], f"rewards at step {t}")
        same(terminated[0], expected["terminated"][t], f"terminated at step {t}")
        same(truncated[0], expected["truncated"][t], f"truncated at step {t}")
        info = np.array(
            [
                [
                    fights.state.health[f, 0],
                    fights.state.stocks[f, 0],
                    events.hits_landed[f, 0],
                    events.hits_blocked[f, 0],
                    events.damage_dealt[f, 0],
                    events.damage_taken[f, 0],
                    events.rung_out[f, 0],
                    events.knocked_out[f, 0],
                ]
                for f in (0, 1)
            ],
            dtype=np.float64,
        )
        same(info, expected["info"][t], f"infos ({', '.join(INFO_KEYS)}) at step {t}")
        same(winner[0], WINNER_CODES[int(expected["winner"][t])], f"winner at step {t}")
        if terminated[0] or truncated[0]:
            k = next(resets)
            assert expected["reset_steps"][k] == t
            same(fights.reset_done(np.array([True]))[0], expected["reset_obs"][k], f"reset {k}")
    return summary(
        {key: value[:steps] for key, value in expected.items() if key != "reset_steps"}
        | {"reset_steps": expected["reset_steps"][expected["reset_steps"] < steps]}
    )


def test_one_batched_fight_replays_every_reference_game():
    totals: dict[str, int] = {}
    for scenario in SCENARIOS:
        for key, count in replay(scenario, STEPS).items():
            totals[key] = totals.get(key, 0) + count
    # the games went through every kind of event (summary of the steps that were compared)
    assert all(count > 0 for count in totals.values()), totals


def side_by_side(
    steps: int,
    fights_in_batch: int = 6,
    seed: int = 40,
    config: str = "default",
    threads: int = 1,
    **overrides,
) -> dict:
    """N single envs and one batch of N, the same seeds and actions; compared at every step."""
    overrides = overrides or dict(max_cycles=150, fighter={"health": 20.0})
    singles = [
        vooga_env.parallel_env(config=config, backend="engine", **overrides)
        for _ in range(fights_in_batch)
    ]
    observations = [env.reset(seed=seed + i)[0] for i, env in enumerate(singles)]
    fights = VectorFight(fights_in_batch, config=config, threads=threads, **overrides)
    batch_obs = fights.reset(seed=seed)
    names = ["rush", "turtle", "zoner", "edge_guard", "random"]
    policies = [
        [make_policy(names[(i + seat) % len(names)], 10 * i + seat) for seat in (0, 1)]
        for i in range(fights_in_batch)
    ]
    rng = np.random.default_rng(seed)
    agents = ("fighter_0", "fighter_1")
    counts = dict(hits=0, blocks=0, ring_outs=0, knock_outs=0, terminations=0, truncations=0)
    for i, obs in enumerate(observations):
        same(batch_obs[i], np.stack([obs[a] for a in agents]), f"fight {i} first observation")
    for t in range(steps):
        actions = np.array(
            [
                [
                    rng.integers(10) if rng.random() < 0.2 else policy.act(observations[i][agent])
                    for policy, agent in zip(policies[i], agents)
                ]
                for i in range(fights_in_batch)
            ]
        )
        batch_obs, rewards, terminated, truncated, info = fights.step(actions)
        finals = dict(zip(info["done_index"].tolist(), info["final_observation"]))
        for i, env in enumerate(singles):
            obs, reward, term, trunc, infos = env.step(dict(zip(agents, actions[i].tolist())))
            where = f"fight {i}, step {t}"
            stacked = np.stack([obs[a] for a in agents])
            same(rewards[i], np.array([reward[a] for a in agents]), f"{where}: rewards")
            same(terminated[i], term["fighter_0"], f"{where}: terminated")
            same(truncated[i], trunc["fighter_0"], f"{where}: truncated")
            for f, agent in enumerate(agents):
                for key in INFO_KEYS:
                    assert info[key][f, i] == infos[agent][key], f"{where}: {agent} {key}"
            counts["hits"] += infos["fighter_0"]["hits_landed"] + infos["fighter_1"]["hits_landed"]
            counts["blocks"] += (
                infos["fighter_0"]["hits_blocked"] + infos["fighter_1"]["hits_blocked"]
            )
            counts["ring_outs"] += infos["fighter_0"]["rung_out"] + infos["fighter_1"]["rung_out"]
            counts["knock_outs"] += (
                infos["fighter_0"]["knocked_out"] + infos["fighter_1"]["knocked_out"]
            )
            if term["fighter_0"] or trunc["fighter_0"]:
                counts["terminations"] += term["fighter_0"]
                counts["truncations"] += trunc["fighter_0"]
                same(finals.pop(i), stacked, f"{where}: final observation")
                winner = infos["fighter_0"]["winner"]
                assert info["winner"][i] == Outcome.from_info(winner)
                obs, _ = env.reset()
                stacked = np.stack([obs[a] for a in agents])
            else:
                assert info["winner"][i] == Outcome.GOING_ON
            same(batch_obs[i], stacked, f"{where}: observations")
            fighters = env.fight.fighters
            expected = np.array([[f.x, f.y, f.vx, f.vy] for f in fighters])
            same(state(fights, i), expected, f"{where}: positions and velocities")
            observations[i] = obs
        assert not finals, "the batch ended fights the single envs did not"
    return counts


def test_a_batch_of_fights_matches_single_envs_step_by_step():
    counts = side_by_side(STEPS)
    assert all(count > 0 for count in counts.values()), counts


def test_a_batch_stepped_on_three_threads_matches_single_envs():
    counts = side_by_side(STEPS, threads=3)
    assert all(count > 0 for count in counts.values()), counts


VARIANTS = {
    "water, 3 frames a step, no air jumps": (
        "water",
        dict(frame_skip=3, max_cycles=120, fighter={"air_jumps": 0, "health": 30.0}),
    ),
    "platforms, no friction, no jitter": (
        "platforms",
        dict(max_cycles=120, physics={"ground_friction": 0.0}, arena={"spawn_jitter": 0.0}),
    ),
    "no edge shaping, a time penalty, a win on time paid, 2 stocks": (
        "small",
        dict(
            max_cycles=120,
            stocks=2,
            rewards={"edge": 0.0, "time_penalty": 0.01, "time_out": 5.0},
        ),
    ),
}


@pytest.mark.parametrize("variant", VARIANTS)
def test_config_variants_match_single_envs(variant):
    config, overrides = VARIANTS[variant]
    counts = side_by_side(STEPS // 6, 4, 7, config, **overrides)
    assert counts["hits"] > 0
