"""The league: PFSP draws, the pool opponent, and smoke runs (snapshots, exploiters, resume)."""

from __future__ import annotations

import json
import math
import signal
import sys
from dataclasses import replace

import numpy as np
import pytest
import torch

pytest.importorskip("stable_baselines3")

from agents.exploit import make_learner  # noqa: E402
from agents.league import (  # noqa: E402
    LeagueCallback,
    build,
    format_pool,
    load_league_config,
    main,
    train_league,
)
from agents.league_exploiter import (  # noqa: E402
    ExploiterJob,
    ExploiterWorker,
    against_target,
    train_exploiter,
)
from agents.league_pool import Pool, PoolOpponent, Slipping  # noqa: E402
from tests.agents.interrupt import group_size, interrupt_when  # noqa: E402
from vooga_env.envs.sb3 import FightVecEnv  # noqa: E402
from vooga_env.game.actions import Action  # noqa: E402
from vooga_env.game.config import CONFIG_DIR, ConfigError, load_config  # noqa: E402
from vooga_env.policies.batched import VectorOpponent, scripted_actions  # noqa: E402
from vooga_env.policies.models import FrozenPolicy, load_model  # noqa: E402


def test_pfsp_draws_the_opponent_the_learner_beats_least_far_more_often():
    pool = Pool(window=10)
    pool.add("beaten", VectorOpponent("idle"), [1.0] * 9 + [0.0])  # p = 0.9
    pool.add("hard", VectorOpponent("rush"), [0.0] * 9 + [1.0])  # p = 0.1
    rng = np.random.default_rng(0)
    draws = [pool.draw(rng) for _ in range(2000)]
    hard = draws.count("hard") / len(draws)
    assert pool.weights() == pytest.approx([0.05 / 0.86, 0.81 / 0.86])  # (1-p)^2, floor 0.05
    assert 0.9 < hard < 0.97
    variance = Pool(window=10, weighting="variance")
    for name, p in (("beaten", 1.0), ("even", 0.5), ("out_of_reach", 0.0)):
        variance.add(name, None, [p])
    assert variance.weights() == pytest.approx([0.05 / 0.35, 0.25 / 0.35, 0.05 / 0.35])
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


def test_a_slipping_member_replaces_the_share_asked_of_its_actions_uniformly_and_by_seed():
    observations = np.random.default_rng(1).uniform(-1, 1, (20_000, 41)).astype(np.float32)
    own = scripted_actions("rush", observations, np.random.default_rng(7).random(20_000))

    def played(noise, seed):
        return Slipping(VectorOpponent("rush", seed=7), noise, seed).act(observations)

    actions = played(0.1, 3)
    slipped = actions != own
    # a slip that draws rush's own action goes unseen: 0.1 x 9/10 of the rows differ
    assert slipped.mean() == pytest.approx(0.09, abs=0.01)
    assert np.bincount(actions[slipped], minlength=len(Action)).min() > 0
    assert np.array_equal(played(0.1, 3), actions)  # its own seeded stream
    assert not np.array_equal(played(0.1, 4), actions)
    assert np.array_equal(played(0.0, 3), own)


def test_snapshot_noise_slips_the_pooled_snapshots_only(tmp_path):
    plain = load_league_config("smoke")
    config = replace(plain, league=replace(plain.league, snapshot_noise=0.5))
    model, league = build(config, tmp_path / "noisy", {}, resume=False, saved=None)
    model.learn(config.total_timesteps, callback=league)
    assert league.snapshots and league.exploiters
    for name, member in league.pool.members.items():
        assert isinstance(member, Slipping) == (name in league.snapshots), name
    model, league = build(plain, tmp_path / "plain", {}, resume=False, saved=None)
    model.learn(plain.total_timesteps, callback=league)
    assert not any(isinstance(member, Slipping) for member in league.pool.members.values())


