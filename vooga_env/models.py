"""Loading saved SB3 models as fighters, with a clear error when their spaces do not fit."""

from __future__ import annotations

from pathlib import Path
from typing import Any

from vooga_env.actions import Action
from vooga_env.observations import OBSERVATION_SIZE


def load_model(path: str | Path) -> Any:
    """A saved PPO model, checked against the fight's observation and action spaces."""
    try:
        from stable_baselines3 import PPO
    except ImportError:
        raise ImportError(
            "loading a saved model needs stable-baselines3: pip install 'vooga-env[train]'"
        ) from None
    path = Path(path)
    if not path.is_file() and not path.with_suffix(".zip").is_file():
        raise FileNotFoundError(f"no saved model at {path}")
    model = PPO.load(path, device="cpu")
    observation_shape = getattr(model.observation_space, "shape", None)
    if observation_shape != (OBSERVATION_SIZE,):
        raise ValueError(
            f"model {path} expects observations of shape {observation_shape}, "
            f"the fight gives ({OBSERVATION_SIZE},)"
        )
    actions = getattr(model.action_space, "n", None)
    if actions != len(Action):
        raise ValueError(f"model {path} has {actions} actions, the fight has {len(Action)}")
    return model
