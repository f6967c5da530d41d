"""`agents.evaluate`'s style rows: per opponent and play, results, endings, actions, attacks."""

from __future__ import annotations

import json

import pytest

pytest.importorskip("stable_baselines3")

from agents import evaluate  # noqa: E402


def report(capsys, *argv: str) -> dict:
    common = ["--episodes", "2", "--max-cycles", "60", "--json", "--no-progress"]
    assert evaluate.main([*argv, *common]) == 0
    return json.loads(capsys.readouterr().out)


def test_a_model_is_shown_sampled_and_argmax_against_each_opponent(tiny_model, capsys):
    rows = report(capsys, str(tiny_model), "--opponents", "idle", "rush")["style"]
    assert [(row["opponent"], row["play"]) for row in rows] == [
        ("idle", "sampled"),
        ("idle", "argmax"),
        ("rush", "sampled"),
        ("rush", "argmax"),
    ]
    for row in rows:
        assert row["games"] == row["wins"] + row["draws"] + row["losses"] == 2
        assert sum(row["endings"].values()) == 2
        assert sum(row["actions"].values()) == pytest.approx(1.0)
        low, high = row["ci95"]
        assert low <= row["win_rate"] <= high
    argmax = [row for row in rows if row["play"] == "argmax"]
    plain = report(capsys, str(tiny_model), "--opponents", "idle", "rush")["opponents"]
    assert [row["wins"] for row in argmax] == [row["wins"] for row in plain]  # the same games


def test_one_play_on_request_and_a_scripted_fighter_plays_as_it_is(tiny_model, capsys):
    rows = report(capsys, str(tiny_model), "--opponents", "idle", "--argmax")["style"]
    assert [row["play"] for row in rows] == ["argmax"]
    rows = report(capsys, "rush", "--opponents", "idle", "zoner")["style"]
    assert [row["play"] for row in rows] == ["scripted", "scripted"]
    assert rows[0]["win_rate"] == 1.0 and rows[0]["attacks"]["punch"]["landed"] > 0


def test_the_text_report_has_the_style_tables(capsys):
    argv = ["rush", "--opponents", "idle", "--episodes", "2", "--max-cycles", "100"]
    assert evaluate.main([*argv, "--no-progress"]) == 0
    out = capsys.readouterr().out
    assert "punches landed/tried" in out and "its actions (% of its steps)" in out
