"""vooga_env: a two-fighter combat environment for RL on the VOOGA physics and collision engine.

- `vooga_env.parallel_env(**kwargs)`: the PettingZoo ParallelEnv; `vooga_env.env(**kwargs)`: AEC.
- `gymnasium.make("vooga_env/Fight-v0", opponent="rush")`: one fighter against a scripted or saved
  opponent (variants: FightWater-v0, FightPlatforms-v0, FightSmall-v0); `gymnasium.make_vec(...,
  vectorization_mode="vector_entry_point")` gives the batched engine as a `VectorEnv`.
- `vooga_env.physics`: the engine alone (no gymnasium or pettingzoo inside); `game` the fight's
  rules on it, `kernel` the same rules compiled (`VectorFight`: N fights), `policies` the
  fighters, `envs` the PettingZoo/Gymnasium/SB3 faces, `tools` matches, Elo, replays.

The env names load on first use, so that `import vooga_env.physics` needs neither gymnasium nor
pettingzoo; the Gymnasium ids are registered on `import vooga_env`.
"""

from __future__ import annotations

import importlib
from typing import Any

from vooga_env import moved

__version__ = "0.2.0"

GYM_IDS = {
    "vooga_env/Fight-v0": "default",
    "vooga_env/FightWater-v0": "water",
    "vooga_env/FightPlatforms-v0": "platforms",
    "vooga_env/FightSmall-v0": "small",
}

_LAZY = {
    "Action": "vooga_env.game.actions",
    "ConfigError": "vooga_env.game.config",
    "FightConfig": "vooga_env.game.config",
    "load_config": "vooga_env.game.config",
    "FightParallelEnv": "vooga_env.envs.parallel",
    "env": "vooga_env.envs.parallel",
    "parallel_env": "vooga_env.envs.parallel",
    "raw_env": "vooga_env.envs.parallel",
    "FightEnv": "vooga_env.envs.gym_env",
}


def __getattr__(name: str) -> Any:
    if name in _LAZY:
        value = getattr(importlib.import_module(_LAZY[name]), name)
        globals()[name] = value
        return value
    raise AttributeError(f"module 'vooga_env' has no attribute {name!r}")


def _register() -> None:
    try:
        import gymnasium
    except ImportError:  # only the engine is usable without the RL stack; nothing to register
        return
    for env_id, config in GYM_IDS.items():
        if env_id not in gymnasium.registry:
            gymnasium.register(
                env_id,
                entry_point="vooga_env.envs.gym_env:FightEnv",
                vector_entry_point="vooga_env.envs.gym_vector:FightVectorEnv",
                kwargs={"config": config},
            )


moved.install()
_register()

__all__ = ["GYM_IDS", *_LAZY]
