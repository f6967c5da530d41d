"""Bad input to the training and match tools: a usage error (exit 2) naming the key, the value
and what is allowed, before any work starts (no run folder made, no game played)."""

from __future__ import annotations

import importlib
import zipfile

import gymnasium as gym
import numpy as np
import pytest
import torch

from agents import evaluate, match, tournament, train
from agents.train_config import load_train_config
from vooga_env.game.actions import Action
from vooga_env.game.observations import OBSERVATION_SIZE

SMOKE = 'fight = "small"\ntotal_timesteps = 512\nn_envs = 2\ncheckpoint_every = 256\n'
PPO_SMOKE = "[ppo]\nn_steps = 128\nbatch_size = 128\nn_epochs = 1\n"


def usage_error(main, argv, capsys) -> str:
    """Run a CLI that must refuse its input; return what it said on stderr."""
    with pytest.raises(SystemExit) as stop:
        main(argv)
    assert stop.value.code == 2
    return capsys.readouterr().err


# Each: the TOML text of a training config, and what the message must say.
TRAIN_CONFIGS = [
    (SMOKE + "[ppo]\nn_steps = 0\n", "ppo.n_steps = 0 is not allowed: must be >= 1"),
    (SMOKE + "[ppo]\nbatch_size = 0\n", "ppo.batch_size = 0 is not allowed: must be >= 2"),
    (SMOKE + "[ppo]\nbatch_size = 1\n", "ppo.batch_size = 1 is not allowed: must be >= 2"),
    (SMOKE + "[ppo]\nn_epochs = 0\n", "ppo.n_epochs = 0 is not allowed: must be >= 1"),
    (SMOKE + "[ppo]\nlearning_rate = -1\n", "ppo.learning_rate = -1.0 is not allowed: must be > 0"),
    (SMOKE + "[ppo]\nlearning_rate = 0\n", "ppo.learning_rate = 0.0 is not allowed: must be > 0"),
    (SMOKE + "[ppo]\nlearning_rate = nan\n", "ppo.learning_rate must be a finite number"),
    (SMOKE + '[ppo]\nlearning_rate = "fast"\n', "ppo.learning_rate must be a finite number"),
    (SMOKE + "[ppo]\ngamma = 1.5\n", "ppo.gamma = 1.5 is not allowed: must be in [0, 1]"),
    (SMOKE + "[ppo]\ngamma = -0.1\n", "ppo.gamma = -0.1 is not allowed: must be in [0, 1]"),
    (SMOKE + "[ppo]\ngae_lambda = 2\n", "ppo.gae_lambda = 2.0 is not allowed: must be in [0, 1]"),
    (SMOKE + "[ppo]\nent_coef = -0.01\n", "ppo.ent_coef = -0.01 is not allowed: must be >= 0"),
    (
        SMOKE + "[ppo]\nent_coef_final = -0.1\n",
        "ppo.ent_coef_final = -0.1 is not allowed: must be >= 0",
    ),
    (
        SMOKE + "[ppo]\nent_decay_steps = -5\n",
        "ppo.ent_decay_steps = -5 is not allowed: must be >= 0",
    ),
    (
        SMOKE + "[ppo]\nlearning_rate_final = -1e-5\n",
        "ppo.learning_rate_final = -1e-05 is not allowed: must be >= 0",
    ),
    (
        SMOKE + "[ppo]\nlr_decay_steps = -5\n",
        "ppo.lr_decay_steps = -5 is not allowed: must be >= 0",
    ),
    (SMOKE + "[ppo]\nclip_range = 0\n", "ppo.clip_range = 0.0 is not allowed: must be > 0"),
    (SMOKE + "[ppo]\nnet_arch = [0]\n", "ppo.net_arch = [0] is not allowed: every layer needs"),
    (SMOKE + "[ppo]\nnet_arch = [64, -1]\n", "ppo.net_arch = [64, -1] is not allowed"),
    (SMOKE + '[ppo]\nnet_arch = "64"\n', "ppo.net_arch must be a list"),
    (SMOKE + "[ppo]\nnet_arch = [64.5]\n", "ppo.net_arch[0] must be an integer"),
    (SMOKE + "[ppo]\nnormalize_reward = 1\n", "ppo.normalize_reward must be true or false"),
    (SMOKE + "[ppo]\nlearning_rat = 0.1\n", "unknown key 'ppo.learning_rat'"),
    (SMOKE + "[selfplay]\nwindow = 0\n", "selfplay.window = 0 is not allowed: must be >= 1"),
    (SMOKE + "[selfplay]\nsave_steps = 0\n", "selfplay.save_steps = 0 is not allowed"),
    (SMOKE + "[selfplay]\nswap_steps = -4\n", "selfplay.swap_steps = -4 is not allowed"),
    (
        SMOKE + "[selfplay]\nplay_against_latest_ratio = 2\n",
        "selfplay.play_against_latest_ratio = 2.0 is not allowed: must be in [0, 1]",
    ),
    (SMOKE + "[selfplay]\nscripted_ratio = -0.5\n", "selfplay.scripted_ratio = -0.5 is not"),
    (SMOKE + '[selfplay]\nscripted = ["rusj"]\n', "selfplay.scripted = ['rusj'] is not allowed"),
    (SMOKE + "[selfplay]\nscripted = []\n", "selfplay.scripted = [] is not allowed: name a"),
    (SMOKE + "[selfplay]\nsave_step = 5\n", "unknown key 'selfplay.save_step'"),
    (SMOKE + "[curriculum]\nwindow = 0\n", "curriculum.window = 0 is not allowed: must be >= 1"),
    (SMOKE + "[curriculum]\npromote_win_rate = 0\n", "curriculum.promote_win_rate = 0.0 is not"),
    (SMOKE + "[curriculum]\nreview_ratio = 1\n", "curriculum.review_ratio = 1.0 is not allowed"),
    (SMOKE + '[curriculum]\nladder = ["rush+ninja"]\n', "'ninja' is not one of"),
    (SMOKE + "[curriculum]\nladder = []\n", "ladder = [] is not allowed"),
    (SMOKE + "seed = -1\n", "seed = -1 is not allowed: must be in 0 .."),
    (SMOKE + "seed = 4294967295\n", "seed = 4294967295 is not allowed: must be in 0 .. 42949672"),
    (SMOKE + "seed = 4294967296\n", "seed must be an integer in +-4294967295, got 4294967296"),
    (SMOKE + "minutes = -1\n", "minutes = -1.0 is not allowed: must be >= 0"),
    (SMOKE + "minutes = nan\n", "minutes must be a finite number"),
    (SMOKE + "eval_games = 0\n", "eval_games = 0 is not allowed: must be >= 1"),
    (SMOKE + 'mode = "coop"\n', "mode = 'coop' is not allowed: one of scripted, selfplay"),
    ('fight = "moon"\n', "fight = 'moon' is not allowed: unknown config 'moon'"),
    (SMOKE + "total_steps = 5\n", "unknown key 'total_steps'"),
    (SMOKE + "init = 5\n", "init must be a string"),
    ('total_timesteps = 0\nfight = "small"\n', "total_timesteps = 0 is not allowed: must be >= 1"),
    ('n_envs = 0\nfight = "small"\n', "n_envs = 0 is not allowed: must be >= 1"),
    ('checkpoint_every = 0\nfight = "small"\n', "checkpoint_every = 0 is not allowed"),
    ('n_envs = 1\nfight = "small"\n[ppo]\nn_steps = 1\n', "n_envs * ppo.n_steps (1) must be"),
    ("[ppo\nn_steps = 5\n", "not valid TOML"),
]


