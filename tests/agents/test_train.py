"""Smoke runs of the training script: files written and loadable, resume, interrupts keep work."""

import dataclasses
import json
import signal
import sys
from pathlib import Path

import pytest

from agents.train import main, make_envs, train
from agents.train_config import load_train_config
from tests.agents.interrupt import interrupt_when
from vooga_env.game.config import ConfigError
from vooga_env.policies import SCRIPTED
from vooga_env.policies.models import load_model

ROOT = Path(__file__).resolve().parents[2]


def test_scripted_curriculum_writes_loadable_models(tmp_path):
    config = load_train_config("smoke")
    final = train(config, tmp_path, progress=False)
    assert load_model(final).num_timesteps == config.total_timesteps
    state = json.loads((tmp_path / "train_state.json").read_text())
    assert state["num_timesteps"] == config.total_timesteps
    assert state["opponent"] in config.curriculum.ladder
    checkpoints = sorted((tmp_path / "checkpoints").glob("*.zip"))
    names = ["ppo_0_steps.zip", "ppo_1024_steps.zip", "ppo_2048_steps.zip"]  # 0: resumable at once
    assert sorted(p.name for p in checkpoints) == sorted(names)
    assert state["checkpoint"] == "checkpoints/ppo_2048_steps.zip"
    load_model(checkpoints[0])


def test_resume_continues_from_the_last_checkpoint(tmp_path, temp_folder):
    first = load_train_config("smoke", total_timesteps=1024)
    train(first, tmp_path, progress=False)
    second = load_train_config("smoke", total_timesteps=2048)
    final = train(second, tmp_path, resume=True, progress=False)
    assert load_model(final).num_timesteps == 2048
    assert (tmp_path / "checkpoints" / "ppo_2048_steps.zip").is_file()
    assert list(temp_folder.glob("SB3-*")) == []  # no logger folder of SB3's left behind


@pytest.mark.parametrize(("minutes", "steps"), [(None, "fewer"), (0.0, "all")])
def test_minutes_0_lifts_the_configs_clock(tmp_path, minutes, steps):
    config = load_train_config("smoke", minutes=1e-9, total_timesteps=1024)
    train(config, tmp_path, progress=False, minutes=minutes)
    trained = json.loads((tmp_path / "train_state.json").read_text())["num_timesteps"]
    assert (trained == 1024) == (steps == "all") and trained > 0


@pytest.mark.parametrize("resumed", [False, True])
def test_entropy_and_learning_rate_follow_their_schedules_through_a_resume(tmp_path, resumed):
    text = (ROOT / "configs" / "train" / "smoke.toml").read_text()
    path = tmp_path / "decay.toml"
    schedules = [
        "ent_coef = 0.01",
        "ent_decay_steps = 4096",
        "learning_rate = 4e-4",
        "learning_rate_final = 1e-4",
        "lr_decay_steps = 4096",
    ]
    path.write_text(text.replace("n_epochs = 1", "\n".join(["n_epochs = 1", *schedules])))
    if resumed:
        train(load_train_config(path, total_timesteps=1024), tmp_path / "run", progress=False)
    final = train(load_train_config(path), tmp_path / "run", resume=resumed, progress=False)
    model = load_model(final)
    # the last update came after 2048 of the 4096 steps: half way along both schedules
    assert model.ent_coef == pytest.approx(0.005)
    assert model.policy.optimizer.param_groups[0]["lr"] == pytest.approx(2.5e-4)


def test_a_fresh_run_never_overwrites_an_old_one_unless_told(tmp_path, capsys):
    config = load_train_config("smoke", total_timesteps=512)
    train(config, tmp_path, progress=False)
    stale = tmp_path / "snapshots" / "snapshot_0.zip"
    stale.parent.mkdir()
    stale.write_bytes(b"an older run's file")
    with pytest.raises(FileExistsError, match="--resume continues it, --overwrite starts over"):
        train(config, tmp_path, progress=False)
    argv = ["--config", "smoke", "--out", str(tmp_path), "--no-progress"]
    with pytest.raises(SystemExit) as exit_info:
        main(argv)
    assert exit_info.value.code == 2 and "holds a run already" in capsys.readouterr().err
    assert main([*argv, "--overwrite"]) == 0
    assert not stale.exists()  # started over: nothing of the old run is left to mix in
    mine = tmp_path / "elsewhere" / "notes.txt"
    mine.parent.mkdir()
    mine.write_text("not a run's")
    again = ["--steps", "512", "--out", str(mine.parent), "--no-progress", "--overwrite"]
    assert main([*argv[:2], *again]) == 0
    assert mine.read_text() == "not a run's"  # a folder without a run is not emptied


