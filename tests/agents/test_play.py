"""`python -m agents.play`: the key -> action mapping, the game loop driven by a scripted key
source and a fake clock (no window: SDL's dummy driver for the drawing), the command line, and one
game in a real window under a virtual X display when Xvfb is installed."""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
import textwrap
from pathlib import Path

import pygame
import pytest

import vooga_env
from agents import play
from agents.play_keys import InputHandler, action_from_keys
from agents.play_loop import Game, Phase, PlaySettings, run
from agents.play_screens import Screens
from vooga_env.game.actions import Action
from vooga_env.game.observations import OBSERVATION_NAMES
from vooga_env.policies import make_policy
from vooga_env.tools.replay import Replay, play_back

K = pygame
FRAME_MS = 40  # the default config's env step: 2 frames of 20 ms, render_fps 25
ROOT = Path(__file__).resolve().parents[2]


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


def down(key):
    return pygame.event.Event(pygame.KEYDOWN, key=key)


def up(key):
    return pygame.event.Event(pygame.KEYUP, key=key)


def test_input_handler_tracks_held_keys():
    handler = InputHandler(seat=0)
    handler.handle(down(K.K_RIGHT))
    handler.handle(down(K.K_k))
    assert handler.action() == Action.KICK
    handler.handle(up(K.K_k))
    assert handler.action() == Action.RIGHT
    handler.handle(pygame.event.Event(pygame.WINDOWFOCUSLOST))
    assert handler.action() == Action.IDLE


class FakeClock:
    """pygame.time.Clock without the waiting: every tick is one frame at the asked rate."""

    def __init__(self):
        self.rates = []

    def tick(self, framerate=0):
        self.rates.append(framerate)
        return round(1000 / framerate)


class ScriptedKeys:
    """A key source that plays like a person watching the screen: each entry of the script waits
    until `when(game)` holds, then sends its events in that frame; frames in between send none."""

    def __init__(self, game, script):
        self.game = game
        self.script = list(script)
        self.frames = 0

    def __call__(self):
        self.frames += 1
        if self.script and self.script[0][0](self.game):
            return self.script.pop(0)[1]
        return []


TIME_LEFT = OBSERVATION_NAMES.index("time_left")


def walks_off(obs):
    """After 10 steps of 900 it walks off the stage (fighter_1's LEFT is the screen's right), so
    a person who walks off their own end at once falls first."""
    return Action.LEFT if obs[TIME_LEFT] < 1 - 10 / 900 else Action.IDLE


@pytest.fixture
def headless(monkeypatch):
    monkeypatch.setenv("SDL_VIDEODRIVER", "dummy")
    monkeypatch.setenv("SDL_AUDIODRIVER", "dummy")  # what main sets, restored after the test
    pygame.display.init()
    yield
    pygame.display.quit()


def new_game(rounds=3, opponent=walks_off, max_cycles=900, **settings):
    env = vooga_env.parallel_env(
        config="default", backend="engine", stocks=1, max_cycles=max_cycles
    )
    reported = []

    def on_round_end(record, game):
        reported.append((record, game.match.number))
        return f"replay-{len(reported)}.json"

    game = Game(
        env,
        make_policy(opponent),
        PlaySettings(rounds=rounds, **settings),
        on_round_end=on_round_end,
    )
    return game, reported


def phase(*phases):
    return lambda game: game.phase in phases


def after_steps(steps):
    return lambda game: game.phase is Phase.FIGHT and game.record.steps >= steps


def accepting(game):
    return game.phase in (Phase.ROUND_OVER, Phase.MATCH_OVER) and game.accepts_keys


def test_countdown_holds_the_fight_and_pause_freezes_it():
    game, _ = new_game()
    frames = round(3000 / FRAME_MS)
    for _ in range(frames - 1):
        game.frame([], FRAME_MS)
    assert game.phase is Phase.COUNTDOWN and game.record.steps == 0
    game.frame([down(K.K_p)], FRAME_MS)  # paused in the countdown: it stops counting
    for _ in range(50):
        game.frame([], FRAME_MS)
    assert game.paused and game.phase is Phase.COUNTDOWN and game.record.steps == 0
    game.frame([down(K.K_p)], FRAME_MS)
    assert game.phase is Phase.FIGHT and game.record.steps == 0  # the last countdown frame
    game.frame([down(K.K_RIGHT)], FRAME_MS)
    assert game.record.steps == 1 and not game.help_visible
    game.frame([down(K.K_p)], FRAME_MS)
    for _ in range(20):
        game.frame([], FRAME_MS)
    assert game.paused and game.record.steps == 1
    game.frame([down(K.K_p)], FRAME_MS)
    game.frame([], FRAME_MS)
    assert game.record.steps == 3 and [a for a, _ in game.record.actions] == [Action.RIGHT] * 3