def test_a_smoke_league_pools_snapshots_and_exploiters_and_resumes(tmp_path, temp_folder):
    config = load_league_config("smoke", total_timesteps=2048)
    train_league(config, tmp_path, progress=False)
    state = json.loads((tmp_path / "train_state.json").read_text())
    assert state["snapshots"] == ["snapshot_1024", "snapshot_2048"]  # window 2
    assert state["exploiters"] == ["exploiter_2048"]
    assert (tmp_path / "exploiters" / "exploiter_2048.zip").is_file()
    result = json.loads((tmp_path / "exploiters" / "exploiter_2048.json").read_text())
    assert state["exploiter_win_rates"] == {"exploiter_2048": result["best_win_rate"]}
    assert sum(len(state["results"][name]) for name in ("rush", "punisher")) > 0
    assert state["ratings"]["learner"] != 1200.0  # Elo moved with the games
    assert set(state["styles"]) == {"styles_0"}  # the smoke's random-style opponent, kept
    final = train_league(load_league_config("smoke"), tmp_path, resume=True, progress=False)
    assert load_model(final).num_timesteps == 4096
    resumed = json.loads((tmp_path / "train_state.json").read_text())
    assert resumed["snapshots"] == ["snapshot_3072", "snapshot_4096"]
    assert list(temp_folder.glob("SB3-*")) == []  # no logger folder of SB3's left behind


def test_the_pool_table_shows_each_exploiters_wins_against_its_own_target():
    state = {
        "num_timesteps": 4096,
        "ratings": {"learner": 1300.0, "rush": 1200.0, "exploiter_2048": 1250.0},
        "results": {"rush": [1.0, 0.0], "exploiter_2048": [1.0]},
        "exploiter_win_rates": {"exploiter_2048": 0.75},
        "probes": {"exploiter_2048": 0.25},
    }
    rows = {line.split()[0]: line.split() for line in format_pool(state).splitlines()[4:]}
    assert rows["exploiter_2048"][-2:] == ["75.00", "25.00"] and rows["rush"][-2:] == ["-", "-"]


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


def test_scripted_fighters_join_in_order_once_the_learner_beats_those_present(tmp_path):
    config = load_league_config(
        "smoke",
        league={"scripted": ["idle", "rush", "turtle"], "join_win_rate": 0.75, "results_window": 4},
    )
    league = LeagueCallback(config, tmp_path, {})
    assert list(league.pool.members) == ["idle"]
    for score in (1.0, 1.0, 0.0):
        league.pool.record("idle", score)
    assert not league._ready_for_next()  # three games of four: the window is not full yet
    league.pool.record("idle", 1.0)
    assert league._ready_for_next()  # 3 of 4 = 0.75
    league._join_scripted({})
    assert list(league.pool.members) == ["idle", "rush"]
    for _ in range(4):
        league.pool.record("rush", 0.5)
    assert not league._ready_for_next()  # mean of 0.75 and 0.5
    resumed = LeagueCallback(config, tmp_path, league.state())
    assert list(resumed.pool.members) == ["idle", "rush"]
    assert list(LeagueCallback(load_league_config("smoke"), tmp_path, {}).pool.members) == [
        "rush",
        "punisher",
        "styles_0",
    ]  # join_win_rate = 0: all from the start


def test_random_styles_play_from_the_start_and_draw_a_new_style_once_beaten(tmp_path):
    config = load_league_config(
        "smoke",
        league={"scripted": ["rush"], "styles": 2, "results_window": 4, "styles_redraw": 0.75},
    )
    league = LeagueCallback(config, tmp_path, {})
    assert list(league.pool.members) == ["rush", "styles_0", "styles_1"]
    first, second = (league.styles[name].moves.copy() for name in ("styles_0", "styles_1"))
    for score in (1.0, 1.0, 0.0):
        league.pool.record("styles_0", score)
    league._redraw_beaten_styles()
    assert np.array_equal(league.styles["styles_0"].moves, first)  # the window is not full yet
    league.pool.record("styles_0", 1.0)  # 3 of 4 = 0.75
    for _ in range(4):
        league.pool.record("styles_1", 0.5)
    league._redraw_beaten_styles()
    assert not np.array_equal(league.styles["styles_0"].moves, first)
    assert len(league.pool.results["styles_0"]) == 0 and league.styles_redrawn == 1
    assert np.array_equal(league.styles["styles_1"].moves, second)  # not beaten: kept
    league.pool.record("styles_0", 0.0)
    resumed = LeagueCallback(config, tmp_path, league.state())
    for name in ("styles_0", "styles_1"):
        assert resumed.styles[name].state() == league.styles[name].state()
        assert list(resumed.pool.results[name]) == list(league.pool.results[name])
    assert resumed.styles_redrawn == 1


