"""The league ships the candidate whose worst score (games won against a scripted fighter, not
lost against an exploiter) is best, measured on fresh games."""

from __future__ import annotations

import json

import pytest
import torch

pytest.importorskip("stable_baselines3")

from stable_baselines3 import PPO  # noqa: E402

from agents.league import LEAGUE_DIR, load_league_config, train_league  # noqa: E402
from agents.league_select import SELECTION_FILE, league_opponents, scores, ship_best  # noqa: E402
from vooga_env.envs.sb3 import FightVecEnv  # noqa: E402
from vooga_env.game.actions import Action  # noqa: E402
from vooga_env.game.config import ConfigError, load_config  # noqa: E402
from vooga_env.policies.models import load_model  # noqa: E402


def _always(action: Action, path):
    """A saved PPO model whose every action, sampled or argmax, is `action`."""
    model = PPO("MlpPolicy", FightVecEnv(2, load_config("small"), opponent="idle"), device="cpu")
    with torch.no_grad():
        model.policy.action_net.weight.zero_()
        model.policy.action_net.bias.fill_(-30.0)
        model.policy.action_net.bias[int(action)] = 30.0
    model.save(path)
    return path


def test_the_walker_beats_idle_and_the_stander_does_not_in_one_mixed_batch(tmp_path):
    opponents = league_opponents(tmp_path, ["idle", "rush"], [])
    walker = scores(load_model(_always(Action.RIGHT, tmp_path / "w.zip")), opponents, 4, 0)
    stander = scores(load_model(_always(Action.IDLE, tmp_path / "s.zip")), opponents, 4, 0)
    for play in ("sampled", "argmax"):
        assert walker[play]["idle"] == 1.0  # walks idle off the stage, from either seat
        assert stander[play]["idle"] == 0.0  # two fighters standing still: a draw
        assert set(walker[play]) == {"idle", "rush"}


def test_a_draw_fails_against_a_scripted_fighter_and_holds_against_an_exploiter(tmp_path):
    opponents = league_opponents(tmp_path, ["idle"], [])
    stander = load_model(_always(Action.IDLE, tmp_path / "s.zip"))
    retreater = load_model(_always(Action.LEFT, tmp_path / "r.zip"))
    for play in ("sampled", "argmax"):  # two fighters standing still: a draw
        assert scores(stander, opponents, 4, 0)[play]["idle"] == 0.0
        assert scores(stander, opponents, 4, 0, exploiters={"idle"})[play]["idle"] == 1.0
        # walking off its own edge is a loss either way
        assert scores(retreater, opponents, 4, 0, exploiters={"idle"})[play]["idle"] == 0.0


def test_the_best_worst_win_rate_is_shipped_even_when_older(tmp_path):
    walker = _always(Action.RIGHT, tmp_path / "walker.zip")
    stander = _always(Action.IDLE, tmp_path / "stander.zip")
    final = tmp_path / "final.zip"
    final.write_bytes(stander.read_bytes())
    opponents = league_opponents(tmp_path, ["idle"], [])
    ship_best(tmp_path, {"walker.zip": walker, "final.zip": final}, opponents, 4, 0)
    assert final.read_bytes() == walker.read_bytes()
    selection = json.loads((tmp_path / SELECTION_FILE).read_text())
    assert selection["chosen"] == "walker.zip"
    assert selection["candidates"]["final.zip"]["worst"] == 0.0
    assert selection["candidates"]["walker.zip"]["worst"] == 1.0


def test_a_league_with_select_games_ships_its_best_candidate_repeatably(tmp_path):
    path = tmp_path / "select.toml"  # the smoke league, [league] last
    path.write_text((LEAGUE_DIR / "smoke.toml").read_text() + "select_games = 4\n")
    config = load_league_config(path, total_timesteps=2048)
    run = tmp_path / "run"
    final = train_league(config, run, progress=False)
    selection = json.loads((run / SELECTION_FILE).read_text())
    state = json.loads((run / "train_state.json").read_text())
    names = [f"{name}.zip" for name in state["snapshots"]] + ["final.zip"]
    assert list(selection["candidates"]) == names
    for row in selection["candidates"].values():
        for rates in row["scores"].values():
            assert set(rates) == {"rush", "punisher", *state["exploiters"]}
    rows = list(selection["candidates"].values())
    best = max(
        range(len(rows)), key=lambda index: (rows[index]["worst"], rows[index]["mean"], index)
    )
    assert selection["chosen"] == names[best]
    if names[best] != "final.zip":
        chosen = run / "snapshots" / names[best]
        assert final.read_bytes() == chosen.read_bytes()
    opponents = league_opponents(run, ["rush", "punisher"], state["exploiters"])
    assert selection["exploiters"] == sorted(state["exploiters"])
    fight = load_config(config.fight)
    again = scores(load_model(final), opponents, 4, config.seed, fight, state["exploiters"])
    assert again == selection["candidates"][selection["chosen"]]["scores"]  # the same games
    for argmax in (False, True):  # exploiters play as `exploiter_pool_play` has them play
        players = league_opponents(run, [], state["exploiters"], argmax, "league_0/")
        assert list(players) == [f"league_0/{name}" for name in state["exploiters"]]
        assert all(player(0).policy.deterministic == argmax for player in players.values())


@pytest.mark.parametrize("games", [-2, 3])
def test_select_games_must_be_even_and_not_negative(games):
    with pytest.raises(ConfigError, match=f"select_games = {games} is not allowed: an even number"):
        load_league_config("smoke", league={"select_games": games})