def test_init_starts_from_a_saved_models_weights_or_says_why_not(tmp_path):
    import torch

    from agents.train import build_model, start_from

    config = load_train_config("smoke", total_timesteps=512)
    saved = train(config, tmp_path / "first", progress=False)
    model = build_model(config, make_envs(config), tmp_path)
    start_from(model, load_model(saved))
    expected = load_model(saved).policy.state_dict()
    for name, tensor in model.policy.state_dict().items():
        assert torch.equal(tensor, expected[name]), name
    wider = load_train_config("smoke", init=str(saved))
    wider = dataclasses.replace(wider, ppo=dataclasses.replace(wider.ppo, net_arch=(8,)))
    with pytest.raises(ConfigError, match=r"init = .*layers \[64, 64\], .*net_arch = \[8\]"):
        train(wider, tmp_path / "second", progress=False)
    assert not (tmp_path / "second").exists()  # refused before any work
    with pytest.raises(ConfigError, match="init = 'nowhere.zip': no saved model"):
        train(load_train_config("smoke", init="nowhere.zip"), tmp_path / "third", progress=False)


def test_resume_keeps_the_reward_normaliser_statistics(tmp_path):
    from stable_baselines3.common.vec_env import VecNormalize

    path = tmp_path / "normalised.toml"
    path.write_text(
        'fight = "small"\ntotal_timesteps = 1024\nn_envs = 2\ncheckpoint_every = 512\n'
        "[ppo]\nn_steps = 256\nbatch_size = 256\nn_epochs = 1\nnormalize_reward = true\n"
    )
    out = tmp_path / "run"
    train(load_train_config(path), out, progress=False)
    saved = out / "vec_normalize.pkl"
    first = VecNormalize.load(str(saved), make_envs(load_train_config(path)).venv).ret_rms.count
    assert first >= 1024
    train(load_train_config(path, total_timesteps=2048), out, resume=True, progress=False)
    second = VecNormalize.load(str(saved), make_envs(load_train_config(path)).venv).ret_rms.count
    assert second >= first + 1024  # went on from the saved statistics, not from scratch


def test_selfplay_builds_a_snapshot_pool_with_ratings(tmp_path):
    path = tmp_path / "selfplay.toml"
    path.write_text(
        'mode = "selfplay"\nfight = "small"\ntotal_timesteps = 2048\nn_envs = 2\n'
        "checkpoint_every = 1024\n[ppo]\nn_steps = 256\nbatch_size = 256\nn_epochs = 1\n"
        "[selfplay]\nsave_steps = 512\nswap_steps = 256\nwindow = 3\n"
    )
    out = tmp_path / "run"
    train(load_train_config(path), out, progress=False)
    state = json.loads((out / "train_state.json").read_text())
    assert 1 < len(state["pool"]) <= 3
    assert set(state["pool"]) <= set(state["ratings"])
    for name in state["pool"]:
        load_model(out / "snapshots" / f"{name}.zip")


@pytest.mark.parametrize("name", ["smoke", "smoke_selfplay"])
def test_the_seed_makes_a_run_repeatable(tmp_path, name):
    import torch

    config = load_train_config(name, total_timesteps=4096)
    first, second = (train(config, tmp_path / run, progress=False) for run in ("a", "b"))
    one, two = (load_model(path).policy.state_dict() for path in (first, second))
    assert all(torch.equal(one[key], two[key]) for key in one)


@pytest.mark.parametrize("signum", [signal.SIGINT, signal.SIGTERM], ids=["ctrl_c", "sigterm"])
def test_ctrl_c_or_sigterm_keeps_the_last_checkpoint_and_resume_finishes(tmp_path, signum):
    config = tmp_path / "long.toml"
    config.write_text(
        'fight = "small"\ntotal_timesteps = 400000\nn_envs = 2\ncheckpoint_every = 512\n'
        "[ppo]\nn_steps = 256\nbatch_size = 256\nn_epochs = 1\n"
    )
    out = tmp_path / "run"
    command = [
        sys.executable,
        "-m",
        "agents.train",
        "--config",
        str(config),
        "--out",
        str(out),
        "--no-progress",
    ]
    ready = (out / "checkpoints" / "ppo_1024_steps.zip").is_file
    interrupt_when(command, ready, wait=120, stop=60, signum=signum)
    state = json.loads((out / "train_state.json").read_text())
    assert state["num_timesteps"] >= 1024
    assert load_model(out / "latest.zip").num_timesteps == state["num_timesteps"]
    assert not (out / "final.zip").exists()
    resumed = load_train_config(config, total_timesteps=state["num_timesteps"] + 512)
    final = train(resumed, out, resume=True, progress=False)
    assert load_model(final).num_timesteps == state["num_timesteps"] + 512


def test_a_crash_keeps_the_checkpoint(tmp_path, monkeypatch):
    from stable_baselines3 import PPO

    def crash(self, *args, **kwargs):
        self.num_timesteps = 77
        raise RuntimeError("boom")

    monkeypatch.setattr(PPO, "learn", crash)
    with pytest.raises(RuntimeError, match="boom"):
        train(load_train_config("smoke"), tmp_path, progress=False)
    assert json.loads((tmp_path / "train_state.json").read_text())["num_timesteps"] == 77
    assert (tmp_path / "latest.zip").is_file()