def test_the_same_seed_trains_the_same_league_and_init_starts_from_a_model(tmp_path):
    config = load_league_config("smoke", total_timesteps=2048)
    first = load_model(train_league(config, tmp_path / "a", progress=False))
    second = load_model(train_league(config, tmp_path / "b", progress=False))
    for a, b in zip(first.policy.parameters(), second.policy.parameters(), strict=True):
        assert torch.equal(a, b)
    states = [json.loads((tmp_path / run / "train_state.json").read_text()) for run in "ab"]
    assert states[0]["results"] == states[1]["results"]
    assert states[0]["ratings"] == states[1]["ratings"]
    started = load_league_config("smoke", total_timesteps=512, init=str(tmp_path / "a/final.zip"))
    train_league(started, tmp_path / "c", progress=False)
    zero = load_model(tmp_path / "c" / "snapshots" / "snapshot_0.zip")
    for a, b in zip(first.policy.parameters(), zero.policy.parameters(), strict=True):
        assert torch.equal(a, b)  # the first snapshot is the model it started from
    with pytest.raises(ConfigError, match="init = 'nowhere.zip'"):
        train_league(load_league_config("smoke", init="nowhere.zip"), tmp_path / "d")


@pytest.mark.parametrize("start", ["learner", "new"])
def test_exploiters_start_from_the_learner_when_asked(tmp_path, start):
    """With `exploiter_start = "learner"` the exploiter trained 512 steps from the learner saved
    at its mark, so its weights are far closer to the learner's than a new network's are; from a
    new network, they are not (its seed is not the league's, 0, whose first weights the learner
    has barely left)."""
    config = load_league_config("smoke", total_timesteps=2048)
    league = replace(config.league, exploiter_start=start)
    train_league(replace(config, league=league), tmp_path, progress=False)
    folder = tmp_path / "exploiters"
    learner, exploiter = (
        load_model(folder / f"{name}_2048.zip") for name in ("target", "exploiter")
    )
    fresh = make_learner(FightVecEnv(2, load_config("small"), opponent="idle"), seed=1)
    layers = zip(*(m.policy.parameters() for m in (learner, exploiter, fresh)), strict=True)
    moved, apart = zip(*[((e - t).abs().mean(), (f - t).abs().mean()) for t, e, f in layers])
    assert (sum(moved) < sum(apart) / 10) == (start == "learner"), (sum(moved), sum(apart))


def parallel_config(tmp_path, total: int):
    """The smoke league with an exploiter every 1024 steps, trained in a second process."""
    path = tmp_path / f"parallel_{total}.toml"
    text = (CONFIG_DIR / "league" / "smoke.toml").read_text()
    text = text.replace("exploiter_every = 2048", "exploiter_every = 1024")
    text = text.replace("exploiters = 1", "exploiters = 2")
    path.write_text(text + 'exploiter_parallel = true\nexploiter_start = "last"\n')
    return load_league_config(path, total_timesteps=total)