def test_rounds_won_and_lost_then_restart_and_quit(headless):
    """Round 1: the person waits, the opponent walks off (won). Round 2: the person walks off
    first (lost). Then R on the result screen starts a new match, and Esc quits it."""
    game, reported = new_game(rounds=3)
    script = [
        (after_steps(5), [down(K.K_RETURN)]),  # mid-fight: ignored
        (phase(Phase.ROUND_OVER), [down(K.K_RETURN)]),  # inside the lockout: ignored
        (accepting, [down(K.K_RETURN)]),
        (phase(Phase.FIGHT), [down(K.K_LEFT)]),
        (phase(Phase.ROUND_OVER), [up(K.K_LEFT)]),
        (accepting, [down(K.K_r)]),
        (phase(Phase.FIGHT), [down(K.K_ESCAPE)]),
    ]
    keys = ScriptedKeys(game, script)
    screens = Screens(game, pygame.Surface((800, 480)))
    clock = FakeClock()
    frames = run(game, screens.draw, keys, clock, max_frames=5000)
    assert game.phase is Phase.QUIT and not keys.script and frames < 5000
    assert set(clock.rates) == {25.0}
    first, second = game.matches
    assert [(r.outcome, r.how) for r in first.rounds] == [("win", "ring-out"), ("loss", "ring-out")]
    assert first.outcome == "draw" and second.rounds == []
    records = [record for record, _ in reported]
    assert [match for _, match in reported] == [1, 1]  # Esc before a step of match 2: nothing
    assert [r.outcome(0) for r in records] == ["win", "loss"]
    assert all(pair[0] == Action.IDLE for pair in records[0].actions)
    assert {pair[0] for pair in records[1].actions} == {Action.LEFT}
    assert records[0].seed != records[1].seed  # each round its own seeds
    for record in records:
        assert record.names == ("human", "walks_off")
        played = play_back(Replay.from_episode(record, game.env.config))  # raises if it differs
        assert played.positions == record.positions
    assert game.last_saved == "replay-2.json"


def test_match_over_then_play_again(headless):
    game, reported = new_game(rounds=1)
    keys = ScriptedKeys(
        game,
        [
            (phase(Phase.MATCH_OVER), [down(K.K_r)]),  # in the lockout: ignored
            (accepting, [down(K.K_RETURN)]),
            (phase(Phase.FIGHT), [down(K.K_ESCAPE)]),
        ],
    )
    run(game, lambda: None, keys, FakeClock(), max_frames=5000)
    assert [m.outcome for m in game.matches] == ["win", "draw"]  # match 2 had no round
    assert len(game.matches[1].rounds) == 0 and len(reported) == 1


def test_time_up_level_is_a_drawn_round_and_match():
    game, reported = new_game(rounds=1, opponent="idle", max_cycles=5, countdown_ms=0)
    for _ in range(6):
        game.frame([], FRAME_MS)
    assert game.phase is Phase.MATCH_OVER and game.match.outcome == "draw"
    assert [(r.outcome, r.how, r.steps) for r in game.match.rounds] == [
        ("draw", "time up, level", 5)
    ]
    assert reported[0][0].winner == "draw"


def test_time_up_with_more_health_wins_the_round():
    """The person walks up to an idle opponent and kicks until the clock runs out."""
    game, _ = new_game(rounds=3, opponent="idle", max_cycles=80, countdown_ms=0)
    keys = ScriptedKeys(
        game,
        [(after_steps(0), [down(K.K_RIGHT)]), (after_steps(25), [up(K.K_RIGHT), down(K.K_k)])],
    )
    run(game, lambda: None, keys, FakeClock(), max_frames=200)
    (result,) = game.match.rounds
    assert (result.outcome, result.how, result.steps) == ("win", "time up, more health", 80)
    assert game.phase is Phase.ROUND_OVER and game.record.health[1] < game.record.health[0]


