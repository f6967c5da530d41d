"""Saved SB3 models as fighters: loading with a space check, and a fast frozen copy for play."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np

from vooga_env.actions import Action
from vooga_env.observations import OBSERVATION_SIZE
from vooga_env.policies import Policy


class ModelError(ValueError):
    """A file that is not a saved model this fight can use; the message names the file."""


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
    try:
        model = PPO.load(path, device="cpu")
    except Exception as error:  # SB3 raises many kinds (assert, KeyError, BadZipFile, ...)
        raise ModelError(
            f"{path} is not a saved PPO model: {type(error).__name__}: {error}"
        ) from None
    observation_shape = getattr(model.observation_space, "shape", None)
    if observation_shape != (OBSERVATION_SIZE,):
        raise ModelError(
            f"model {path} expects observations of shape {observation_shape}, "
            f"the fight gives ({OBSERVATION_SIZE},)"
        )
    actions = getattr(model.action_space, "n", None)
    if actions != len(Action):
        raise ModelError(f"model {path} has {actions} actions, the fight has {len(Action)}")
    return model


class FrozenPolicy(Policy):
    """An SB3 MLP actor copied into numpy: the same actions as `predict`, far less overhead.

    Self-play runs an opponent on every env step; SB3's `predict` spends most of its time outside
    the network. `deterministic` takes the most likely action; otherwise actions are sampled from
    the policy's distribution with a generator seeded by `reset(seed)`.
    """

    _ACTIVATIONS = {"Tanh": np.tanh, "ReLU": lambda x: np.maximum(x, 0.0)}

    def __init__(self, model: Any, name: str = "frozen", deterministic: bool = True) -> None:
        import torch

        policy = model.policy
        activation = policy.activation_fn.__name__
        if activation not in self._ACTIVATIONS:
            raise ValueError(f"FrozenPolicy supports Tanh and ReLU networks, got {activation}")
        if type(policy.features_extractor).__name__ != "FlattenExtractor":
            raise ValueError("FrozenPolicy supports MlpPolicy (a FlattenExtractor) only")
        self.activation = self._ACTIVATIONS[activation]
        linears = [m for m in policy.mlp_extractor.policy_net if isinstance(m, torch.nn.Linear)]
        linears.append(policy.action_net)
        self.layers = [
            (
                m.weight.detach().cpu().numpy().astype(np.float64).T,
                m.bias.detach().cpu().numpy().astype(np.float64),
            )
            for m in linears
        ]
        self.name = name
        self.deterministic = deterministic
        self.rng = np.random.default_rng()

    def reset(self, seed: int | None = None) -> None:
        if seed is not None:
            self.rng = np.random.default_rng(seed)

    def logits(self, observation: np.ndarray) -> np.ndarray:
        hidden = np.asarray(observation, dtype=np.float64)
        for weight, bias in self.layers[:-1]:
            hidden = self.activation(hidden @ weight + bias)
        weight, bias = self.layers[-1]
        return hidden @ weight + bias

    def act(self, observation: np.ndarray) -> int:
        logits = self.logits(observation)
        if self.deterministic:
            return int(np.argmax(logits))
        odds = np.exp(logits - logits.max())
        return int(self.rng.choice(len(odds), p=odds / odds.sum()))