def long_exploiter_config(tmp_path):
    """The smoke league with its first exploiter started at 1024 steps, in its second process,
    and still training when the league checkpoints there (the league waits for it at 2048)."""
    text = (CONFIG_DIR / "league" / "smoke.toml").read_text()
    text = text.replace("exploiter_every = 2048", "exploiter_every = 1024")
    text = text.replace("exploiter_steps = 512", "exploiter_steps = 1_000_000")  # still training
    text = text.replace("checkpoint_every = 2048", "checkpoint_every = 1024")  # after its start
    path = tmp_path / "long.toml"
    path.write_text(text + "exploiter_parallel = true\n")
    return path


@pytest.mark.parametrize("signum", [signal.SIGINT, signal.SIGTERM], ids=["ctrl_c", "sigterm"])
def test_a_stopped_league_stops_its_exploiter_process_too(tmp_path, signum):
    """Ctrl-C, or SIGTERM (`kill`, a job scheduler), while an exploiter trains in its second
    process: the league checkpoints, ends that process and exits 130 (SIGTERM used to kill the
    league on the spot and leave its exploiter training on)."""
    config, out = long_exploiter_config(tmp_path), tmp_path / "run"
    command = [sys.executable, "-m", "agents.league", "--config", str(config), "--out", str(out)]
    command += ["--steps", str(10**7), "--no-progress"]
    ready = (out / "checkpoints" / "ppo_1024_steps.zip").is_file  # the league waits at 2048
    interrupt_when(command, ready, wait=120, stop=60, signum=signum)
    state = json.loads((out / "train_state.json").read_text())
    assert state["num_timesteps"] >= 1024 and state["pending_exploiter"]["steps"] == 1024
    assert load_model(out / "latest.zip").num_timesteps == state["num_timesteps"]


def test_parallel_exploiters_continue_from_the_last_and_a_resume_trains_them_again(tmp_path):
    train_league(parallel_config(tmp_path, 2048), tmp_path, progress=False)
    stopped = json.loads((tmp_path / "train_state.json").read_text())
    assert stopped["exploiters"] == ["exploiter_1024"]  # a mark late: 2048's is still training
    pending = stopped["pending_exploiter"]
    assert pending["steps"] == 2048 and pending["init"] == "exploiter_1024.zip"
    config = parallel_config(tmp_path, 3072)
    train_league(config, tmp_path, resume=True, progress=False)
    state = json.loads((tmp_path / "train_state.json").read_text())
    assert state["exploiters"] == ["exploiter_1024", "exploiter_2048"]
    for name in state["exploiters"]:  # each played the learner it trained on, once trained
        result = json.loads((tmp_path / "exploiters" / f"{name}.json").read_text())
        assert result["target"] == name.replace("exploiter", "target") + ".zip"
        assert state["exploiter_win_rates"][name] == result["best_win_rate"]
    league = LeagueCallback(config, tmp_path, state)
    job = replace(league._job(**pending), out=str(tmp_path / "again.zip"))
    trained = [load_model(path) for path in (job.init, train_exploiter(job))]
    resumed = load_model(tmp_path / "exploiters" / "exploiter_2048.zip")
    for a, b, c in zip(*(m.policy.parameters() for m in (*trained, resumed)), strict=True):
        assert not torch.equal(a, b)  # it trained on from exploiter_1024
        assert torch.equal(b, c)  # the second process trained what the job says, after a resume
    for play, argmax in (("sampled", False), ("argmax", True)):
        league = replace(config.league, exploiter_pool_play=play)
        members = LeagueCallback(replace(config, league=league), tmp_path, state).pool.members
        assert [members[name].policy.deterministic for name in state["exploiters"]] == [argmax] * 2
        assert not members["snapshot_3072"].policy.deterministic  # snapshots always sample
    starts = {
        "last": "exploiter_2048.zip",
        "lines": "exploiter_1024.zip",  # the line exploiter_2048 is not on
        "new": "",
        "learner": "target_4096.zip",
    }
    for start, init in starts.items():  # what the next exploiter (at 4096) would start from
        league = replace(config.league, exploiter_start=start)
        assert LeagueCallback(replace(config, league=league), tmp_path, state)._start(4096) == init


