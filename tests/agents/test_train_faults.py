"""Training loses nothing: SIGKILL at random points then --resume, a diverging run, two runs on
one folder, and a state file that must agree with the checkpoint it names."""

from __future__ import annotations

import json
import os
import random
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest
import torch

from agents import train as train_cli
from agents.checkpoints import STATE_FILE, BrokenRun, Diverged, read_state, sha256
from agents.train import build_model, make_envs, train
from agents.train_config import load_train_config
from vooga_env.game.config import ConfigError
from vooga_env.policies.models import load_model

ROOT = Path(__file__).resolve().parents[2]


def finite(path: Path) -> bool:
    return all(torch.isfinite(t).all() for t in load_model(path).policy.state_dict().values())


def check_committed(folder: Path) -> int:
    """What a kill must leave: a state whose checkpoint is whole, loads and is at its step."""
    if not (folder / STATE_FILE).exists():
        return 0  # killed before the first checkpoint: --resume starts from step 0
    state = read_state(folder)  # every file it names is there with its sha256
    assert load_model(folder / state["checkpoint"]).num_timesteps == state["num_timesteps"]
    return state["num_timesteps"]


def wait_to_kill(
    process: subprocess.Popen, folder: Path, rng: random.Random, spread: float
) -> None:
    """Sleep to a random moment of the run: a third of the time in its first `spread` seconds
    (imports, the resume's checks and repairs, the first checkpoint), else in the `spread / 2`
    seconds after it commits a checkpoint, as it trains on and writes the next one."""
    if rng.random() < 1 / 3:
        time.sleep(rng.uniform(0.0, spread))
        return

    def commit() -> tuple[int, int] | None:
        state = folder / STATE_FILE
        return (state.stat().st_ino, state.stat().st_mtime_ns) if state.exists() else None

    before, deadline = commit(), time.monotonic() + 120
    while commit() == before and process.poll() is None and time.monotonic() < deadline:
        time.sleep(0.02)
    time.sleep(rng.uniform(0.0, spread / 2))


def kill_and_resume(
    folder: Path, config: str, steps: int, kills: int, seed: int, spread: float
) -> tuple[int, int]:
    """SIGKILL the run `kills` times at random moments, resuming each time; return the kills that
    hit a live run, and those that cut a write short (they left a temp file). Then resume once
    more to the end and check every file the run left."""
    rng = random.Random(seed)
    command = [sys.executable, "-m", "agents.train", "--config", config, "--steps", str(steps)]
    command += ["--out", str(folder), "--no-progress"]
    survived = cut = 0
    for _ in range(kills):
        resume = ["--resume"] if folder.exists() else []
        process = subprocess.Popen(
            command + resume, cwd=ROOT, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE
        )
        wait_to_kill(process, folder, rng, spread)
        if process.poll() is None:
            process.send_signal(signal.SIGKILL)
            survived += 1
        _, stderr = process.communicate(timeout=120)
        assert process.returncode in (0, -signal.SIGKILL), stderr.decode()
        check_committed(folder)
        cut += bool([*folder.rglob(".*.tmp"), *folder.rglob(".*.link")])
    done = subprocess.run(command + ["--resume"], cwd=ROOT, capture_output=True, timeout=300)
    assert done.returncode == 0, done.stderr.decode()
    assert check_committed(folder) == steps
    assert load_model(folder / "final.zip").num_timesteps == steps
    assert sha256(folder / "latest.zip") == sha256(folder / read_state(folder)["checkpoint"])
    for path in folder.rglob("*.zip"):
        load_model(path)  # every checkpoint and snapshot whole
    assert not [*folder.rglob("*.tmp"), *folder.rglob("*.link")]
    return survived, cut


def test_sigkill_at_random_points_then_resume_reaches_the_end(tmp_path):
    survived, _ = kill_and_resume(tmp_path / "run", "smoke", 4096, kills=2, seed=0, spread=3.0)
    assert survived >= 1


@pytest.mark.slow
@pytest.mark.parametrize("config", ["smoke", "smoke_selfplay"])
def test_many_sigkills_then_resume_reaches_the_end(tmp_path, config):
    survived, cut = kill_and_resume(tmp_path / "run", config, 16384, kills=25, seed=1, spread=6.0)
    print(f"{config}: {survived} kills survived, {cut} of them cut a write short")
    assert survived >= 15  # the others came after that run had ended


def test_a_diverging_run_keeps_the_last_good_checkpoint(tmp_path, capsys):
    config = load_train_config("smoke")
    model = build_model(config, make_envs(config), tmp_path)
    with torch.no_grad():  # a finite network whose first update overflows the value loss
        model.policy.value_net.weight.mul_(1e30)
    model.save(tmp_path / "overflowing.zip")
    out = tmp_path / "run"
    argv = ["--config", "smoke", "--init", str(tmp_path / "overflowing.zip"), "--out", str(out)]
    assert train_cli.main([*argv, "--no-progress"]) == 1
    err = capsys.readouterr().err
    assert "training diverged by step" in err and "non-finite weights, in " in err
    assert "kept the last good checkpoint" in err
    state = read_state(out)
    assert state["num_timesteps"] < config.total_timesteps
    assert str(out / state["checkpoint"]) in err
    for path in out.rglob("*.zip"):
        assert finite(path), path  # nothing non-finite was saved, over the good one or beside
    assert not (out / "final.zip").exists()