def test_config_typo_names_the_key(tmp_path):
    path = tmp_path / "typo.toml"
    path.write_text("[ppo]\nlearning_rat = 0.1\n")
    with pytest.raises(ConfigError, match=r"typo\.toml.*'ppo\.learning_rat'"):
        load_train_config(path)
    with pytest.raises(ConfigError, match="ladder.*ninja.*rush"):
        path.write_text('[curriculum]\nladder = ["ninja"]\n')
        load_train_config(path)
    with pytest.raises(SystemExit):
        main(["--config", "no_such_recipe"])


def test_the_benchmark_runs_in_quick_mode(tmp_path, capsys):
    from bench import train_recipe

    assert train_recipe.main(["--quick", "--out", str(tmp_path)]) == 0
    result = json.loads((tmp_path / "result.json").read_text())
    vs = result["vs_rush"]
    assert vs["wins"] + vs["losses"] + vs["draws"] == vs["games"] == 4
    names = {row["name"] for row in result["elo"]["ratings"]}
    assert names == {"model", *SCRIPTED}
    assert "Elo (K=16" in capsys.readouterr().out


def test_the_selfplay_benchmark_measures_latest_against_first(tmp_path):
    from bench import train_recipe

    assert train_recipe.main(["--quick", "--selfplay", "--out", str(tmp_path)]) == 0
    result = json.loads((tmp_path / "result.json").read_text())
    first = result["vs_first_snapshot"]
    assert result["vs_first_argmax"]["games"] == 4
    assert first["wins"] + first["losses"] + first["draws"] == first["games"] == 4
    assert train_recipe.first_snapshot(tmp_path).name == "snapshot_0.zip"


def test_torch_is_the_pinned_cpu_build():
    import torch

    pinned = (ROOT / "constraints.txt").read_text().split("torch==")[1].split()[0]
    assert torch.__version__.split("+")[0] == pinned


def test_resume_keeps_the_curriculums_recent_results(tmp_path):
    (tmp_path / "short.toml").write_text("max_cycles = 60\n")  # games that end within the run
    path = tmp_path / "run.toml"
    path.write_text(
        f'fight = "{tmp_path / "short.toml"}"\ntotal_timesteps = 512\nn_envs = 2\n'
        "checkpoint_every = 512\n[ppo]\nn_steps = 256\nbatch_size = 256\nn_epochs = 1\n"
        '[curriculum]\nladder = ["idle", "random"]\nwindow = 50\n'
    )
    out = tmp_path / "out"
    train(load_train_config(path), out, progress=False)
    before = json.loads((out / "train_state.json").read_text())
    assert before["results"]  # some games ended: their scores are what promotion is judged on
    train(load_train_config(path), out, resume=True, progress=False)
    after = json.loads((out / "train_state.json").read_text())
    assert after["results"] == before["results"] and after["stage"] == before["stage"]


def test_the_pixel_recipe_trains_a_cnn_on_stacked_images(tmp_path):
    from bench import train_recipe

    assert train_recipe.main(["--quick", "--pixels", "--out", str(tmp_path)]) == 0
    result = json.loads((tmp_path / "result.json").read_text())
    for opponent in ("idle", "random", "rush"):
        vs = result[f"vs_{opponent}"]
        assert vs["wins"] + vs["losses"] + vs["draws"] == vs["games"] == 4
    from stable_baselines3 import PPO

    model = PPO.load(tmp_path / "final.zip", device="cpu")
    assert model.observation_space.shape == (2, 36, 36)  # two stacked 36x36 (SB3: channels first)
    assert type(model.policy.features_extractor).__name__ == "NatureCNN"


@pytest.mark.slow  # 15 minutes of training, then 300 games
def test_the_pixel_recipe_beats_idle_and_random(tmp_path):
    from bench import train_recipe

    assert train_recipe.main(["--config", "pixels", "--games", "100", "--out", str(tmp_path)]) == 0
    result = json.loads((tmp_path / "result.json").read_text())
    assert result["vs_idle"]["win_rate"] >= 0.9 and result["vs_random"]["win_rate"] >= 0.9


@pytest.mark.parametrize(
    ("key", "value", "message"),
    [
        ("obs_type", "both", "obs_type = 'both' is not allowed: one of vector, pixels"),
        ("pixel_size", [8, 8], r"pixel_size = \(8, 8\) is not allowed"),
        ("frame_stack", 4, "frame_stack = 4 is not allowed: 1 with obs_type = 'vector'"),
    ],
)
def test_bad_pixel_training_options_name_the_key(tmp_path, key, value, message):
    path = tmp_path / "bad.toml"
    text = f"{key} = {json.dumps(value)}\n"
    if key == "pixel_size":
        text = 'obs_type = "pixels"\n' + text
    path.write_text(text)
    with pytest.raises(ConfigError, match=message):
        load_train_config(path)
