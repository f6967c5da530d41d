"""The fight as an RLlib MultiAgentEnv, and the scripted fighters as non-learning RLModules.

RLlib's new API stack steps `MultiAgentEnv`s (`ray.rllib.env.multi_agent_env`); this is the
PettingZoo env (`vooga_env.envs.parallel`) with RLlib's `"__all__"` done flags, no other change,
so an RLlib-trained fighter sees exactly the observations an SB3 one does.
"""

from __future__ import annotations

from typing import Any

import numpy as np
from ray.rllib.core.columns import Columns
from ray.rllib.core.rl_module.rl_module import RLModule
from ray.rllib.env.multi_agent_env import MultiAgentEnv

from vooga_env.envs.parallel import AGENTS, FightParallelEnv
from vooga_env.policies import SCRIPTED


def fight_seed(run_seed: int, worker_index: int, seed: int) -> int:
    """A stream of its own for each env runner and vector index: RLlib resets env i of runner
    w with `seed = run_seed + w + i`, so runner 1's env 1 and runner 2's env 0 would share one;
    (run_seed, w, seed) tells every (w, i) apart."""
    entropy = [run_seed, worker_index, seed]
    return int(np.random.SeedSequence(entropy).generate_state(1, np.uint64)[0])


class FightMultiAgentEnv(MultiAgentEnv):
    """Two fighters, `fighter_0` and `fighter_1`; `env_config` holds `fight` (a config name or
    path), the run's `seed` (optional) and any override `FightParallelEnv` takes
    (`max_cycles`, ...)."""

    def __init__(self, env_config: dict[str, Any] | None = None) -> None:
        super().__init__()
        options = dict(env_config or {})
        self.run_seed: int | None = options.pop("seed", None)
        self.worker_index = int(getattr(env_config, "worker_index", 0) or 0)  # RLlib's EnvContext
        self.fight = FightParallelEnv(options.pop("fight", "default"), **options)
        self.possible_agents = list(AGENTS)
        self.agents = list(AGENTS)
        self.observation_spaces = {a: self.fight.observation_space(a) for a in AGENTS}
        self.action_spaces = {a: self.fight.action_space(a) for a in AGENTS}

    def reset(self, *, seed: int | None = None, options: dict | None = None) -> tuple[dict, dict]:
        self.agents = list(AGENTS)
        if seed is not None and self.run_seed is not None:
            seed = fight_seed(self.run_seed, self.worker_index, seed)
        return self.fight.reset(seed=seed, options=options)

    def step(self, action_dict: dict[str, Any]) -> tuple[dict, dict, dict, dict, dict]:
        actions = {agent: int(action) for agent, action in action_dict.items()}
        observations, rewards, terminated, truncated, infos = self.fight.step(actions)
        terminated["__all__"] = terminated[AGENTS[0]]
        truncated["__all__"] = truncated[AGENTS[0]]
        if terminated["__all__"] or truncated["__all__"]:
            self.agents = []
        return observations, rewards, terminated, truncated, infos


class ScriptedModule(RLModule):
    """A shipped scripted fighter (`model_config={"fighter": NAME, "seed": N}`) in RLlib's shape:
    a pool member that acts but never learns (it has no parameters)."""

    def setup(self) -> None:
        name = self.model_config.get("fighter")
        if name not in SCRIPTED:
            raise KeyError(f"fighter = {name!r} is not a scripted fighter: {', '.join(SCRIPTED)}")
        self.fighter = SCRIPTED[name](self.model_config.get("seed"))

    def _forward(self, batch: dict[str, Any], **kwargs: Any) -> dict[str, Any]:
        observations = np.asarray(batch[Columns.OBS], dtype=np.float64)
        actions = np.array([self.fighter.act(row) for row in observations], dtype=np.int64)
        return {Columns.ACTIONS: actions}

    def _forward_train(self, batch: dict[str, Any], **kwargs: Any) -> dict[str, Any]:
        raise NotImplementedError(f"the scripted fighter {self.fighter.name!r} does not learn")

    def compile(self, *args: Any, **kwargs: Any) -> None:
        """Nothing to compile (RLlib calls this on torch modules)."""
