"""Replays: written from a game, played back bit-identically, and refused when they disagree."""

from __future__ import annotations

import dataclasses
import json
import re

import numpy as np
import pytest

import vooga_env
from vooga_env.game.actions import Action
from vooga_env.policies import make_policy
from vooga_env.tools.match import play_episode
from vooga_env.tools.replay import FORMAT, VERSION, Replay, ReplayError, ReplayMismatch, play_back

# Spawn jitter and a part-way start make the seed matter, and an override checks that the
# resolved config is stored.
OVERRIDES = {
    "max_cycles": 150,
    "arena": {"spawn_jitter": 25.0},
    "physics": {"gravity": 0.0025},
    "start": {"damage": 20.0, "steps": 60},
}


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
    assert data["config"]["start"] == {"damage": 20.0, "steps": 60}
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
        ({"version": True}, "version True"),
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


def edited(replay: Replay, step: int, seat: int) -> Replay:
    """The replay with one action changed: seat `seat`'s at `step`, to another action."""
    actions = list(replay.actions)
    pair = list(actions[step])
    pair[seat] = (pair[seat] + 1 + step % 9) % len(Action)  # never the same action
    actions[step] = (pair[0], pair[1])
    return dataclasses.replace(replay, actions=actions)


def observations(replay: Replay) -> list[np.ndarray] | None:
    """Every step's observations when played unchecked (None: the fight ended before the end)."""
    try:
        return play_back(replay, record_observations=True, check=False).observations
    except ReplayMismatch:
        return None


def catch_every_edit(replay: Replay) -> tuple[int, int, int]:
    """Edit each action of each fighter in turn; return (edits, caught at their step, edits
    that changed the game's state, which the outcome alone would not always show)."""
    original = observations(replay)
    edits = caught = changed = 0
    for step in range(len(replay.actions)):
        for seat in (0, 1):
            bad = edited(replay, step, seat)
            edits += 1
            with pytest.raises(ReplayMismatch, match=f"step {step} differs") as mismatch:
                play_back(bad)
            caught += mismatch.value.step == step
            played = observations(bad)
            changed += played is None or any(
                not np.array_equal(a, b) for a, b in zip(original, played, strict=True)
            )
    return edits, caught, changed


def test_every_single_edited_action_is_caught_at_its_own_step(game):
    _, _, path = game
    edits, caught, changed = catch_every_edit(Replay.load(path))
    assert caught == edits == 2 * len(Replay.load(path).actions)
    assert 0 < changed < edits  # some edits change nothing the outcome or state could show


@pytest.mark.slow
def test_every_edited_action_of_a_whole_default_game_is_caught():
    env = vooga_env.parallel_env(config="default")
    policies = [make_policy("zoner"), make_policy("edge_guard")]  # 413 steps
    record = play_episode(env, policies, seed=5, policy_seeds=(1, 2), record_actions=True)
    replay = Replay.from_episode(record, env.config)
    edits, caught, changed = catch_every_edit(replay)
    print(f"{caught} of {edits} edits caught at their step; {changed} changed the state")
    assert caught == edits


@pytest.mark.parametrize(
    "change",
    [{"names": ["random", "turtle"]}, {"policy_seeds": [7, 9]}, {"seed": 1235}],
    ids=["names", "policy_seeds", "seed"],
)
def test_an_edited_header_is_caught_before_playing(game, tmp_path, change):
    _, _, path = game
    bad = tmp_path / "bad.json"
    bad.write_text(json.dumps({**json.loads(path.read_text()), **change}))
    with pytest.raises(ReplayMismatch, match="the header differs from the recording"):
        play_back(Replay.load(bad))


def test_an_old_version_1_file_loads_and_is_checked_on_its_result(game, tmp_path):
    record, _, path = game
    data = json.loads(path.read_text())
    del data["digests"], data["header_digest"]
    old = tmp_path / "v1.json"
    old.write_text(json.dumps({**data, "version": 1}))
    replay = Replay.load(old)
    assert not replay.digests
    assert play_back(replay).positions == record.positions
    replay.actions[0] = (replay.actions[0][0], (replay.actions[0][1] + 5) % 10)
    with pytest.raises(ReplayMismatch, match="playback differs from the recording|ended after"):
        play_back(replay)