def test_a_failed_exploiter_process_is_an_error_that_names_it(tmp_path):
    worker = ExploiterWorker()
    missing = str(tmp_path / "no_target.zip")
    worker.submit(ExploiterJob(missing, True, 0, 0, 64, "small", 2, str(tmp_path / "e.zip")))
    with pytest.raises(RuntimeError, match="the exploiter process training .*e.zip exited"):
        worker.collect()


def always(action: Action, path) -> str:
    """A saved model (by seat) that takes `action` whatever it sees."""
    model = make_learner(FightVecEnv(2, "small"), 0)
    with torch.no_grad():
        model.policy.action_net.weight.zero_()
        model.policy.action_net.bias.fill_(-20.0)
        model.policy.action_net.bias[action] = 20.0
    model.save(path)
    return str(path)


@pytest.mark.parametrize(("action", "won"), [(Action.RIGHT, 1.0), (Action.IDLE, 0.0)])
def test_a_trained_exploiter_counts_its_wins_against_its_own_target(tmp_path, action, won):
    """Against a learner that stands still, an exploiter that walks in shoves it off the stage
    every game, sampling or not; one that stands still too wins none."""
    target = always(Action.IDLE, tmp_path / "idle.zip")
    job = ExploiterJob(target, True, 0, 0, 64, "small", 2, str(tmp_path / "e.zip"))
    exploiter = load_model(always(action, tmp_path / "exploiter.zip"))
    rates = {"sampled": won, "argmax": won}
    assert against_target(exploiter, job) == {"win_rate": rates, "best_win_rate": won}


@pytest.mark.parametrize(
    ("play", "deterministic"),
    [
        ("sampled", [False, False, False]),
        ("argmax", [True] * 3),
        ("alternate", [True, False, True]),
    ],
)
def test_exploiters_train_against_the_learner_playing_as_asked(tmp_path, play, deterministic):
    config = load_league_config("smoke", league={"exploiter_play": play})
    league = LeagueCallback(config, tmp_path, {})
    targets = []
    for made in range(3):
        league.exploiters_made = made
        targets.append(league.exploiter_argmax())
    assert targets == deterministic
    assert LeagueCallback(config, tmp_path, {"exploiters_made": 5}).exploiters_made == 5


def test_the_learner_takes_its_argmax_against_exploiters_only_when_asked(tmp_path):
    def trained(play, folder):
        config = load_league_config("smoke", total_timesteps=2048)
        config = replace(config, league=replace(config.league, against_exploiters=play))
        model, league = build(config, folder, {}, resume=False, saved=None)
        model.learn(config.total_timesteps, callback=league)
        return model, league

    model, league = trained("argmax", tmp_path / "argmax")
    assert league.exploiters  # the smoke pools one at 2048 steps, the last here
    league.opponent.assigned[:2] = [league.exploiters[0], league.snapshots[0]]
    league.locals["dones"] = np.zeros(len(league.opponent.assigned), dtype=bool)
    league._on_step()  # no fight ended: the assignments stay
    rows = model.policy.argmax_rows.tolist()
    assert rows == [name in league.exploiters for name in league.opponent.assigned]
    assert rows[:2] == [True, False]
    model, league = trained("half", tmp_path / "half")
    league.opponent.assigned[:4] = [league.exploiters[0]] * 3 + [league.snapshots[0]]
    league._argmax_rows()
    assert model.policy.argmax_rows.tolist()[:4] == [True, False, True, False]
    model, _ = trained("sampled", tmp_path / "sampled")
    assert model.policy.argmax_rows is None


