"""RLlib self-play on the tests' Ray (conftest): train, resume, export, play; clear errors for
bad input. Skipped without the `rllib` extra."""

import contextlib
import json
import os
import shutil
import signal
import socket
import subprocess
import sys
import threading
import time
from pathlib import Path
from typing import Any

import numpy as np
import pytest

ray = pytest.importorskip("ray")
pytest.importorskip("ray.rllib")

from agents import train_rllib  # noqa: E402
from agents.rllib_config import load_rllib_config  # noqa: E402
from agents.rllib_export import export_checkpoint  # noqa: E402
from agents.train_rllib import CHECKPOINT, check_address, connect, main, train  # noqa: E402
from vooga_env.envs.gym_env import FightEnv  # noqa: E402
from vooga_env.game.config import ConfigError  # noqa: E402
from vooga_env.game.observations import OBSERVATION_SIZE  # noqa: E402
from vooga_env.policies import make_policy  # noqa: E402
from vooga_env.policies.models import load_mlp, save_mlp  # noqa: E402
from vooga_env.tools.match import run_match  # noqa: E402

ROOT = Path(__file__).resolve().parents[3]


def test_smoke_trains_resumes_and_logs_the_league(smoke_run):
    folder, first, second = smoke_run.folder, smoke_run.first, smoke_run.second
    config = load_rllib_config("rllib_smoke")
    assert first["iteration"] == 1
    assert first["league"]["snapshots"] == ["main_v1"]  # snapshot_every = 1
    assert second["iteration"] == 2
    assert second["league"]["snapshots"] == ["main_v1", "main_v2"]
    progress = [json.loads(line) for line in (folder / "progress.jsonl").read_text().splitlines()]
    assert [p["iteration"] for p in progress] == [1, 2]
    assert progress[-1]["env_steps"] >= config.ppo.train_batch_size
    assert progress[-1]["pool"] == ["idle", "rush", "main_v1", "main_v2"]  # after iteration 2
    assert set(progress[-1]["elo"]) >= {"main", "main_v1"}
    assert sum(second["nodes"].values()) >= 2 * config.ppo.train_batch_size


def test_the_exported_fighter_plays_matches_and_the_gym_env(smoke_run):
    folder = smoke_run.folder
    fighter = make_policy(folder / "main.npz")
    result = run_match(fighter, "rush", episodes=2, config="small", seed=0)
    assert result.games == 2
    env = FightEnv(config="small", opponent=str(folder / "main.npz"))
    observation, _ = env.reset(seed=0)
    env.step(fighter.act(observation))


def test_export_gives_the_modules_own_logits(smoke_run, tmp_path):
    import torch
    from ray.rllib.core.columns import Columns
    from ray.rllib.core.rl_module.rl_module import RLModule

    folder = smoke_run.folder
    path = export_checkpoint(folder / CHECKPOINT, "main_v2", tmp_path / "exported.npz")
    module = RLModule.from_checkpoint(
        folder / CHECKPOINT / "learner_group" / "learner" / "rl_module" / "main_v2"
    )
    observations = np.random.default_rng(0).uniform(-1, 1, (16, OBSERVATION_SIZE))
    with torch.no_grad():
        batch = {Columns.OBS: torch.as_tensor(observations, dtype=torch.float32)}
        expected = module.forward_inference(batch)[Columns.ACTION_DIST_INPUTS].numpy()
    exported = load_mlp(path)
    np.testing.assert_allclose(exported.logits(observations), expected, atol=1e-5)
    assert np.array_equal(exported.logits(observations).argmax(1), expected.argmax(1))


def test_resume_from_a_checkpoint_that_does_not_fit_names_it(smoke_run, tmp_path):
    folder = tmp_path / "run"
    shutil.copytree(smoke_run.folder, folder)
    wider = load_rllib_config("rllib_smoke", iterations=3, ppo={"net_arch": [48, 48]})
    with pytest.raises(ConfigError, match=f"checkpoint {folder / CHECKPOINT} does not fit"):
        train(wider, folder, resume=True, echo=False)