@pytest.mark.parametrize("text, message", TRAIN_CONFIGS, ids=[m for _, m in TRAIN_CONFIGS])
def test_a_bad_training_config_is_a_usage_error(text, message, tmp_path, capsys):
    path = tmp_path / "bad.toml"
    path.write_text(text)
    out = tmp_path / "run"
    err = usage_error(train.main, ["--config", str(path), "--out", str(out)], capsys)
    assert message in err and "Traceback" not in err
    assert not out.exists()  # refused before any work


@pytest.fixture(scope="module")
def bad_models(tmp_path_factory):
    """Files that are not models this fight can use, by the name of what is wrong."""
    from stable_baselines3 import PPO

    folder = tmp_path_factory.mktemp("models")
    (folder / "text.zip").write_text("not a zip")
    with zipfile.ZipFile(folder / "empty.zip", "w") as archive:
        archive.writestr("readme.txt", "a zip, but no model in it")
    (folder / "folder.zip").mkdir()
    PPO("MlpPolicy", gym.make("CartPole-v1"), n_steps=64, device="cpu").save(folder / "cart")
    PPO("MlpPolicy", ThreeActions(), n_steps=64, device="cpu").save(folder / "three")
    narrow = {"net_arch": [8]}
    PPO("MlpPolicy", FightShaped(), policy_kwargs=narrow, device="cpu").save(folder / "narrow")
    broken = PPO("MlpPolicy", FightShaped(), device="cpu")
    with torch.no_grad():
        broken.policy.value_net.bias[0] = float("inf")
    broken.save(folder / "broken")
    return folder