def test_the_learner_takes_its_argmax_against_the_other_members_only_when_asked(tmp_path):
    """`against_others` names the rows a snapshot or a scripted fighter plays, as
    `against_exploiters` the exploiters' ones ("half": the even-numbered, "quarter": every
    fourth)."""
    config = load_league_config("smoke", total_timesteps=2048)  # its exploiter joins at 2048
    scripted = config.league.scripted[0]
    plays = {
        "argmax": [True, True, True, False, True],
        "half": [True, False, True, False, True],
        "quarter": [True, False, False, False, True],
    }
    for play, expected in plays.items():
        played = replace(config, league=replace(config.league, against_others=play))
        model, league = build(played, tmp_path / play, {}, resume=False, saved=None)
        model.learn(config.total_timesteps, callback=league)
        assigned = [scripted, scripted, league.snapshots[0], league.exploiters[0], scripted]
        league.opponent.assigned[:5] = assigned
        league._argmax_rows()
        assert model.policy.argmax_rows.tolist()[:5] == expected


def test_the_current_self_plays_the_learners_weights_of_each_rollout(tmp_path):
    """With `self_play` the pool holds "self", sampling with the weights the learner had when the
    rollout began: copied in at each rollout, so an update shows at the next one and not before."""
    config = load_league_config("smoke")
    config = replace(config, league=replace(config.league, self_play=True))
    model, league = build(config, tmp_path, {}, resume=False, saved=None)
    model.learn(config.total_timesteps, callback=league)
    assert len(league.pool.results["self"]) > 0  # the learner fought itself
    observations = np.random.default_rng(2).uniform(-1, 1, (64, 41)).astype(np.float32)
    current = league.current_self.player
    assert not current.deterministic and current.frame == "opponent"

    def logits():
        return FrozenPolicy(model, deterministic=False).logits(observations)

    assert not np.allclose(current.logits(observations), logits())  # the last update since
    league.on_rollout_start()
    assert np.array_equal(league.current_self.player.logits(observations), logits())
    resumed = LeagueCallback(config, tmp_path, league.state())
    assert list(resumed.pool.results["self"]) == list(league.pool.results["self"])


@pytest.mark.parametrize(
    ("learner", "exploiter", "probe"),
    [(Action.IDLE, Action.RIGHT, 0.0), (Action.RIGHT, Action.IDLE, 1.0)],
)
def test_probes_score_the_learners_argmax_against_each_exploiter(
    tmp_path, learner, exploiter, probe
):
    """With `probe_games`, a snapshot has the learner's argmax play each pooled exploiter, and
    PFSP weighs the exploiter by the lower of that score and its training games'."""
    config = load_league_config("smoke")
    config = replace(config, league=replace(config.league, probe_games=4))
    league = LeagueCallback(config, tmp_path, {})
    (tmp_path / "exploiters").mkdir()
    always(exploiter, tmp_path / "exploiters" / "exploiter_0.zip")
    league._join("exploiters", "exploiter_0", [1.0] * 8)
    model = load_model(always(learner, tmp_path / "learner.zip"))
    league.snapshot(model, 1024)
    assert league.pool.probes == {"exploiter_0": probe}
    weights = dict(zip(league.pool.members, league.pool.weights()))
    # its training games were all won: unprobed, it would be the least drawn
    assert weights["exploiter_0"] == (max if probe == 0.0 else min)(weights.values())
    assert LeagueCallback(config, tmp_path, league.state()).pool.probes == league.pool.probes
    league._leave("exploiter_0")
    assert league.pool.probes == {}


def test_probe_scripted_scores_the_argmax_against_the_joined_scripted_fighters(tmp_path):
    """With `probe_scripted`, a snapshot probes the scripted fighters that have joined (not
    those still waiting): an argmax that only stands still draws idle, and PFSP draws idle more
    than its won training games alone would have it."""
    config = load_league_config("smoke")
    model = load_model(always(Action.IDLE, tmp_path / "learner.zip"))
    idle_weight = {}
    for probe_scripted in (False, True):
        league_config = replace(
            config.league,
            scripted=["idle", "rush"],
            join_win_rate=0.7,
            probe_games=4,
            probe_scripted=probe_scripted,
        )
        folder = tmp_path / str(probe_scripted)
        league = LeagueCallback(
            replace(config, league=league_config), folder, {"results": {"idle": [1.0] * 8}}
        )
        league.snapshot(model, 1024)
        assert league.pool.probes == ({"idle": 0.5} if probe_scripted else {})
        idle_weight[probe_scripted] = dict(zip(league.pool.members, league.pool.weights()))["idle"]
    assert idle_weight[True] > idle_weight[False]


