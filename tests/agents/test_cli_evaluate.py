"""`python -m agents.evaluate`: win rates with Wilson intervals and an Elo, for a scripted stand-in
and for a real (tiny) saved PPO model."""

from __future__ import annotations

import json

import pytest

from agents import evaluate, match


def run_json(argv, capsys):
    assert evaluate.main([*argv, "--json", "--no-progress"]) == 0
    return json.loads(capsys.readouterr().out)


def check_report(report, opponents, episodes):
    assert [row["opponent"] for row in report["opponents"]] == opponents
    for row in [*report["opponents"], report["overall"]]:
        low, high = row["ci95"]
        assert 0.0 <= low <= row["win_rate"] <= high <= 1.0
        assert high > low
    for row in report["opponents"]:
        assert row["games"] == episodes
        assert row["wins"] + row["draws"] + row["losses"] == episodes
        assert row["win_rate"] == row["wins"] / episodes
    overall = report["overall"]
    assert overall["games"] == episodes * len(opponents)
    assert overall["wins"] + overall["draws"] + overall["losses"] == overall["games"]
    assert overall["wins"] == sum(row["wins"] for row in report["opponents"])
    assert 1 <= report["elo_rank"] <= report["entrants"] == len(opponents) + 1


def test_scripted_stand_in(tmp_path, capsys):
    out = tmp_path / "eval.json"
    report = run_json(
        [
            "rush",
            "--opponents",
            "idle",
            "turtle",
            "--episodes",
            "4",
            "--max-cycles",
            "300",
            "--out",
            str(out),
        ],
        capsys,
    )
    check_report(report, ["idle", "turtle"], 4)
    assert json.loads(out.read_text()) == report
    idle, turtle = report["opponents"]
    assert idle["win_rate"] == 1.0 and turtle["win_rate"] == 0.0
    assert report["elo_rank"] == 2


def test_evaluating_a_scripted_fighter_against_itself(capsys):
    report = run_json(
        ["idle", "--opponents", "idle", "--episodes", "2", "--max-cycles", "5"], capsys
    )
    assert report["name"] == "idle (evaluated)"
    assert report["opponents"][0]["draws"] == 2


def test_text_report(capsys):
    argv = [
        "rush",
        "--opponents",
        "idle",
        "--episodes",
        "2",
        "--max-cycles",
        "100",
        "--no-progress",
    ]
    assert evaluate.main(argv) == 0
    out = capsys.readouterr().out
    assert "95% CI (Wilson)" in out and "Elo" in out and "rush  <-" in out


def test_saved_model(tiny_model, capsys):
    report = run_json(
        [str(tiny_model), "--opponents", "idle", "rush", "--episodes", "2", "--max-cycles", "60"],
        capsys,
    )
    assert report["name"] == "tiny" and report["model"] == str(tiny_model)
    check_report(report, ["idle", "rush"], 2)


def test_saved_model_in_a_match(tiny_model, capsys):
    assert (
        match.main(
            [
                str(tiny_model),
                "rush",
                "--episodes",
                "2",
                "--max-cycles",
                "40",
                "--json",
                "--no-progress",
            ]
        )
        == 0
    )
    data = json.loads(capsys.readouterr().out)
    assert data["names"] == ["tiny", "rush"] and data["games"] == 2


def test_unknown_model_name(capsys):
    with pytest.raises(SystemExit) as stop:
        evaluate.main(["ppo_final"])
    assert stop.value.code == 2
    assert "edge_guard" in capsys.readouterr().err
