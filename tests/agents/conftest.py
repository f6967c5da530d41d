"""Fixtures the agents' tests share."""

from __future__ import annotations

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