@pytest.mark.parametrize(("minutes", "steps"), [(None, "fewer"), (0.0, "all")])
def test_minutes_0_lifts_the_configs_clock(tmp_path, minutes, steps):
    config = load_league_config("smoke", minutes=1e-9, total_timesteps=1024)
    train_league(config, tmp_path, progress=False, minutes=minutes)
    trained = json.loads((tmp_path / "train_state.json").read_text())["num_timesteps"]
    assert (trained == 1024) == (steps == "all") and trained > 0


def test_bad_league_settings_are_refused_by_name(tmp_path, capsys):
    with pytest.raises(ConfigError, match="pfsp = 'greedy' is not allowed"):
        load_league_config("smoke", league={"pfsp": "greedy"})
    with pytest.raises(ConfigError, match="scripted = 'ninja' is not allowed"):
        load_league_config("smoke", league={"scripted": ["ninja"]})
    with pytest.raises(ConfigError, match="exploiter_play = 'best' is not allowed: one of"):
        load_league_config("smoke", league={"exploiter_play": "best"})
    with pytest.raises(ConfigError, match="exploiter_parallel = true is not allowed with"):
        load_league_config("smoke", league={"exploiter_parallel": True})
    with pytest.raises(ConfigError, match="exploiter_start = 'old' is not allowed: one of"):
        load_league_config("smoke", league={"exploiter_start": "old"})
    with pytest.raises(ConfigError, match="'lines' is not allowed with exploiters = 1: each"):
        load_league_config("smoke", league={"exploiter_start": "lines", "exploiters": 1})
    with pytest.raises(ConfigError, match="exploiter_pool_play = 'best' is not allowed: one of"):
        load_league_config("smoke", league={"exploiter_pool_play": "best"})
    with pytest.raises(ConfigError, match="styles = -1 is not allowed: >= 0"):
        load_league_config("smoke", league={"styles": -1})
    with pytest.raises(ConfigError, match="styles_redraw = 0.0 is not allowed: in \\(0, 1\\]"):
        load_league_config("smoke", league={"styles_redraw": 0.0})
    for key in ("against_exploiters", "against_others"):
        with pytest.raises(ConfigError, match=f"{key} = 'best' is not allowed: one of"):
            load_league_config("smoke", league={key: "best"})
        for play in ("argmax", "half", "quarter"):
            with pytest.raises(ConfigError, match=f"{key} = '{play}' is not allowed with"):
                load_league_config("smoke", ppo={"frame": "seat"}, league={key: play})
    with pytest.raises(ConfigError, match="probe_games = 3 is not allowed: an even number"):
        load_league_config("smoke", league={"probe_games": 3})
    with pytest.raises(ConfigError, match="probe_scripted = true is not allowed with probe_game"):
        load_league_config("smoke", league={"probe_scripted": True})
    for noise in (-0.1, 1.0):
        with pytest.raises(ConfigError, match=f"snapshot_noise = {noise} is not allowed: in"):
            load_league_config("smoke", league={"snapshot_noise": noise})
    with pytest.raises(ConfigError, match="lead_reward = -0.005 is not allowed: in \\[0, 1\\)"):
        load_league_config("smoke", league={"lead_reward": -0.005})
    with pytest.raises(ConfigError, match="minutes = -1.0 is not allowed: must be >= 0"):
        load_league_config("smoke", minutes=-1.0)
    with pytest.raises(ConfigError, match="minutes must be a finite number"):
        load_league_config("smoke", minutes=math.nan)
    with pytest.raises(SystemExit) as stop:
        main(["--config", "smoke", "--out", str(tmp_path), "--resume"])
    assert stop.value.code == 2 and "no checkpoint" in capsys.readouterr().err