def test_a_non_finite_model_is_never_a_starting_point(tmp_path):
    config = load_train_config("smoke")
    model = build_model(config, make_envs(config), tmp_path)
    with torch.no_grad():
        model.policy.action_net.bias[0] = float("nan")
    model.save(tmp_path / "nan.zip")
    with pytest.raises(ConfigError, match=r"nan\.zip.*1 non-finite weights, in action_net\.bias"):
        train(load_train_config("smoke", init=str(tmp_path / "nan.zip")), tmp_path / "run")
    assert not (tmp_path / "run").exists()


def test_resume_puts_latest_back_in_step_with_the_state(tmp_path):
    out = tmp_path / "run"
    train(load_train_config("smoke", total_timesteps=1024), out, progress=False)
    older = out / "checkpoints" / "ppo_0_steps.zip"
    (out / "latest.zip").unlink()
    os.link(older, out / "latest.zip")  # as a kill between the state and its link leaves it
    (out / "checkpoints" / ".ppo_2048_steps.zip.77.abcd.tmp").write_bytes(b"half a zip")
    train(load_train_config("smoke", total_timesteps=2048), out, resume=True, progress=False)
    assert sha256(out / "latest.zip") == sha256(out / "checkpoints" / "ppo_2048_steps.zip")
    assert load_model(out / "latest.zip").num_timesteps == 2048
    assert not [*out.rglob("*.tmp")]


def test_resume_refuses_a_checkpoint_that_changed_under_its_state(tmp_path, capsys):
    out = tmp_path / "run"
    train(load_train_config("smoke", total_timesteps=512), out, progress=False)
    committed = out / json.loads((out / STATE_FILE).read_text())["checkpoint"]
    committed.write_bytes(committed.read_bytes()[:-10])  # truncated behind our back
    with pytest.raises(BrokenRun, match=f"{committed}, committed in .* is missing or changed"):
        read_state(out)
    argv = ["--config", "smoke", "--out", str(out), "--resume", "--no-progress"]
    with pytest.raises(SystemExit) as stop:
        train_cli.main(argv)
    assert stop.value.code == 2 and "missing or changed" in capsys.readouterr().err


def test_a_used_folder_is_locked_and_a_stale_lock_taken_over(tmp_path, capsys):
    out = tmp_path / "run"
    command = [sys.executable, "-m", "agents.train", "--config", "smoke", "--steps", "400000"]
    process = subprocess.Popen(
        [*command, "--out", str(out), "--no-progress"], cwd=ROOT, stderr=subprocess.PIPE
    )
    try:
        deadline = time.monotonic() + 120
        while not (out / STATE_FILE).exists():  # the lock is taken before the state is written
            assert process.poll() is None and time.monotonic() < deadline
            time.sleep(0.1)
        assert (out / ".lock").read_text().strip() == str(process.pid)
        for flags in ([], ["--resume"], ["--overwrite"]):
            argv = ["--config", "smoke", "--out", str(out), "--no-progress", *flags]
            with pytest.raises(SystemExit) as stop:
                train_cli.main(argv)
            err = capsys.readouterr().err
            assert stop.value.code == 2, flags
            assert f"in use by another training run (pid {process.pid})" in err
        assert (out / STATE_FILE).exists()  # --overwrite deleted nothing
    finally:
        process.send_signal(signal.SIGKILL)
        process.communicate(timeout=60)
    state = read_state(out)
    resumed = load_train_config("smoke", total_timesteps=state["num_timesteps"] + 512)
    train(resumed, out, resume=True, progress=False)
    assert f"taking over the lock left by pid {process.pid}" in capsys.readouterr().out
    assert (out / ".lock").read_text() == ""  # released cleanly this time
    assert load_model(out / "final.zip").num_timesteps == state["num_timesteps"] + 512


def test_a_diverged_model_is_not_saved_over_a_good_one(tmp_path):
    from agents.checkpoints import save_checkpoint

    config = load_train_config("smoke")
    model = build_model(config, make_envs(config), tmp_path)
    save_checkpoint(model, tmp_path, [])
    before = {path: sha256(path) for path in tmp_path.rglob("*") if path.is_file()}
    with torch.no_grad():
        model.policy.mlp_extractor.policy_net[0].weight[0, :3] = np.inf
    model.num_timesteps = 512
    with pytest.raises(Diverged, match=r"3 non-finite weights, in mlp_extractor\.policy_net\.0"):
        save_checkpoint(model, tmp_path, [])
    assert {path: sha256(path) for path in tmp_path.rglob("*") if path.is_file()} == before


def test_a_write_that_fails_half_way_leaves_the_old_file_whole(tmp_path):
    from vooga_env.tools.files import atomic_write, atomic_write_text

    path = atomic_write_text(tmp_path / "report.json", "old, whole")

    def half_then_fail(temporary: str) -> None:
        Path(temporary).write_text("new, but on")
        raise OSError("disk full")

    with pytest.raises(OSError, match="disk full"):
        atomic_write(path, half_then_fail)
    assert path.read_text() == "old, whole"
    assert [p.name for p in tmp_path.iterdir()] == ["report.json"]  # no temp file left behind