class FightShaped(gym.Env):
    """The fight's observation and action spaces, and nothing else."""

    observation_space = gym.spaces.Box(-1.0, 1.0, (OBSERVATION_SIZE,), np.float32)
    action_space = gym.spaces.Discrete(len(Action))

    def reset(self, *, seed=None, options=None):
        return np.zeros(OBSERVATION_SIZE, np.float32), {}

    def step(self, action):
        return np.zeros(OBSERVATION_SIZE, np.float32), 0.0, True, False, {}


class ThreeActions(FightShaped):
    """The fight's observations, but only three actions."""

    action_space = gym.spaces.Discrete(3)


MODELS = [
    ("text.zip", "is not a saved PPO model"),
    ("empty.zip", "is not a saved PPO model"),
    ("folder.zip", "no saved model at"),
    ("missing.zip", "no saved model at"),
    ("cart.zip", "expects observations of shape (4,)"),
    ("three.zip", "has 3 actions, the fight has"),
]


@pytest.mark.parametrize("name, message", MODELS)
def test_a_bad_model_is_refused_by_every_tool(bad_models, name, message, tmp_path, capsys):
    model = str(bad_models / name)
    out = tmp_path / "run"
    err = usage_error(train.main, ["--config", "smoke", "--init", model, "--out", str(out)], capsys)
    assert f"init = {model!r}" in err and message in err
    assert not out.exists()
    for main, argv in (
        (match.main, ["rush", model, "--episodes", "1"]),
        (evaluate.main, [model, "--episodes", "1"]),
        (tournament.main, ["--scripted", "rush", "--models", model, "--out", str(tmp_path / "t")]),
    ):
        err = usage_error(main, argv, capsys)
        assert message in err and "Traceback" not in err


@pytest.mark.parametrize(
    "name, message",
    [
        ("narrow.zip", "its policy network has layers [8], which do not fit net_arch = [64, 64]"),
        ("broken.zip", "1 non-finite weights, in value_net.bias (1 of 1)"),
    ],
)
def test_a_model_training_cannot_start_from_is_a_usage_error(bad_models, name, message, capsys):
    model = str(bad_models / name)
    out = bad_models / "run"
    err = usage_error(train.main, ["--config", "smoke", "--init", model, "--out", str(out)], capsys)
    assert f"init = {model!r}" in err and message in err
    assert not out.exists()


def test_a_seed_past_2_to_the_31_is_a_good_seed():
    assert load_train_config("smoke", seed=3_000_000_000).seed == 3_000_000_000


@pytest.mark.parametrize(
    "flags, message",
    [
        (["--seed", "-1"], "seed = -1 is not allowed: must be in 0 .."),
        (["--seed", "4294967296"], "with seed = 4294967296: seed must be an integer in +-42949"),
        (["--seed", "one"], "--seed: invalid int value: 'one'"),
        (["--steps", "0"], "total_timesteps = 0 is not allowed: must be >= 1"),
        (["--steps", "-5"], "total_timesteps = -5 is not allowed"),
        (["--minutes", "-1"], "--minutes: must be a number >= 0 (0: no budget), got '-1'"),
        (["--minutes", "nan"], "--minutes: must be a number >= 0"),
        (["--minutes", "inf"], "--minutes: must be a number >= 0"),
        (["--minutes", "soon"], "--minutes: invalid _minutes value: 'soon'"),
        (["--resume", "--overwrite"], "--resume continues a run, --overwrite deletes it"),
        (["--resume"], "--resume: no run folder at"),
        (["--init", "nowhere.zip"], "init = 'nowhere.zip': no saved model at nowhere.zip"),
        (
            ["--config", "nope"],
            "unknown training config 'nope'; known: default, pixels, rllib_selfplay, rllib_smoke, "
            "selfplay",
        ),
        (["--config", "missing.toml"], "cannot read training config file missing.toml"),
    ],
)
def test_bad_training_flags_are_usage_errors(flags, message, tmp_path, capsys):
    out = tmp_path / "run"
    err = usage_error(train.main, ["--config", "smoke", "--out", str(out), *flags], capsys)
    assert message in err and "Traceback" not in err
    assert not out.exists()


