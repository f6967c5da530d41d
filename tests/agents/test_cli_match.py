"""`python -m agents.match` and `python -m agents.tournament`: tables, JSON, files, clean errors."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest
from PIL import Image

from agents import common, match, tournament
from vooga_env.policies import SCRIPTED

ROOT = Path(__file__).resolve().parents[2]


def run_json(main, argv, capsys):
    assert main([*argv, "--json", "--no-progress"]) == 0
    return json.loads(capsys.readouterr().out)


def test_match_json_table_is_consistent(capsys):
    data = run_json(
        match.main, ["rush", "turtle", "--episodes", "6", "--max-cycles", "150"], capsys
    )
    assert data["games"] == 6 and data["names"] == ["rush", "turtle"]
    assert data["max_cycles"] == 150 and data["config"] == "default"
    rush, turtle = data["sides"]
    for side in (rush, turtle):
        assert side["wins"] + side["losses"] + side["draws"] == 6
    assert rush["wins"] == turtle["losses"] and rush["draws"] == turtle["draws"]
    assert 0 < data["mean_length"] <= 150


def test_match_prints_a_table(capsys):
    assert (
        match.main(["rush", "idle", "--episodes", "2", "--max-cycles", "100", "--no-progress"]) == 0
    )
    out = capsys.readouterr().out
    for word in ("wins", "losses", "draws", "ring-outs", "KOs", "mean damage", "mean length"):
        assert word in out
    lines = out.splitlines()
    assert lines[0].startswith("rush vs idle: 2 games")
    rows = [line.split() for line in lines[3:5]]
    assert [row[0] for row in rows] == ["rush", "idle"]
    assert int(rows[0][1]) + int(rows[0][2]) + int(rows[0][3]) == 2


def test_same_policy_on_both_sides_is_told_apart(capsys):
    data = run_json(match.main, ["idle", "idle", "--episodes", "2", "--max-cycles", "5"], capsys)
    assert data["names"] == ["idle (A)", "idle (B)"]
    assert [side["draws"] for side in data["sides"]] == [2, 2]


def test_record_and_replay_round_trip(tmp_path, capsys):
    gif, replay = tmp_path / "first.gif", tmp_path / "first.json"
    argv = [
        "zoner",
        "rush",
        "--episodes",
        "2",
        "--max-cycles",
        "60",
        "--record",
        str(gif),
        "--record-scale",
        "2",
        "--save-replay",
        str(replay),
    ]
    data = run_json(match.main, argv, capsys)
    assert data["record"] == str(gif) and data["replay"] == str(replay)
    with Image.open(gif) as image:
        assert image.size == (400, 240) and image.n_frames > 1
    saved = json.loads(replay.read_text())
    assert saved["names"] == ["zoner", "rush"]
    played = run_json(match.main, ["--replay", str(replay)], capsys)
    assert played["matches_recording"] is True
    assert played["steps"] == len(saved["actions"]) == saved["result"]["steps"]
    assert played["winner"] == saved["result"]["winner"]
    assert played["result"]["positions"] == saved["result"]["positions"]


def test_a_doctored_replay_fails(tmp_path, capsys):
    replay = tmp_path / "game.json"
    run_json(
        match.main,
        ["rush", "idle", "--episodes", "1", "--max-cycles", "40", "--save-replay", str(replay)],
        capsys,
    )
    data = json.loads(replay.read_text())
    data["result"]["health"][0] -= 1.0
    replay.write_text(json.dumps(data))
    assert match.main(["--replay", str(replay), "--no-progress"]) == 1
    assert "health" in capsys.readouterr().err


def test_watching_in_a_window_headless(tmp_path, capsys, monkeypatch):
    monkeypatch.setenv("SDL_VIDEODRIVER", "dummy")
    gif = tmp_path / "watched.gif"
    data = run_json(
        match.main,
        ["rush", "idle", "--episodes", "1", "--max-cycles", "8", "--render", "--record", str(gif)],
        capsys,
    )
    assert data["games"] == 1
    with Image.open(gif) as image:
        assert image.size == (800, 480)


def test_closing_the_window_stops_a_watched_match(monkeypatch):
    monkeypatch.setenv("SDL_VIDEODRIVER", "dummy")
    import pygame

    pygame.display.init()
    try:
        pygame.display.set_mode((40, 30))
        pygame.event.clear()
        for _ in range(50):
            pygame.event.post(pygame.event.Event(pygame.KEYDOWN, key=pygame.K_a))
        common.stop_on_window_close(None)  # other keys: go on, and empty the queue
        assert pygame.event.peek(pygame.KEYDOWN) is False
        pygame.event.post(pygame.event.Event(pygame.QUIT))
        with pytest.raises(common.WindowClosed):
            common.stop_on_window_close(None)
        pygame.event.post(pygame.event.Event(pygame.KEYDOWN, key=pygame.K_ESCAPE))
        with pytest.raises(common.WindowClosed):
            common.stop_on_window_close(None)
    finally:
        pygame.display.quit()


@pytest.mark.parametrize(
    "argv, needle",
    [
        (["rush", "bogus"], "unknown policy 'bogus'"),
        (["rush", "missing.zip"], "no saved model"),
        (["rush", "idle", "--config", "nope"], "unknown config 'nope'"),
        (["rush"], "two policies"),
        (["--replay", "missing.json"], "cannot read replay"),
        (["rush", "idle", "--record", "out.png"], ".gif or .mp4"),
        (["--replay", "missing.json", "--record", "out.webm"], ".gif or .mp4"),
    ],
)
def test_bad_input_is_a_usage_error(argv, needle, capsys):
    with pytest.raises(SystemExit) as stop:
        match.main(argv)
    assert stop.value.code == 2
    err = capsys.readouterr().err
    assert needle in err
    if "policy" in needle or "model" in needle:
        assert all(name in err for name in SCRIPTED)


def test_unknown_policy_from_the_shell_lists_the_known_ones():
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    done = subprocess.run(
        [sys.executable, "-m", "agents.match", "rush", "kungfu", "--episodes", "1"],
        capture_output=True,
        text=True,
        cwd=ROOT,
        env=env,
        timeout=60,
    )
    assert done.returncode == 2
    assert "Traceback" not in done.stderr
    assert "unknown policy 'kungfu'" in done.stderr
    assert all(name in done.stderr for name in SCRIPTED)


def test_tournament_prints_and_writes_elo(tmp_path, capsys):
    out = tmp_path / "runs" / "elo.json"
    argv = [
        "--scripted",
        "rush",
        "idle",
        "turtle",
        "--episodes",
        "2",
        "--max-cycles",
        "300",
        "--out",
        str(out),
    ]
    data = run_json(tournament.main, argv, capsys)
    assert json.loads(out.read_text()) == data
    assert data["k_factor"] == 16.0 and data["start_rating"] == 1200.0
    assert data["episodes_per_pairing"] == 2 and len(data["pairings"]) == 3
    assert [row["name"] for row in data["ratings"]][-1] == "idle"
    assert sum(row["rating"] for row in data["ratings"]) == pytest.approx(3600.0)
    for row in data["ratings"]:
        assert row["wins"] + row["losses"] + row["draws"] == row["games"] == 4

    assert tournament.main([*argv, "--no-progress"]) == 0
    text = capsys.readouterr().out
    assert "K=16" in text and "start rating 1200" in text and str(out) in text
    assert "score % of the row against the column" in text


def test_tournament_writes_no_file_unasked(tmp_path, monkeypatch, capsys):
    monkeypatch.chdir(tmp_path)
    argv = ["--scripted", "rush", "idle", "--episodes", "1", "--max-cycles", "50", "--json"]
    assert "out" not in run_json(tournament.main, argv, capsys)
    assert list(tmp_path.iterdir()) == []


def test_tournament_refuses_a_bad_entrant(capsys):
    with pytest.raises(SystemExit):
        tournament.main(["--scripted", "rush", "--models", "nope.zip"])
    assert "no saved model" in capsys.readouterr().err
