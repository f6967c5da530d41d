"""The module paths of vooga_env 0.1, kept working for one release with a DeprecationWarning.

0.2 put the modules on floors (physics, game, kernel, policies, envs, tools: docs/architecture.md).
An import of an old path (`vooga_env.vector.sb3`, `vooga_env.config`, ...) gets the module at its
new path, the same object, so classes pickled under the old names (saved models, replays) load too.
"""

from __future__ import annotations

import importlib
import importlib.abc
import importlib.machinery
import sys
import warnings
from types import ModuleType

MOVED = {
    "vooga_env.actions": "vooga_env.game.actions",
    "vooga_env.config": "vooga_env.game.config",
    "vooga_env.fight": "vooga_env.game.fight",
    "vooga_env.hits": "vooga_env.game.hits",
    "vooga_env.observations": "vooga_env.game.observations",
    "vooga_env.rewards": "vooga_env.game.rewards",
    "vooga_env.outcome": "vooga_env.game.outcome",
    "vooga_env.formulas": "vooga_env.game.formulas",
    "vooga_env.simulation": "vooga_env.game.simulation",
    "vooga_env.vector.layout": "vooga_env.kernel.layout",
    "vooga_env.vector.state": "vooga_env.kernel.state",
    "vooga_env.vector.params": "vooga_env.kernel.params",
    "vooga_env.vector.kernel_parts": "vooga_env.kernel.parts",
    "vooga_env.vector.stages": "vooga_env.kernel.stages",
    "vooga_env.vector.kernel_observe": "vooga_env.kernel.observe",
    "vooga_env.vector.kernel_step": "vooga_env.kernel.step",
    "vooga_env.vector.kernel": "vooga_env.kernel.compiled",
    "vooga_env.vector.rng": "vooga_env.kernel.rng",
    "vooga_env.vector.cache": "vooga_env.kernel.cache",
    "vooga_env.vector.engine": "vooga_env.kernel.vector_fight",
    "vooga_env.vector.single": "vooga_env.kernel.single",
    "vooga_env.vector.opponents": "vooga_env.policies.batched",
    "vooga_env.vector.matches": "vooga_env.tools.batch_match",
    "vooga_env.vector.sb3": "vooga_env.envs.sb3",
    "vooga_env.vector": "vooga_env.kernel",
    "vooga_env.models": "vooga_env.policies.models",
    "vooga_env.parallel": "vooga_env.envs.parallel",
    "vooga_env.aec": "vooga_env.envs.aec",
    "vooga_env.gym_env": "vooga_env.envs.gym_env",
    "vooga_env.gym_vector": "vooga_env.envs.gym_vector",
    "vooga_env.spectator": "vooga_env.envs.spectator",
    "vooga_env.render": "vooga_env.envs.render",
    "vooga_env.match": "vooga_env.tools.match",
    "vooga_env.elo": "vooga_env.tools.elo",
    "vooga_env.replay": "vooga_env.tools.replay",
    "vooga_env.replay_format": "vooga_env.tools.replay_format",
    "vooga_env.recording": "vooga_env.tools.recording",
    "vooga_env.demo": "vooga_env.tools.demo",
    "vooga_env.physics_demo": "vooga_env.tools.physics_demo",
    "vooga_env.files": "vooga_env.tools.files",
    "vooga_env.style": "vooga_env.tools.style",
}


class _Alias(importlib.abc.Loader):
    """Loads an old path as the module at its new path."""

    def __init__(self, new: str) -> None:
        self.new = new

    def create_module(self, spec: importlib.machinery.ModuleSpec) -> ModuleType:
        module = importlib.import_module(self.new)
        self.spec = module.__spec__
        return module

    def exec_module(self, module: ModuleType) -> None:
        """Nothing to run, the new module is imported; only its own spec goes back, which the
        import system replaced by the old path's."""
        module.__spec__ = self.spec


class MovedModuleFinder(importlib.abc.MetaPathFinder):
    """Finds the old paths in `MOVED`, warns, and hands back the new modules."""

    def find_spec(self, name, path=None, target=None):  # noqa: ARG002 (the finder protocol)
        new = MOVED.get(name)
        if new is None:
            return None
        warnings.warn(
            f"{name} moved to {new} in vooga_env 0.2; the old path goes in 0.3",
            DeprecationWarning,
            stacklevel=2,
        )
        return importlib.machinery.ModuleSpec(name, _Alias(new))


def install() -> None:
    """Put the finder first on `sys.meta_path`, once."""
    if not any(isinstance(finder, MovedModuleFinder) for finder in sys.meta_path):
        sys.meta_path.insert(0, MovedModuleFinder())
