"""Replays: written from a game, played back bit-identically, and refused when they disagree."""

from __future__ import annotations

import json

import numpy as np
import pytest

import vooga_env
from vooga_env.match import play_episode
from vooga_env.policies import make_policy
from vooga_env.replay import FORMAT, VERSION, Replay, ReplayError, ReplayMismatch, play_back

# Spawn jitter makes the seed matter, and an override checks that the resolved config is stored.
OVERRIDES = {"max_cycles": 150, "arena": {"spawn_jitter": 25.0}, "physics": {"gravity": 0.0025}}


@pytest.fixture
def game(tmp_path):
    env = vooga_env.parallel_env(config="small", **OVERRIDES)
    policies = [make_policy("random"), make_policy("rush")]
    record = play_episode(
        env,
        policies,
        seed=1234,
        policy_seeds=(7, 8),
        record_actions=True,
        record_observations=True,
    )
    path = Replay.from_episode(record, env.config).save(tmp_path / "game.json")
    env.close()
    return record, env.config, path


def test_playback_is_bit_identical(game):
    record, config, path = game
    replay = Replay.load(path)
    assert replay.config == config
    assert replay.config.physics.gravity == 0.0025 and replay.config.name == "small"
    played = play_back(replay, record_observations=True)
    assert played.actions == record.actions
    assert len(played.observations) == len(record.observations) == record.steps + 1
    for original, again in zip(record.observations, played.observations, strict=True):
        assert original.dtype == again.dtype == np.float32
        assert np.array_equal(original, again)
    assert (played.winner, played.steps, played.health, played.positions) == (
        record.winner,
        record.steps,
        record.health,
        record.positions,
    )


def test_file_holds_what_it_says(game):
    record, config, path = game
    data = json.loads(path.read_text())
    assert data["format"] == FORMAT and data["version"] == VERSION
    assert data["config_name"] == "small" and data["max_cycles"] == 150
    assert data["config"]["arena"]["spawn_jitter"] == 25.0
    assert data["seed"] == 1234 and data["names"] == ["random", "rush"]
    assert data["policy_seeds"] == [7, 8]
    assert len(data["actions"]) == record.steps
    assert data["result"]["winner"] == record.winner
    assert data["result"]["positions"] == record.positions


def test_a_changed_seed_or_action_is_caught(game):
    _, _, path = game
    replay = Replay.load(path)
    replay.seed += 1  # another spawn jitter: another game, however it comes to differ
    with pytest.raises(ReplayMismatch):
        play_back(replay)
    replay = Replay.load(path)
    replay.actions[0] = (replay.actions[0][0], (replay.actions[0][1] + 5) % 10)
    with pytest.raises(ReplayMismatch):
        play_back(replay)
    replay = Replay.load(path)
    replay.actions.extend(replay.actions[:1] * 1000)  # more actions than the fight has steps
    with pytest.raises(ReplayMismatch, match="ended after"):
        play_back(replay)


def test_playback_renders_the_same_game(game):
    record, _, path = game
    played = play_back(Replay.load(path), render_mode="rgb_array", record_frames=True)
    assert len(played.frames) == record.steps + 1
    assert played.frames[0].shape == (480, 640, 3)
    assert played.positions == record.positions


@pytest.mark.parametrize(
    "change, message",
    [
        ({"format": "other"}, "not a vooga_env replay"),
        ({"version": 99}, "version 99"),
        ({"actions": [[0, 10]]}, r"actions\[0\]"),
        ({"actions": [[0]]}, r"actions\[0\]"),
        ({"seed": -1}, "seed"),
        ({"config": {"arena": {"widht": 3}}}, "widht"),
    ],
)
def test_bad_files_are_refused_with_the_reason(game, tmp_path, change, message):
    _, _, path = game
    data = {**json.loads(path.read_text()), **change}
    bad = tmp_path / "bad.json"
    bad.write_text(json.dumps(data))
    with pytest.raises(ReplayError, match=message):
        Replay.load(bad)


def test_unreadable_files(tmp_path):
    with pytest.raises(ReplayError, match="cannot read"):
        Replay.load(tmp_path / "missing.json")
    (tmp_path / "junk.json").write_text("{not json")
    with pytest.raises(ReplayError, match="not JSON"):
        Replay.load(tmp_path / "junk.json")


def test_a_game_without_actions_makes_no_replay():
    env = vooga_env.parallel_env(max_cycles=3)
    record = play_episode(env, [make_policy("idle"), make_policy("idle")], seed=0)
    with pytest.raises(ValueError, match="record_actions"):
        Replay.from_episode(record, env.config)