def test_more_env_runners_or_gpus_than_the_cluster_has_are_refused_not_waited_for(ray_cluster):
    with pytest.raises(ConfigError, match="env_runners = 3, .* need 3 CPUs; .* has 2 CPUs"):
        connect(None, load_rllib_config("rllib_smoke", env_runners=3))
    with pytest.raises(ConfigError, match="gpus_per_learner = 1 need 1 GPUs; .* has 0 GPUs"):
        connect(None, load_rllib_config("rllib_smoke", gpus_per_learner=1.0))


def test_an_address_that_does_not_answer_fails_within_seconds(capsys, tmp_path):
    start = time.monotonic()
    with pytest.raises(SystemExit):
        main(["--config", "rllib_smoke", "--out", str(tmp_path), "--address", "127.0.0.1:9"])
    assert time.monotonic() - start < 10
    assert "--address 127.0.0.1:9: no Ray cluster answers there" in capsys.readouterr().err
    with pytest.raises(ConfigError, match="not HOST:PORT"):
        check_address("nowhere")


@pytest.fixture
def listener():
    """Starts servers that accept, read, then send a reply (None: stay silent); HOST:PORT."""
    servers = []

    def start(reply: bytes | None) -> str:
        server = socket.create_server(("127.0.0.1", 0))
        servers.append(server)
        threading.Thread(target=serve, args=(server, reply), daemon=True).start()
        return f"127.0.0.1:{server.getsockname()[1]}"

    def serve(server: socket.socket, reply: bytes | None) -> None:
        held = []  # kept open: a silent server, not one that hangs up
        with contextlib.suppress(OSError):  # the server closed at the test's end
            while True:
                held.append(server.accept()[0])
                held[-1].recv(64)
                if reply is not None:
                    held[-1].sendall(reply)

    yield start
    for server in servers:
        server.close()


def test_an_address_that_accepts_but_is_not_ray_fails_within_the_timeout(
    monkeypatch, listener, ray_cluster
):
    """ray.init would wait on these for minutes; a real head passes the same check."""
    monkeypatch.setattr(train_rllib, "CONNECT_TIMEOUT_S", 0.5)
    silent = listener(None)
    with pytest.raises(ConnectionError, match=f"{silent}: no Ray cluster answers .*timed out"):
        check_address(silent)
    web = listener(b"HTTP/1.1 400 Bad Request\r\n\r\n")
    with pytest.raises(ConnectionError, match=f"{web}: something answers .* not as a Ray"):
        check_address(web)
    check_address(ray.get_runtime_context().gcs_address)


def test_an_unknown_module_id_is_named_with_the_known_ones(tmp_path):
    modules = tmp_path / CHECKPOINT / "learner_group" / "learner" / "rl_module"
    for name in ("main", "rush"):
        (modules / name).mkdir(parents=True)
    with pytest.raises(KeyError, match="module 'mian' is not in .* it holds main, rush"):
        export_checkpoint(tmp_path / CHECKPOINT, "mian", tmp_path / "x.npz")


def test_resume_from_a_checkpoint_of_another_observation_size_names_both(tmp_path):
    """Refused before Ray starts: a module saved for 45 observations, where the fight has 41."""
    import gymnasium

    main_path = tmp_path / CHECKPOINT / "learner_group" / "learner" / "rl_module" / "main"
    module = default_module(gymnasium.spaces.Box(-2, 2, (OBSERVATION_SIZE + 4,), np.float32))
    module.save_to_path(main_path)
    (tmp_path / "train_state.json").write_text(json.dumps({"iteration": 1}))
    start = time.monotonic()
    with pytest.raises(ConfigError, match=r"reads observations of shape \(45,\), .* gives \(41,\)"):
        train(load_rllib_config("rllib_smoke"), tmp_path, resume=True, echo=False)
    assert time.monotonic() - start < 10


def test_a_fighter_for_another_observation_size_is_refused(tmp_path):
    rng = np.random.default_rng(0)
    layers = [(rng.normal(size=(OBSERVATION_SIZE + 3, 8)), np.zeros(8)), (np.ones((8, 10)), [0])]
    path = save_mlp(tmp_path / "other.npz", layers, "tanh")
    with pytest.raises(ValueError, match=f"observations of size {OBSERVATION_SIZE + 3}"):
        make_policy(path)


