"""Run by tests/install/test_wheel.py with the fresh venv's Python, from a folder outside the
checkout: everything a user reaches after `pip install`, with nothing of the checkout in sight."""

from __future__ import annotations

import importlib.util
import sys
import time
from importlib.resources import files
from pathlib import Path

import gymnasium
import numpy as np

import vooga_env
from vooga_env.agents.league import load_league_config
from vooga_env.agents.train_config import load_train_config
from vooga_env.envs.sb3 import FightVecEnv
from vooga_env.game.config import load_config
from vooga_env.kernel import VectorFight

site = Path(sys.argv[1]).resolve()
assert Path(vooga_env.__file__).resolve().is_relative_to(site), vooga_env.__file__
assert importlib.util.find_spec("agents") is None, "a generic top-level 'agents' is installed"

configs = files("vooga_env.configs")
names = sorted(p.name[:-5] for p in configs.iterdir() if p.name.endswith(".toml"))
train_names = sorted(p.name[:-5] for p in configs.joinpath("train").iterdir())
for name in names:
    load_config(name)
for name in train_names:
    if not name.startswith("rllib_"):  # the rllib extra's, checked below when it is there
        load_train_config(name)
for path in configs.joinpath("league").iterdir():
    load_league_config(path.name[:-5])
print("configs", " ".join(names), "| train", " ".join(train_names))

start = time.perf_counter()
env = vooga_env.parallel_env()
env.reset(seed=0)
env.step({"fighter_0": 0, "fighter_1": 0})
print(f"first compiled step {time.perf_counter() - start:.1f} s ({env.backend})")
for name in names:
    for backend in ("engine", "compiled"):
        env = vooga_env.parallel_env(config=name, backend=backend)
        env.reset(seed=1)
        while env.agents:
            env.step({agent: env.action_space(agent).sample() for agent in env.agents})
aec = vooga_env.env()
aec.reset(seed=0)
for agent in aec.agent_iter(40):
    aec.step(None if aec.terminations[agent] or aec.truncations[agent] else 2)
for env_id in vooga_env.GYM_IDS:
    single = gymnasium.make(env_id, opponent="rush")
    single.reset(seed=0)
    single.step(single.action_space.sample())
batch = gymnasium.make_vec(
    "vooga_env/Fight-v0", num_envs=8, vectorization_mode="vector_entry_point"
)
batch.reset(seed=0)
batch.step(batch.action_space.sample())
fights = VectorFight(16)
fights.reset(seed=0)
fights.step(np.zeros((16, 2), dtype=np.int64))
sb3 = FightVecEnv(4, opponent="rush")
sb3.reset()
sb3.step(np.zeros(4, dtype=np.int64))
print("faces ok")

if importlib.util.find_spec("ray") is not None:  # the rllib extra
    from vooga_env.agents.rllib_config import load_rllib_config
    from vooga_env.agents.rllib_env import FightMultiAgentEnv
    from vooga_env.agents.train_rllib import main as train_rllib  # noqa: F401

    for name in train_names:
        if name.startswith("rllib_"):
            load_rllib_config(name)
    multi = FightMultiAgentEnv({"fight": "small", "max_cycles": 20})
    multi.reset(seed=0)
    _, _, _, truncated, _ = multi.step({"fighter_0": 1, "fighter_1": 2})
    assert "__all__" in truncated
    print("rllib ok")
