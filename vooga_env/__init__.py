"""vooga_env: a two-fighter combat environment for RL on the VOOGA physics and collision engine.

- `vooga_env.parallel_env(**kwargs)`: the PettingZoo ParallelEnv; `vooga_env.env(**kwargs)`: AEC.
- `gymnasium.make("vooga_env/Fight-v0", opponent="rush")`: one fighter against a scripted or saved
  opponent (variants: FightWater-v0, FightPlatforms-v0, FightSmall-v0).
- `vooga_env.physics`: the engine alone (no gymnasium or pettingzoo inside).
"""

import gymnasium

from vooga_env.actions import Action
from vooga_env.config import ConfigError, FightConfig, load_config
from vooga_env.gym_env import FightEnv
from vooga_env.parallel import FightParallelEnv, env, parallel_env, raw_env

__version__ = "0.1.0"

GYM_IDS = {
    "vooga_env/Fight-v0": "default",
    "vooga_env/FightWater-v0": "water",
    "vooga_env/FightPlatforms-v0": "platforms",
    "vooga_env/FightSmall-v0": "small",
}
for _id, _config in GYM_IDS.items():
    if _id not in gymnasium.registry:
        gymnasium.register(
            _id, entry_point="vooga_env.gym_env:FightEnv", kwargs={"config": _config}
        )

__all__ = [
    "Action",
    "ConfigError",
    "FightConfig",
    "FightEnv",
    "FightParallelEnv",
    "GYM_IDS",
    "env",
    "load_config",
    "parallel_env",
    "raw_env",
]