@pytest.mark.parametrize(
    ("module", "config"), [("agents.league", "smoke"), ("agents.train_rllib", "rllib_smoke")]
)
@pytest.mark.parametrize("minutes", ["-1", "nan", "inf", "soon"])
def test_every_trainer_refuses_a_bad_minutes_flag(module, config, minutes, tmp_path, capsys):
    out = tmp_path / "run"
    cli = importlib.import_module(module).main
    err = usage_error(cli, ["--config", config, "--out", str(out), "--minutes", minutes], capsys)
    assert "--minutes: " in err and repr(minutes) in err and "Traceback" not in err
    assert not out.exists()


def test_an_out_that_is_a_file_is_a_usage_error(tmp_path, capsys):
    out = tmp_path / "run"
    out.write_text("a file")
    err = usage_error(train.main, ["--config", "smoke", "--out", str(out)], capsys)
    assert f"--out {out} is a file" in err


@pytest.mark.parametrize(
    "tool, argv, message",
    [
        ("match", ["rush", "idle", "--episodes", "0"], "--episodes: must be >= 1, got 0"),
        ("match", ["rush", "idle", "--seed", "-3"], "--seed: must be >= 0, got -3"),
        ("match", ["rush", "idle", "--max-cycles", "0"], "max_cycles = 0 is not allowed"),
        ("match", ["rush", "idle", "--record-scale", "0"], "--record-scale 0 is not allowed"),
        ("match", ["rush", "idle", "--save-replay", "{tmp}"], "--save-replay {tmp} is a folder"),
        ("match", ["rush", "idle", "--save-replay", "{file}/r.json"], "{file} is a file, not a"),
        ("match", ["rush", "idle", "--record", "{tmp}/clip.gif"], "clip.gif is a folder"),
        ("match", ["rush", "idle", "--replay", "r.json"], "give no policies with it"),
        ("match", ["rush", "idle", "ninja"], "give two policies (got 3)"),
        ("tournament", ["--out", "{tmp}"], "--out {tmp} is a folder"),
        ("tournament", ["--out", "{file}/elo.json"], "{file} is a file, not a folder"),
        ("tournament", ["--scripted", "rush"], "at least two entrants, got 1"),
        ("tournament", ["--scripted", "rush", "ninja"], "unknown policy 'ninja'"),
        ("tournament", ["--episodes", "-1"], "--episodes: must be >= 1, got -1"),
        ("evaluate", ["rush", "--opponents"], "give at least one opponent"),
        ("evaluate", ["rush", "--opponents", "ninja"], "unknown policy 'ninja'"),
        ("evaluate", ["rush", "--out", "{tmp}"], "--out {tmp} is a folder"),
        ("evaluate", ["rush", "--config", "nope"], "unknown config 'nope'"),
        ("evaluate", ["rush", "--episodes", "zero"], "--episodes: invalid _positive value"),
    ],
)
def test_bad_match_tool_flags_are_usage_errors(tool, argv, message, tmp_path, capsys):
    file = tmp_path / "a_file"
    file.write_text("")
    (tmp_path / "clip.gif").mkdir()
    fill = {"tmp": str(tmp_path), "file": str(file)}
    main = {"match": match.main, "tournament": tournament.main, "evaluate": evaluate.main}[tool]
    err = usage_error(main, [arg.format(**fill) for arg in argv], capsys)
    assert message.format(**fill) in err and "Traceback" not in err