def test_quitting_mid_round_reports_the_game_so_far():
    game, reported = new_game(rounds=1, opponent="idle")
    keys = ScriptedKeys(
        game,
        [(after_steps(3), [down(K.K_k)]), (after_steps(12), [pygame.event.Event(pygame.QUIT)])],
    )
    run(game, lambda: None, keys, FakeClock(), max_frames=1000)
    ((record, _),) = reported
    assert record.steps == 12 and record.winner is None
    assert [a for a, _ in record.actions][3] == Action.KICK
    play_back(Replay.from_episode(record, game.env.config))


def test_losing_focus_pauses_and_clears_keys():
    game, _ = new_game(countdown_ms=0)
    game.frame([down(K.K_RIGHT)], FRAME_MS)
    game.frame([], FRAME_MS)
    steps = game.record.steps
    game.frame([pygame.event.Event(pygame.WINDOWFOCUSLOST)], FRAME_MS)
    assert game.paused and game.record.steps == steps and not game.keys.held


def test_restart_while_paused_reports_the_round_cut_short():
    game, reported = new_game(countdown_ms=0)
    for _ in range(4):
        game.frame([], FRAME_MS)
    game.frame([down(K.K_r)], FRAME_MS)  # not paused: R does nothing mid-fight
    assert len(game.matches) == 1
    game.frame([down(K.K_p), down(K.K_r)], FRAME_MS)
    assert len(game.matches) == 2 and not game.paused and game.record.steps == 0
    assert len(reported) == 1 and reported[0][0].steps == 4  # the first frame ends the countdown


def test_seat_one_and_speed():
    env = vooga_env.parallel_env(config="small", backend="engine")
    game = Game(env, make_policy("idle"), PlaySettings(seat=1, speed=0.5, countdown_ms=0))
    clock = FakeClock()
    keys = ScriptedKeys(
        game, [(after_steps(0), [down(K.K_LEFT)]), (after_steps(6), [down(K.K_ESCAPE)])]
    )
    run(game, lambda: None, keys, clock)
    assert set(clock.rates) == {12.5}
    assert [pair[1] for pair in game.record.actions] == [Action.RIGHT] * 6  # mirrored
    assert env.fighter_status()[1]["x"] < env.config.arena.spawns[1]  # walked left on screen


@pytest.mark.parametrize(
    "field, value, message",
    [
        ("speed", 0.25, "speed must be a number in 0.5..2.0"),
        ("speed", 2.5, "got 2.5"),
        ("speed", "fast", "got 'fast'"),
        ("rounds", 0, "rounds must be a positive int, got 0"),
        ("seat", 2, "seat must be 0 or 1, got 2"),
        ("seed", -1, "seed must be a non-negative int"),
        ("countdown_ms", -5, "countdown_ms must be >= 0"),
    ],
)
def test_bad_settings(field, value, message):
    with pytest.raises(ValueError, match=message):
        PlaySettings(**{field: value})


def test_best_of_needs_a_majority():
    assert [PlaySettings(rounds=n).wins_needed for n in (1, 2, 3, 5)] == [1, 2, 2, 3]


def frame_script(script):
    """A key source keyed by frame number (for the command line, whose game is its own)."""
    frames = iter(range(1_000_000))
    return lambda: script.get(next(frames), [])


def test_cli_plays_and_saves_every_round(headless, tmp_path, capsys):
    countdown = round(3000 / FRAME_MS)
    # an idle opponent and a person who only kicks: 40 steps, then time is up; then Esc
    script = {
        countdown + 2: [down(K.K_k)],
        countdown + 3: [up(K.K_k)],
        countdown + 80: [down(K.K_ESCAPE)],
    }
    argv = ["idle", "--max-cycles", "40", "--replay-dir", str(tmp_path / "play")]
    assert play.main(argv, events=frame_script(script), clock=FakeClock()) == 0
    out = capsys.readouterr().out
    assert "punch: J or Z" in out
    (path,) = (tmp_path / "play").glob("*.json")
    assert f"replay: {path}" in out and "-idle-m1-r1.json" in path.name
    assert "match 1:" in out
    data = json.loads(path.read_text())
    assert data["names"] == ["human", "idle"] and len(data["actions"]) == 40
    assert data["config"]["stocks"] == 3  # play's default
    assert Action.KICK in [pair[0] for pair in data["actions"]]
    play_back(Replay.load(path))