def test_bad_config_keys_are_named():
    with pytest.raises(ConfigError, match="unknown key 'ppo.lambda'"):
        load_rllib_config("rllib_smoke", ppo={"lambda": 0.9})
    with pytest.raises(ConfigError, match="scripted = 'rushh' is not allowed"):
        load_rllib_config("rllib_smoke", league={"scripted": ["rushh"]})


def test_a_bad_minutes_is_refused_before_anything_is_written(tmp_path):
    with pytest.raises(ConfigError, match="minutes = -1.0 is not allowed: must be >= 0"):
        train(load_rllib_config("rllib_smoke"), tmp_path / "run", minutes=-1.0, echo=False)
    assert not (tmp_path / "run").exists()


@pytest.mark.slow  # ~25 s each: a Ray of its own in a subprocess
@pytest.mark.parametrize("signum", [signal.SIGINT, signal.SIGTERM], ids=["ctrl_c", "sigterm"])
def test_ctrl_c_or_sigterm_keeps_the_last_checkpoint(tmp_path, ray_temp_dir, no_ray_left, signum):
    """SIGTERM as from `kill` or a job scheduler: ray.init's own handler, which exits without
    the checkpoint, gives way to the command's."""
    out = tmp_path / "run"
    command = [sys.executable, "-m", "agents.train_rllib", "--config", "rllib_smoke"]
    command += ["--out", str(out), "--iterations", "1000"]
    # As at a terminal: a suite started in the background inherits an ignored SIGINT.
    process = subprocess.Popen(
        command,
        cwd=ROOT,
        stderr=subprocess.PIPE,
        text=True,
        env={**os.environ, "RAY_TMPDIR": str(ray_temp_dir)},
        preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL),
    )
    deadline = time.monotonic() + 120
    while not (out / "train_state.json").is_file():
        assert process.poll() is None and time.monotonic() < deadline, process.stderr.read()
        time.sleep(0.2)
    process.send_signal(signum)
    _, stderr = process.communicate(timeout=60)
    assert process.returncode == 130, stderr
    assert "--resume" in stderr
    state = json.loads((out / "train_state.json").read_text())
    assert 1 <= state["iteration"] < 1000
    assert make_policy(out / "main.npz").act(np.zeros(OBSERVATION_SIZE)) in range(10)
    no_ray_left(ray_temp_dir)


def default_module(observation_space, **model: Any) -> Any:
    """RLlib's default PPO torch module for these spaces, built without Ray running."""
    import gymnasium
    from ray.rllib.algorithms.ppo.torch.default_ppo_torch_rl_module import (
        DefaultPPOTorchRLModule,
    )
    from ray.rllib.core.rl_module.default_model_config import DefaultModelConfig
    from ray.rllib.core.rl_module.rl_module import RLModuleSpec

    return RLModuleSpec(
        module_class=DefaultPPOTorchRLModule,
        observation_space=observation_space,
        action_space=gymnasium.spaces.Discrete(10),
        model_config=DefaultModelConfig(**{"fcnet_hiddens": [16, 8], **model}),
    ).build()


@pytest.mark.parametrize(("shared", "activation"), [(True, "relu"), (False, "tanh")])
def test_export_reads_shared_and_separate_actor_encoders(shared, activation, tmp_path):
    """Both layouts of RLlib's default PPO module."""
    import gymnasium
    import torch
    from ray.rllib.core.columns import Columns

    from agents.rllib_export import export_module
    from vooga_env.game.observations import HIGH, LOW

    space = gymnasium.spaces.Box(LOW, HIGH, (OBSERVATION_SIZE,), np.float32)
    module = default_module(space, fcnet_activation=activation, vf_share_layers=shared)
    exported = load_mlp(export_module(module, tmp_path / "m.npz"))
    assert exported.activation_name == activation
    observations = np.random.default_rng(1).uniform(-2, 2, (8, OBSERVATION_SIZE))
    with torch.no_grad():
        batch = {Columns.OBS: torch.as_tensor(observations, dtype=torch.float32)}
        expected = module.forward_inference(batch)[Columns.ACTION_DIST_INPUTS].numpy()
    np.testing.assert_allclose(exported.logits(observations), expected, atol=1e-5)
