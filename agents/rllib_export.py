"""A trained RLlib module as a fighter: its actor network copied to an .npz (`save_mlp`), which
`make_policy` (and so agents.match, agents.evaluate, the tournament, `FightEnv(opponent=...)`)
loads with no Ray installed."""

from __future__ import annotations

from pathlib import Path
from typing import Any

from vooga_env.policies.models import Layers, save_mlp

ACTIVATIONS = {"Tanh": "tanh", "ReLU": "relu"}


def module_layers(module: Any) -> tuple[Layers, str]:
    """The actor of an RLlib default (PPO) torch module as numpy layers and its activation:
    the (actor) encoder's MLP, then the policy head's. Anything else is refused by name."""
    import torch

    encoder = getattr(module, "encoder", None)
    actor = getattr(encoder, "actor_encoder", None)  # vf_share_layers off: its own encoder
    if actor is None:
        actor = getattr(encoder, "encoder", None)
    head = getattr(module, "pi", None)
    if actor is None or head is None:
        raise ValueError(
            f"cannot export {type(module).__name__}: it is not RLlib's default actor-critic "
            "module (an encoder and a `pi` head)"
        )
    layers: Layers = []
    activations = set()
    for part in (actor, head):
        for child in part.modules():
            if isinstance(child, torch.nn.Linear):
                weight = child.weight.detach().cpu().numpy().T
                layers.append((weight, child.bias.detach().cpu().numpy()))
            elif type(child).__name__ in ACTIVATIONS:
                activations.add(ACTIVATIONS[type(child).__name__])
            elif not list(child.children()):  # a leaf that is neither: a normalization, ...
                raise ValueError(f"cannot export a module with a {type(child).__name__} layer")
    if len(activations) > 1:
        raise ValueError(f"cannot export a module mixing activations {sorted(activations)}")
    return layers, activations.pop() if activations else "tanh"


def export_module(module: Any, path: str | Path) -> Path:
    """Write `module`'s actor to `path` (.npz)."""
    layers, activation = module_layers(module)
    return save_mlp(path, layers, activation)


def export_checkpoint(checkpoint: str | Path, module_id: str, path: str | Path) -> Path:
    """Write module `module_id` of an algorithm checkpoint (`Algorithm.save_to_path`) to `path`.

    A KeyError names an unknown module id and the ids the checkpoint holds.
    """
    from ray.rllib.core.rl_module.rl_module import RLModule

    modules = Path(checkpoint) / "learner_group" / "learner" / "rl_module"
    if not modules.is_dir():
        raise FileNotFoundError(f"no RLlib algorithm checkpoint at {checkpoint}")
    known = sorted(p.name for p in modules.iterdir() if p.is_dir())
    if module_id not in known:
        raise KeyError(f"module {module_id!r} is not in {checkpoint}; it holds {', '.join(known)}")
    return export_module(RLModule.from_checkpoint(modules / module_id), path)