def test_cli_ctrl_c_keeps_the_round_so_far(headless, tmp_path, capsys):
    frames = iter(range(1_000_000))

    def interrupted():
        if next(frames) == round(3000 / FRAME_MS) + 10:
            raise KeyboardInterrupt
        return []

    argv = ["rush", "--replay-dir", str(tmp_path)]
    assert play.main(argv, events=interrupted, clock=FakeClock()) == 0
    (path,) = tmp_path.glob("*-rush-m1-r1.json")
    assert len(Replay.load(path).actions) == 10
    assert f"replay: {path}" in capsys.readouterr().out


def test_cli_no_replay(headless, tmp_path, monkeypatch, capsys):
    monkeypatch.chdir(tmp_path)
    script = {80: [down(K.K_ESCAPE)]}
    argv = ["idle", "--max-cycles", "3", "--no-replay", "--config", "small", "--rounds", "3"]
    assert play.main(argv, events=frame_script(script), clock=FakeClock()) == 0
    assert not list(tmp_path.rglob("*.json"))
    assert "replay:" not in capsys.readouterr().out


@pytest.mark.parametrize(
    "argv, stocks, max_cycles",
    [
        (["rush"], 3, 2700),  # default.toml: 1 stock in 900 steps; the same time per stock
        (["rush", "--stocks", "1"], 1, 900),
        (["rush", "--stocks", "2", "--max-cycles", "50"], 2, 50),
        (["rush", "--config", "small", "--stocks", "5"], 5, 4500),
    ],
)
def test_the_clock_keeps_the_time_per_stock(argv, stocks, max_cycles):
    parser = play.build_parser()
    config = play.play_config(parser, parser.parse_args(argv))
    assert (config.stocks, config.max_cycles) == (stocks, max_cycles)


@pytest.mark.parametrize(
    "argv, message",
    [
        (["ninja"], "unknown policy 'ninja'"),
        (["rush", "--speed", "3"], "speed must be a number in 0.5..2.0"),
        (["rush", "--speed", "slow"], "speed must be a number"),
        (["rush", "--stocks", "0"], "must be >= 1, got 0"),
        (["rush", "--rounds", "0"], "must be >= 1, got 0"),
        (["rush", "--config", "moon"], "moon"),
        (["rush", "--max-cycles", "0"], "max_cycles"),
        (["rush", "--no-replay", "--replay-dir", "x"], "not allowed with argument"),
    ],
)
def test_cli_bad_arguments(headless, argv, message, capsys):
    with pytest.raises(SystemExit) as stopped:
        play.main(argv)
    assert stopped.value.code == 2
    assert message in capsys.readouterr().err


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="X11/Wayland variables: Linux")
def test_no_display_is_an_error_not_a_blind_game(monkeypatch, tmp_path, capsys):
    pygame.display.quit()
    for name in ("SDL_VIDEODRIVER", "DISPLAY", "WAYLAND_DISPLAY"):
        monkeypatch.delenv(name, raising=False)
    monkeypatch.setenv("SDL_AUDIODRIVER", "dummy")
    assert play.main(["rush", "--replay-dir", str(tmp_path)]) == 2
    err = capsys.readouterr().err
    assert "no display" in err and "xvfb-run" in err and "DISPLAY" in err
    assert not pygame.display.get_init() and not list(tmp_path.iterdir())


WINDOW_GAME = """
import sys, pygame
from agents import play

class PostingClock:
    # posts the scripted key events to pygame's real queue; the game reads them from the window
    def __init__(self, script):
        self.script, self.frame = script, 0
    def tick(self, framerate=0):
        self.frame += 1
        for event_type, key in self.script.get(self.frame, []):
            pygame.event.post(pygame.event.Event(event_type, key=key))
        if self.frame == 90:
            pygame.image.save(pygame.display.get_surface(), sys.argv[2])
            print("driver", pygame.display.get_driver())
        return 40

script = {78: [(pygame.KEYDOWN, pygame.K_RIGHT)], 88: [(pygame.KEYUP, pygame.K_RIGHT)],
          120: [(pygame.KEYDOWN, pygame.K_ESCAPE)]}
sys.exit(play.main(["idle", "--replay-dir", sys.argv[1]], clock=PostingClock(script)))
"""


