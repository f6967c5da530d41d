"""`make_policy`: a Policy from whatever names one (a scripted name, a model file, a callable)."""

from __future__ import annotations

import copy
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np

from vooga_env.game.actions import Action, action_index
from vooga_env.policies.base import Policy
from vooga_env.policies.models import FrozenPolicy, load_mlp, load_model
from vooga_env.policies.scripted import SCRIPTED


def _one_action(name: str, action: Any) -> int:
    """A policy's action as an int in 0..9 (a one-element array counts), or an error naming it."""
    if isinstance(action, np.ndarray):
        if action.size != 1:
            raise ValueError(
                f"the action of policy {name!r} must be one int in 0..{len(Action) - 1}, "
                f"got {action!r}"
            )
        action = action.reshape(())
    return action_index(f"the action of policy {name!r}", action)


class CallablePolicy(Policy):
    """Wraps any `obs -> action` callable."""

    def __init__(self, function: Callable[[np.ndarray], Any]) -> None:
        self.function = function
        self.name = getattr(function, "__name__", "callable")

    def act(self, observation: np.ndarray) -> int:
        return _one_action(self.name, self.function(observation))


class PredictPolicy(Policy):
    """Wraps an object with SB3's `predict` (a trained model), deterministic by default."""

    def __init__(self, model: Any, name: str = "model", deterministic: bool = True) -> None:
        self.model = model
        self.name = name
        self.deterministic = deterministic

    def act(self, observation: np.ndarray) -> int:
        action, _ = self.model.predict(observation, deterministic=self.deterministic)
        return _one_action(self.name, np.asarray(action))

    def predict(self, observation, state=None, episode_start=None, deterministic=True):
        return self.model.predict(observation, state, episode_start, deterministic)


def make_policy(spec: str | Path | Policy | Callable | Any, seed: int | None = None) -> Policy:
    """A Policy from a scripted name, a saved model (.zip), an exported MLP fighter (.npz), a
    Policy, a predict-er or a callable.

    A Policy given with a seed comes back as a copy reseeded with it (the original may be shared,
    say by several envs, and each must draw its own numbers to be repeatable).
    """
    if seed is not None and (
        isinstance(seed, bool) or not isinstance(seed, (int, np.integer)) or seed < 0
    ):
        raise ValueError(f"seed must be a non-negative int or None, got {seed!r}")
    if isinstance(spec, Policy):
        if seed is None:
            return spec
        policy = copy.copy(spec)
        policy.reset(seed)
        return policy
    if isinstance(spec, (str, Path)):
        if str(spec) in SCRIPTED:
            return SCRIPTED[str(spec)](seed)
        path = Path(spec)
        if path.suffix == ".npz":
            return load_mlp(path)
        if path.suffix == ".zip" or path.with_suffix(".zip").is_file():
            return FrozenPolicy(load_model(path), name=path.stem)
        raise ValueError(
            f"unknown policy {str(spec)!r}: use one of {', '.join(SCRIPTED)}, "
            "a saved model (.zip) or an exported fighter (.npz)"
        )
    if hasattr(spec, "predict"):
        if not callable(spec.predict):
            raise TypeError(f"a policy's predict must be callable, got {spec.predict!r}")
        return PredictPolicy(spec, name=type(spec).__name__)
    if callable(spec):
        return CallablePolicy(spec)
    raise TypeError(
        f"a policy must be a name, a model path, a callable or have predict(), got {spec!r}"
    )