def test_the_league_benchmark_measures_every_target_and_by_steps_repeats(tmp_path):
    """Once with its exploiters one at a time, once two at a time: the same result, with a row
    for every target of issue 12."""
    from bench import league_recipe
    from vooga_env.policies import SCRIPTED

    flags = ["--quick", "--steps", "1024", "--exploit-steps", "512"]
    results = []
    for run, jobs in (("first", "1"), ("second", "2")):
        out = ["--exploit-jobs", jobs, "--out", str(tmp_path / run)]
        assert league_recipe.main([*flags, *out]) == 0
        result = json.loads((tmp_path / run / "result.json").read_text())
        del result["train_minutes"], result["model"]
        for runs in result["exploit"].values():
            for row in runs[0]["curve"]:
                del row["minutes"]  # the clock's, not the steps'
        results.append(result)
    assert results[0] == results[1]
    result = results[0]
    assert 1024 <= result["steps"] < 1024 + 8 * 64  # the smoke's rollout: 8 fights x 64
    for play in ("sampled", "argmax"):
        assert list(result["win_rates"][play]) == list(SCRIPTED)
        assert all(row["games"] == 4 for row in result["win_rates"][play].values())
        (run,) = result["exploit"][play]
        assert run["seed"] == 3 and run["curve"][0]["steps"] == 0
        assert 512 <= run["curve"][-1]["steps"] < 512 + 64 * 128  # the exploiter's rollout
    assert sorted(row["name"] for row in result["elo"]) == sorted(["model", *SCRIPTED])
    attacks = result["style"]["attacks"]
    assert set(attacks) == {"punch", "kick"} and result["style"]["games"] == 2 * len(SCRIPTED)
    assert all(attack["landed"] <= attack["attempted"] for attack in attacks.values())


@pytest.mark.parametrize(
    ("flag", "message"),
    [
        (["--steps", "1000", "--minutes", "3"], "--steps: not with --minutes"),
        (["--steps", "1000", "--model", "final.zip"], "--steps: not with --model"),
        (["--exploit-steps", "9", "--exploit-minutes", "0"], "--exploit-steps: not with"),
        (["--exploit-games", "3"], "must be an even number >= 2, got 3"),
        (["--games", "0"], "must be >= 1, got 0"),
        (["--exploit-minutes", "-1"], "--exploit-minutes: must be >= 0"),
        (["--exploit-seeds", "-2"], "must be >= 0, got -2"),
        (["--exploit-jobs", "0"], "must be >= 1, got 0"),
    ],
)
def test_the_league_benchmark_refuses_bad_flags_by_name(flag, message, capsys):
    from bench import league_recipe

    with pytest.raises(SystemExit) as stop:
        league_recipe.main(flag)
    assert stop.value.code == 2 and message in capsys.readouterr().err


@pytest.mark.parametrize("phase", ["training", "measuring"])
def test_a_stopped_league_benchmark_leaves_nothing_running(tmp_path, tiny_model, phase):
    """SIGTERM (`kill`, a job scheduler) while the league's exploiter trains in its second
    process, or while the measuring exploiters train in theirs: exit 130, nothing left running,
    and what to do next (SIGTERM killed the benchmark on the spot and left them training on)."""
    out = tmp_path / "run"
    command = [sys.executable, "-m", "bench.league_recipe", "--out", str(out)]
    if phase == "training":
        command += ["--config", str(long_exploiter_config(tmp_path)), "--steps", str(10**7)]
        ready, says = (out / "checkpoints" / "ppo_1024_steps.zip").is_file, "--resume"
    else:
        command += ["--model", str(tiny_model), "--games", "2", "--elo-games", "1"]
        command += ["--style-games", "1", "--exploit-steps", str(10**9), "--exploit-games", "2"]
        ready, says = lambda: group_size(str(out)) >= 3, "again with --model"  # its Pool started
    interrupt_when(command, ready, wait=180, stop=60, signum=signal.SIGTERM, says=says)
    assert not (out / "result.json").exists()