@pytest.fixture
def x_display():
    """A virtual X display (Xvfb) for the test's subprocess, or skip."""
    if shutil.which("Xvfb") is None:
        pytest.skip("Xvfb is not installed (apt-get install xvfb)")
    read, write = os.pipe()
    server = subprocess.Popen(
        ["Xvfb", "-displayfd", str(write), "-screen", "0", "1024x768x24", "-nolisten", "tcp"],
        pass_fds=(write,),
        stderr=subprocess.DEVNULL,
    )
    os.close(write)
    with os.fdopen(read) as pipe:
        number = pipe.readline().strip()
    yield f":{number}"
    server.terminate()
    server.wait(timeout=10)


def test_a_game_in_a_real_window(x_display, tmp_path):
    env = {k: v for k, v in os.environ.items() if k not in ("SDL_VIDEODRIVER", "WAYLAND_DISPLAY")}
    env.update(DISPLAY=x_display, PYTHONPATH=str(ROOT), SDL_AUDIODRIVER="dummy")
    shot = tmp_path / "window.png"
    done = subprocess.run(
        [sys.executable, "-c", textwrap.dedent(WINDOW_GAME), str(tmp_path / "play"), str(shot)],
        env=env,
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert done.returncode == 0, done.stderr
    assert "driver x11" in done.stdout
    (path,) = (tmp_path / "play").glob("*.json")
    actions = [pair[0] for pair in Replay.load(path).actions]
    assert actions.count(Action.RIGHT) == 10 and set(actions) == {Action.IDLE, Action.RIGHT}
    picture = pygame.image.load(str(shot))
    assert picture.get_size() == (800, 480)
    assert len({tuple(picture.get_at((x, 300))) for x in range(0, 800, 4)}) > 2  # the fight


HUD = pygame.Rect(0, 0, 10_000, 52)  # the viewer's health bars, names and timer


def shoot_screens(config, seat, folder):
    """Play a best of 3 against rush (the person idle, so rush wins it) and save each screen to
    `folder`; returns each screen's text and panel boxes."""
    env = vooga_env.parallel_env(config=config, backend="engine", stocks=3, max_cycles=400)
    game = Game(env, make_policy("rush"), PlaySettings(seat=seat, rounds=3))
    game.last_saved = "runs/play/20261201-213600-rush-m1-r1.json"
    surface = pygame.Surface((int(env.config.arena.width), int(env.config.arena.height)))
    screens = Screens(game, surface)
    boxes = {}

    def shoot(name):
        screens.draw()
        pygame.image.save(surface, str(Path(folder) / f"{name}.png"))
        boxes[name] = list(screens.boxes)

    def until(done, events=()):
        game.frame(events, FRAME_MS)
        while not done(game):
            game.frame([], FRAME_MS)

    until(lambda g: g.phase_ms >= 1000)
    shoot("countdown")
    until(phase(Phase.FIGHT))
    shoot("fight-banner")
    until(lambda g: g.phase_ms >= 1000)
    shoot("fight-help")
    game.frame([down(K.K_DOWN)], FRAME_MS)
    game.frame([up(K.K_DOWN)], FRAME_MS)
    shoot("fight-hint")
    game.frame([down(K.K_p)], FRAME_MS)
    shoot("paused")
    until(phase(Phase.ROUND_OVER, Phase.MATCH_OVER), [down(K.K_p)])
    shoot("round-over-lockout")
    until(accepting)
    shoot("round-over")
    while game.phase is not Phase.MATCH_OVER:
        until(phase(Phase.ROUND_OVER, Phase.MATCH_OVER), [down(K.K_RETURN)])
    until(accepting)
    shoot("match-over")
    return boxes


@pytest.mark.parametrize("config, seat", [("default", 0), ("small", 1), ("platforms", 0)])
def test_every_screen_draws_inside_and_without_overlaps(headless, tmp_path, config, seat):
    boxes = shoot_screens(config, seat, tmp_path)
    size = pygame.image.load(str(tmp_path / "countdown.png")).get_rect()
    for name, drawn in boxes.items():
        assert drawn, name
        for index, box in enumerate(drawn):
            assert size.contains(box), (name, box)
            assert not box.colliderect(HUD), (name, box)
            assert box.collidelist(drawn[index + 1 :]) == -1, (name, box, drawn)
    pictures = {name: (tmp_path / f"{name}.png").read_bytes() for name in boxes}
    assert len(set(pictures.values())) == len(pictures)  # every screen looks different
