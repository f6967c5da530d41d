"""`python -m agents.play`: the key -> action mapping, and a few headless frames driven by
synthetic pygame key events (SDL's dummy video driver)."""

from __future__ import annotations

import json

import pygame
import pytest

from agents import play
from agents.play import InputHandler, action_from_keys, run_play
from vooga_env.actions import Action
from vooga_env.policies import make_policy
from vooga_env.replay import Replay, play_back

K = pygame


@pytest.mark.parametrize(
    "keys, seat, action",
    [
        ((), 0, Action.IDLE),
        ((K.K_RIGHT,), 0, Action.RIGHT),
        ((K.K_d,), 0, Action.RIGHT),
        ((K.K_LEFT,), 0, Action.LEFT),
        ((K.K_a,), 1, Action.RIGHT),  # fighter_1 is mirrored: screen-left is its right
        ((K.K_RIGHT,), 1, Action.LEFT),
        ((K.K_LEFT, K.K_RIGHT), 0, Action.IDLE),
        ((K.K_UP,), 0, Action.JUMP),
        ((K.K_SPACE, K.K_LEFT), 0, Action.JUMP_LEFT),
        ((K.K_w, K.K_d), 0, Action.JUMP_RIGHT),
        ((K.K_w, K.K_d), 1, Action.JUMP_LEFT),
        ((K.K_DOWN,), 0, Action.DOWN),
        ((K.K_s, K.K_RIGHT), 0, Action.DOWN),
        ((K.K_j,), 0, Action.PUNCH),
        ((K.K_z, K.K_UP), 0, Action.PUNCH),
        ((K.K_k,), 1, Action.KICK),
        ((K.K_x, K.K_j), 0, Action.KICK),
        ((K.K_l, K.K_k, K.K_RIGHT), 0, Action.BLOCK),
        ((K.K_c,), 0, Action.BLOCK),
        ((K.K_q,), 0, Action.IDLE),
    ],
)
def test_keys_map_to_actions(keys, seat, action):
    assert action_from_keys(set(keys), seat) == action


def test_input_handler_tracks_held_keys():
    handler = InputHandler(seat=0)
    handler.handle(pygame.event.Event(pygame.KEYDOWN, key=K.K_RIGHT))
    handler.handle(pygame.event.Event(pygame.KEYDOWN, key=K.K_k))
    assert handler.action() == Action.KICK
    handler.handle(pygame.event.Event(pygame.KEYUP, key=K.K_k))
    assert handler.action() == Action.RIGHT
    handler.handle(pygame.event.Event(pygame.WINDOWFOCUSLOST))
    assert handler.action() == Action.IDLE and not handler.quit
    handler.handle(pygame.event.Event(pygame.KEYDOWN, key=K.K_ESCAPE))
    assert handler.quit


def scripted_keys(script):
    """A get_events that posts step t's synthetic events to pygame's queue, then reads the queue."""
    step = iter(range(10_000))

    def get_events():
        for event_type, key in script.get(next(step), ()):
            event = (
                pygame.event.Event(event_type, key=key) if key else pygame.event.Event(event_type)
            )
            pygame.event.post(event)
        return pygame.event.get()

    return get_events


@pytest.fixture
def headless(monkeypatch):
    monkeypatch.setenv("SDL_VIDEODRIVER", "dummy")


def test_a_few_frames_with_synthetic_keys(headless):
    script = {
        0: [(pygame.KEYDOWN, K.K_RIGHT)],
        6: [(pygame.KEYUP, K.K_RIGHT), (pygame.KEYDOWN, K.K_k)],
        7: [(pygame.KEYUP, K.K_k)],
    }
    record, config = run_play(
        make_policy("idle"),
        seat=0,
        config="default",
        seed=0,
        max_steps=10,
        get_events=scripted_keys(script),
    )
    mine = [pair[0] for pair in record.actions]
    assert mine == [Action.RIGHT] * 6 + [Action.KICK] + [Action.IDLE] * 3
    assert all(pair[1] == Action.IDLE for pair in record.actions)
    assert record.names == ("human", "idle") and record.steps == 10
    assert record.positions[0][0] > config.arena.spawns[0]  # walked right
    played = play_back(Replay.from_episode(record, config))  # raises if it differs
    assert played.positions == record.positions


def test_seat_one_and_quitting(headless):
    script = {0: [(pygame.KEYDOWN, K.K_LEFT)], 4: [(pygame.QUIT, None)]}
    record, config = run_play(
        make_policy("idle"), seat=1, max_steps=50, get_events=scripted_keys(script)
    )
    assert record.steps == 4 and record.winner is None
    assert [pair[1] for pair in record.actions] == [Action.RIGHT] * 4  # mirrored
    assert record.positions[1][0] < config.arena.spawns[1]  # walked left on the screen


def test_cli_saves_a_replay(headless, tmp_path, capsys):
    path = tmp_path / "me.json"
    assert play.main(["rush", "--max-cycles", "6", "--save-replay", str(path)]) == 0
    assert "punch: J or Z" in capsys.readouterr().out
    data = json.loads(path.read_text())
    assert data["names"] == ["human", "rush"] and len(data["actions"]) == 6
    assert all(pair[0] == Action.IDLE for pair in data["actions"])
    play_back(Replay.load(path))


def test_cli_unknown_opponent(capsys):
    with pytest.raises(SystemExit):
        play.main(["ninja"])
    assert "unknown policy 'ninja'" in capsys.readouterr().err