FIELDS = [
    ({"names": ["random"]}, "names = ['random'] is not allowed: two non-empty strings"),
    ({"names": "random rush"}, "names = 'random rush' is not allowed"),
    ({"names": ["random", 3]}, "names = ['random', 3] is not allowed"),
    ({"names": ["", "rush"]}, "names = ['', 'rush'] is not allowed"),
    ({"seed": True}, "seed = True is not allowed: an int >= 0"),
    ({"seed": 1.5}, "seed = 1.5 is not allowed"),
    ({"policy_seeds": [7]}, "policy_seeds = [7] is not allowed: two ints >= 0 or nulls"),
    ({"policy_seeds": [-1, None]}, "policy_seeds = [-1, None] is not allowed"),
    ({"actions": [[0, True]]}, r"actions[0] = [0, True] is not allowed: two ints in 0..9"),
    ({"actions": {"0": [0, 1]}}, "actions = {'0': [0, 1]} is not allowed"),
    ({"actions": [[0, 1]] * 151}, "actions = '151 steps' is not allowed: at most max_cycles"),
    ({"vooga_env": 3}, "vooga_env = 3 is not allowed: a version string"),
    ({"config_name": "water"}, "config_name = 'water' is not allowed: the config's own"),
    ({"max_cycles": 900}, "max_cycles = 900 is not allowed: the config's own max_cycles, 150"),
    ({"max_cycles": 150.0}, "max_cycles = 150.0 is not allowed"),
    ({"extra": 1}, "extra = 1 is not allowed: not a field of a version 2 replay"),
    ({"digests": ["00"]}, "digests = ['00'] is not allowed: a list of one digest per action"),
    ({"header_digest": "xyz"}, "header_digest = 'xyz' is not allowed: 16 hex digits"),
    ({"result": [1]}, "result = [1] is not allowed: a table of the game's result"),
]
RESULTS = [
    ({"winner": "me"}, "result.winner = 'me' is not allowed: fighter_0, fighter_1, draw or null"),
    ({"steps": 3}, "result.steps = 3 is not allowed: the number of actions"),
    ({"steps": -1}, "result.steps = -1 is not allowed: an int >= 0"),
    ({"health": ["x", 1]}, "result.health = ['x', 1] is not allowed: two finite numbers"),
    ({"health": [float("nan"), 1]}, "result.health = [nan, 1] is not allowed"),
    ({"stocks": [1.5, 1]}, "result.stocks = [1.5, 1] is not allowed: two ints >= 0"),
    ({"positions": [[1, 2]]}, "result.positions = [[1, 2]] is not allowed: two [x, y] pairs"),
    ({"ring_outs": [-1, 0]}, "result.ring_outs = [-1, 0] is not allowed"),
    ({"knock_outs": None}, "result.knock_outs = None is not allowed"),
    ({"damage_dealt": [1]}, "result.damage_dealt = [1] is not allowed"),
    ({"score": 3}, "result.score = 3 is not allowed: not a field of a result"),
]


@pytest.mark.parametrize("change, message", FIELDS, ids=[m for _, m in FIELDS])
def test_every_field_is_type_checked_on_load(game, tmp_path, change, message):
    _, _, path = game
    bad = tmp_path / "bad.json"
    bad.write_text(json.dumps({**json.loads(path.read_text()), **change}))
    with pytest.raises(ReplayError, match=re.escape(f"{bad}: ") + ".*" + re.escape(message)):
        Replay.load(bad)


@pytest.mark.parametrize("change, message", RESULTS, ids=[m for _, m in RESULTS])
def test_every_result_field_is_type_checked_on_load(game, tmp_path, change, message):
    _, _, path = game
    data = json.loads(path.read_text())
    data["result"] = {**data["result"], **change}
    bad = tmp_path / "bad.json"
    bad.write_text(json.dumps(data))
    with pytest.raises(ReplayError, match=re.escape(message)):
        Replay.load(bad)


def test_a_result_missing_a_field_is_refused(game, tmp_path):
    _, _, path = game
    data = json.loads(path.read_text())
    del data["result"]["winner"]
    bad = tmp_path / "bad.json"
    bad.write_text(json.dumps(data))
    with pytest.raises(ReplayError, match="result.winner = 'missing' is not allowed"):
        Replay.load(bad)


def test_an_edited_config_value_is_caught_at_the_first_step_it_changes(game, tmp_path):
    _, _, path = game
    data = json.loads(path.read_text())
    data["config"]["physics"]["gravity"] = 0.003
    bad = tmp_path / "bad.json"
    bad.write_text(json.dumps(data))
    with pytest.raises(ReplayMismatch, match=r"step \d+ differs from the recording") as mismatch:
        play_back(Replay.load(bad))
    assert mismatch.value.step is not None
