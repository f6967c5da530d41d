"""The league: PFSP draws, the pool opponent, and smoke runs (snapshots, exploiters, resume)."""

from __future__ import annotations

import json

import numpy as np
import pytest

pytest.importorskip("stable_baselines3")

from agents.league import load_league_config, main, train_league  # noqa: E402
from agents.league_pool import Pool, PoolOpponent  # noqa: E402
from vooga_env.game.config import ConfigError  # noqa: E402
from vooga_env.policies.batched import VectorOpponent, scripted_actions  # noqa: E402
from vooga_env.policies.models import load_model  # noqa: E402


def test_pfsp_draws_the_opponent_the_learner_beats_least_far_more_often():
    pool = Pool(window=10)
    pool.add("beaten", VectorOpponent("idle"), [1.0] * 9 + [0.0])  # p = 0.9
    pool.add("hard", VectorOpponent("rush"), [0.0] * 9 + [1.0])  # p = 0.1
    rng = np.random.default_rng(0)
    draws = [pool.draw(rng) for _ in range(2000)]
    hard = draws.count("hard") / len(draws)
    assert pool.weights() == pytest.approx([0.05 / 0.86, 0.81 / 0.86])  # (1-p)^2, floor 0.05
    assert 0.9 < hard < 0.97
    even = Pool(window=10, weighting="even")
    even.add("a", None, [1.0])
    even.add("b", None, [0.0])
    assert even.weights() == pytest.approx([0.5, 0.5])
    with pytest.raises(ValueError, match="pfsp = 'greedy'"):
        Pool(window=10, weighting="greedy")


def test_the_pool_opponent_asks_each_member_for_its_own_fights():
    pool = Pool(window=4)
    pool.add("idle", VectorOpponent("idle"))
    pool.add("rush", VectorOpponent("rush", seed=7))
    opponent = PoolOpponent(pool, 6)
    opponent.assigned = ["rush", "idle", "rush", "idle", "idle", "rush"]
    observations = np.random.default_rng(1).uniform(-1, 1, (6, 41)).astype(np.float32)
    actions = opponent.act(observations)
    rush_rows = [0, 2, 5]
    expected = scripted_actions("rush", observations[rush_rows], np.random.default_rng(7).random(3))
    assert actions[rush_rows].tolist() == expected.tolist()
    assert actions[[1, 3, 4]].tolist() == [0, 0, 0]


def test_a_smoke_league_pools_snapshots_and_exploiters_and_resumes(tmp_path):
    config = load_league_config("smoke", total_timesteps=2048)
    train_league(config, tmp_path, progress=False)
    state = json.loads((tmp_path / "train_state.json").read_text())
    assert state["snapshots"] == ["snapshot_1024", "snapshot_2048"]  # window 2
    assert state["exploiters"] == ["exploiter_2048"]
    assert (tmp_path / "exploiters" / "exploiter_2048.zip").is_file()
    assert sum(len(state["results"][name]) for name in ("rush", "punisher")) > 0
    assert state["ratings"]["learner"] != 1200.0  # Elo moved with the games
    final = train_league(load_league_config("smoke"), tmp_path, resume=True, progress=False)
    assert load_model(final).num_timesteps == 4096
    resumed = json.loads((tmp_path / "train_state.json").read_text())
    assert resumed["snapshots"] == ["snapshot_3072", "snapshot_4096"]


def test_self_play_from_scratch_has_only_snapshots(tmp_path, capsys):
    path = tmp_path / "selfplay.toml"
    path.write_text(
        'fight = "small"\ntotal_timesteps = 1024\nfights = 4\n[ppo]\nn_steps = 64\n'
        "batch_size = 256\nn_epochs = 1\n[league]\nsave_steps = 512\nscripted = []\n"
    )
    assert main(["--config", str(path), "--out", str(tmp_path / "run"), "--no-progress"]) == 0
    assert "learner score %" in capsys.readouterr().out
    state = json.loads((tmp_path / "run" / "train_state.json").read_text())
    assert set(state["results"]) == {"snapshot_0", "snapshot_512", "snapshot_1024"}


def test_bad_league_settings_are_refused_by_name(tmp_path, capsys):
    with pytest.raises(ConfigError, match="pfsp = 'greedy' is not allowed"):
        load_league_config("smoke", league={"pfsp": "greedy"})
    with pytest.raises(ConfigError, match="scripted = 'ninja' is not allowed"):
        load_league_config("smoke", league={"scripted": ["ninja"]})
    with pytest.raises(SystemExit) as stop:
        main(["--config", "smoke", "--out", str(tmp_path), "--resume"])
    assert stop.value.code == 2 and "no checkpoint" in capsys.readouterr().err
