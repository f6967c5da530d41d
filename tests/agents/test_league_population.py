"""Leagues side by side (`leagues` > 1): one process and seed each, the best final model shipped;
Ctrl-C stops them all, and `--resume` continues every one."""

from __future__ import annotations

import json
import signal
import sys
from contextlib import contextmanager
from pathlib import Path

import pytest

pytest.importorskip("stable_baselines3")

from agents.common import STOP_REQUESTED, stop_on_signals  # noqa: E402
from agents.league import load_league_config, train_league  # noqa: E402
from agents.league_exploiter import ExploiterJob, train_exploiter  # noqa: E402
from agents.league_population import LeagueFailed, run_leagues  # noqa: E402
from tests.agents.interrupt import interrupt_when  # noqa: E402
from vooga_env.game.config import CONFIG_DIR, ConfigError  # noqa: E402
from vooga_env.policies.models import load_model  # noqa: E402

ROOT = Path(__file__).resolve().parents[2]


def two_leagues(tmp_path: Path) -> Path:
    """The smoke league, twice, with 4 games a pairing to choose the one shipped, each league's
    final model first screened by a 512-step exploiter."""
    text = (CONFIG_DIR / "league" / "smoke.toml").read_text()
    path = tmp_path / "two.toml"
    league = "select_games = 4\nscreen_steps = 512\n"  # [league] is the smoke's last table
    path.write_text(text.replace("fights = 8", "fights = 8\nleagues = 2") + league)
    return path


def test_ctrl_c_stops_every_league_and_the_resumed_leagues_ship_the_best(tmp_path):
    config, out = two_leagues(tmp_path), tmp_path / "run"
    command = [sys.executable, "-m", "agents.league", "--config", str(config), "--out", str(out)]
    leagues = [out / "league_0", out / "league_1"]

    def ready() -> bool:
        return all((league / "checkpoints" / "ppo_2048_steps.zip").is_file() for league in leagues)

    interrupt_when([*command, "--steps", str(10**7), "--no-progress"], ready, wait=180, stop=120)
    states = [json.loads((league / "train_state.json").read_text()) for league in leagues]
    assert all(state["num_timesteps"] >= 2048 for state in states)
    assert not (out / "final.zip").exists()
    seeds = [json.loads((league / "league_config.json").read_text())["seed"] for league in leagues]
    assert seeds == [0, 1]  # the config's seed, then the next

    total = max(state["num_timesteps"] for state in states) + 1024
    final = train_league(load_league_config(config, total_timesteps=total), out, resume=True)
    for league in leagues:  # trained to the end (whole rollouts); final.zip may be a snapshot
        assert load_model(league / "latest.zip").num_timesteps >= total
    selection = json.loads((out / "selection.json").read_text())
    assert list(selection["candidates"]) == ["league_0", "league_1"]
    assert final.read_bytes() == (out / selection["chosen"] / "final.zip").read_bytes()
    rows = selection["candidates"].values()
    assert selection["candidates"][selection["chosen"]]["worst"] == max(r["worst"] for r in rows)
    opponents = set(selection["candidates"]["league_0"]["scores"]["argmax"])
    exploiters = {
        f"{league.name}/{name}"
        for league in leagues
        for name in json.loads((league / "train_state.json").read_text())["exploiters"]
    }
    assert len(exploiters) == 2
    screens = {f"{league.name}/screen" for league in leagues}
    assert opponents == {"rush", "punisher", *exploiters, *screens}
    assert set(selection["exploiters"]) == {*exploiters, *screens}  # scored by games not lost
    for league in leagues:  # each screen trained against its league's final model
        assert load_model(league / "exploiters" / "screen.zip").num_timesteps >= 512


@contextmanager
def stop_requested():
    """A stop asked for whose own KeyboardInterrupt was lost (numpy drops one raised in some
    attribute lookups): only the flag is set."""
    STOP_REQUESTED.set()
    try:
        yield
    finally:
        STOP_REQUESTED.clear()


def test_a_lost_interrupt_still_stops_the_league_at_its_next_step(tmp_path):
    config = load_league_config("smoke")
    with stop_requested(), pytest.raises(KeyboardInterrupt):
        train_league(config, tmp_path, progress=False)
    state = json.loads((tmp_path / "train_state.json").read_text())
    assert state["num_timesteps"] < config.total_timesteps  # stopped, checkpointed on the way out
    assert (tmp_path / "latest.zip").is_file() and not (tmp_path / "final.zip").exists()


def test_a_lost_interrupt_still_stops_an_exploiter(tmp_path):
    target = train_league(load_league_config("smoke", total_timesteps=64), tmp_path, progress=False)
    job = ExploiterJob(str(target), True, 0, 0, 20_000, "small", 2, str(tmp_path / "e.zip"))
    with stop_requested(), pytest.raises(KeyboardInterrupt):
        train_exploiter(job)
    assert not (tmp_path / "e.zip").exists()


@contextmanager
def stopping_on_signals(ctrl_c: object):
    """`stop_on_signals` called where Ctrl-C's handler was `ctrl_c`; this process's handlers and
    the stop flag are put back afterwards."""
    previous = {s: signal.getsignal(s) for s in (signal.SIGTERM, signal.SIGINT)}
    signal.signal(signal.SIGINT, ctrl_c)
    try:
        stop_on_signals()
        yield
    finally:
        for s, handler in previous.items():
            signal.signal(s, handler)
        STOP_REQUESTED.clear()


@pytest.mark.parametrize("signum", [signal.SIGTERM, signal.SIGINT], ids=["sigterm", "ctrl_c"])
def test_sigterm_and_ctrl_c_raise_and_ask_training_to_stop(signum):
    """Both raise KeyboardInterrupt and set the flag `StopWhenRequested` reads at the next step
    (Python's own Ctrl-C raised once only, where numpy may drop it)."""
    with stopping_on_signals(signal.default_int_handler):  # Ctrl-C as in a terminal
        with pytest.raises(KeyboardInterrupt):
            signal.raise_signal(signum)
        assert STOP_REQUESTED.is_set()


def test_an_ignored_ctrl_c_stays_ignored():
    """A league's process ignores Ctrl-C (its parent stops it with SIGTERM, once)."""
    with stopping_on_signals(signal.SIG_IGN):
        assert signal.getsignal(signal.SIGINT) is signal.SIG_IGN


def test_a_failed_league_process_is_an_error_that_names_its_folder(tmp_path):
    config = load_league_config("smoke")
    missing = tmp_path / "missing"
    with pytest.raises(LeagueFailed, match=f"league process of {missing} \\(exit code 1\\)"):
        run_leagues(train_league, [(config, missing, True)], 0, progress=False)


def test_leagues_need_games_to_choose_between_them():
    with pytest.raises(ConfigError, match="leagues = 2 is not allowed with .*select_games = 0"):
        load_league_config("smoke", leagues=2)
    with pytest.raises(ConfigError, match="leagues = 0 is not allowed: must be > 0"):
        load_league_config("smoke", leagues=0)


def test_screens_need_leagues_to_choose_between(tmp_path):
    path = tmp_path / "one.toml"
    path.write_text((CONFIG_DIR / "league" / "smoke.toml").read_text() + "screen_steps = 512\n")
    with pytest.raises(ConfigError, match="screen_steps = 512 is not allowed with leagues = 1"):
        load_league_config(path)
    path.write_text((CONFIG_DIR / "league" / "smoke.toml").read_text() + "screen_steps = -1\n")
    with pytest.raises(ConfigError, match="screen_steps = -1 is not allowed: >= 0"):
        load_league_config(path)
