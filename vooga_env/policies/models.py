"""Trained fighters: saved SB3 models (loaded with a space check), their fast numpy copies, and
MLP fighters exported to .npz files (by any trainer, e.g. `agents.train_rllib`)."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np

from vooga_env.game.actions import Action
from vooga_env.game.facing import FRAMES, TURNED_ACTIONS, face_opponent
from vooga_env.game.observations import OBSERVATION_SIZE
from vooga_env.policies.base import Policy


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


ACTIVATIONS = {"tanh": np.tanh, "relu": lambda x: np.maximum(x, 0.0)}
"""The hidden-layer activations an MLP fighter may use, by lower-case name."""

Layers = list[tuple[np.ndarray, np.ndarray]]


class MLPPolicy(Policy):
    """A fighter whose policy is a plain MLP in numpy: `layers` of (weight (in, out), bias (out,))
    with `activation` between them and the last layer's output the action logits.

    `deterministic` takes the most likely action; otherwise actions are sampled from the
    softmax of the logits with a generator seeded by `reset(seed)`. `frame = "opponent"`: the
    network plays in the opponent-facing frame (`vooga_env.game.facing`).
    """

    def __init__(
        self,
        layers: Layers,
        activation: str,
        name: str = "mlp",
        deterministic: bool = True,
        frame: str = "seat",
    ) -> None:
        if activation not in ACTIVATIONS:
            raise ValueError(
                f"activation {activation!r} is not supported: one of {', '.join(ACTIVATIONS)}"
            )
        if frame not in FRAMES:
            raise ValueError(f"frame {frame!r} is not supported: one of {', '.join(FRAMES)}")
        self.frame = frame
        self.activation_name = activation
        self.activation = ACTIVATIONS[activation]
        self.layers = [(np.asarray(w, np.float64), np.asarray(b, np.float64)) for w, b in layers]
        self.name = name
        self.deterministic = deterministic
        self.rng = np.random.default_rng()

    def reset(self, seed: int | None = None) -> None:
        if seed is not None:
            self.rng = np.random.default_rng(seed)

    def logits(self, observation: np.ndarray) -> np.ndarray:
        """The action logits for one observation (41,) or a batch (n, 41)."""
        hidden = np.atleast_2d(np.asarray(observation, dtype=np.float64))
        if self.frame == "opponent":
            hidden, turned = face_opponent(hidden)
        for weight, bias in self.layers[:-1]:
            hidden = self.activation(hidden @ weight + bias)
        weight, bias = self.layers[-1]
        logits = hidden @ weight + bias
        if self.frame == "opponent":
            logits = np.where(turned[:, None], logits[:, TURNED_ACTIONS], logits)
        return logits[0] if np.ndim(observation) == 1 else logits

    def act(self, observation: np.ndarray) -> int:
        logits = self.logits(observation)
        if self.deterministic:
            return int(np.argmax(logits))
        odds = np.exp(logits - logits.max())
        return int(self.rng.choice(len(odds), p=odds / odds.sum()))

    def act_batch(self, observations: np.ndarray) -> np.ndarray:
        """Actions (n,) for observations (n, 41): the argmax, or a sample drawn by Gumbel-max
        (the same distribution as `act`, one draw per row, not the same numbers)."""
        logits = self.logits(observations)
        if not self.deterministic:
            logits = logits + self.rng.gumbel(size=logits.shape)
        return np.argmax(logits, axis=1).astype(np.int64)


class BatchPolicy:
    """An MLP fighter as a batch opponent (`act(observations (n, 41)) -> actions (n,)`), the
    shape `FightVecEnv(opponent=...)` takes: one network call for the whole batch."""

    def __init__(self, policy: MLPPolicy) -> None:
        self.policy = policy
        self.name = policy.name

    def reset(self, seed: int | None = None) -> None:
        self.policy.reset(seed)

    def act(self, observations: np.ndarray) -> np.ndarray:
        return self.policy.act_batch(observations)

    def __repr__(self) -> str:
        mode = "argmax" if self.policy.deterministic else "sampled"
        return f"BatchPolicy({self.name!r}, {mode})"


class FrozenPolicy(MLPPolicy):
    """An SB3 MLP actor copied into numpy: the same actions as `predict`, far less overhead.

    Self-play runs an opponent on every env step; SB3's `predict` spends most of its time outside
    the network. A `FacingPolicy` model keeps its frame.
    """

    def __init__(self, model: Any, name: str = "frozen", deterministic: bool = True) -> None:
        import torch

        policy = model.policy
        activation = policy.activation_fn.__name__.lower()
        if activation not in ACTIVATIONS:
            raise ValueError(f"FrozenPolicy supports Tanh and ReLU networks, got {activation}")
        if type(policy.features_extractor).__name__ != "FlattenExtractor":
            raise ValueError("FrozenPolicy supports MlpPolicy (a FlattenExtractor) only")
        linears = [m for m in policy.mlp_extractor.policy_net if isinstance(m, torch.nn.Linear)]
        linears.append(policy.action_net)
        layers = [
            (m.weight.detach().cpu().numpy().T, m.bias.detach().cpu().numpy()) for m in linears
        ]
        super().__init__(layers, activation, name, deterministic, getattr(policy, "frame", "seat"))


def frozen_batch(model: Any, name: str, deterministic: bool, seed: int) -> BatchPolicy:
    """A saved SB3 model as a seeded batch player (`FightVecEnv(opponent=...)`, `batch_match`)."""
    player = BatchPolicy(FrozenPolicy(model, name, deterministic))
    player.reset(seed)
    return player


def save_mlp(path: str | Path, layers: Layers, activation: str) -> Path:
    """Write an MLP fighter to a small .npz file (`load_mlp` and `make_policy` read it back)."""
    path = Path(path)
    MLPPolicy(layers, activation)  # refuses an activation that could not be loaded
    arrays: dict[str, np.ndarray] = {"activation": np.array(activation)}
    for index, (weight, bias) in enumerate(layers):
        arrays[f"weight_{index}"] = np.asarray(weight, np.float32)
        arrays[f"bias_{index}"] = np.asarray(bias, np.float32)
    path.parent.mkdir(parents=True, exist_ok=True)
    with path.open("wb") as file:
        np.savez(file, **arrays)
    return path


def load_mlp(path: str | Path, deterministic: bool = True) -> MLPPolicy:
    """An MLP fighter from a .npz file of `save_mlp`, checked against the fight's spaces."""
    path = Path(path)
    if not path.is_file():
        raise FileNotFoundError(f"no exported fighter at {path}")
    try:
        with np.load(path) as data:
            activation = str(data["activation"])
            count = sum(1 for key in data.files if key.startswith("weight_"))
            layers = [(data[f"weight_{i}"], data[f"bias_{i}"]) for i in range(count)]
    except (KeyError, ValueError, OSError) as error:
        raise ValueError(f"{path} is not an exported fighter (.npz of save_mlp): {error}") from None
    if not layers:
        raise ValueError(f"{path} is not an exported fighter: it holds no layers")
    inputs, outputs = layers[0][0].shape[0], layers[-1][0].shape[1]
    if inputs != OBSERVATION_SIZE:
        raise ValueError(
            f"fighter {path} expects observations of size {inputs}, "
            f"the fight gives {OBSERVATION_SIZE}"
        )
    if outputs != len(Action):
        raise ValueError(f"fighter {path} has {outputs} actions, the fight has {len(Action)}")
    return MLPPolicy(layers, activation, name=path.stem, deterministic=deterministic)
