"""Fixtures the agents' tests share."""

from __future__ import annotations

import tempfile

import pytest


@pytest.fixture(scope="module")
def tiny_model(tmp_path_factory):
    """An untrained PPO fighter saved as `tiny.zip`: a model file the commands can load."""
    pytest.importorskip("stable_baselines3")
    from stable_baselines3 import PPO

    from vooga_env.envs.sb3 import FightVecEnv

    model = PPO(
        "MlpPolicy",
        FightVecEnv(2, "small", opponent="idle"),
        n_steps=8,
        batch_size=16,
        policy_kwargs={"net_arch": [8]},
        seed=0,
        device="cpu",
    )
    path = tmp_path_factory.mktemp("models") / "tiny.zip"
    model.save(path)
    return path


@pytest.fixture
def temp_folder(tmp_path, monkeypatch):
    """An empty folder as the temp folder, this process's and its children's: SB3's learn()
    without TensorBoard made an empty SB3-<time> folder there each time (thousands in /tmp)."""
    folder = tmp_path / "temp"
    folder.mkdir()
    monkeypatch.setattr(tempfile, "tempdir", str(folder))
    monkeypatch.setenv("TMPDIR", str(folder))
    return folder
