"""Reference trajectories of the single env, for the speed work's "same results" tests.

`SCENARIOS` are fixed seeds, configs and fighters (scripted policies with some random actions,
so that hits, blocks, ring-outs, KOs, truncations and auto-resets all happen). `record` plays one
with the single ParallelEnv and returns every step as arrays; `replay` plays recorded actions
again. The .npz files in `data/` were written by the code as it was before the speed work:

    python -m tests.kernel.reference            # rewrite data/*.npz (only when the rules change)
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np

import vooga_env
import vooga_env.game.outcome
from vooga_env.policies import make_policy

DATA = Path(__file__).resolve().parent / "data"
STEPS = 2000
# the recorded files' layout: infos in this order, winners in this code (not Outcome's: the
# data was recorded before it, and is never re-recorded)
INFO_KEYS = (
    "health",
    "stocks",
    "hits_landed",
    "hits_blocked",
    "damage_dealt",
    "damage_taken",
    "rung_out",
    "knocked_out",
)
assert INFO_KEYS == vooga_env.game.outcome.INFO_KEYS, (
    "the env's infos no longer match the recordings"
)
WINNERS = {None: -1, "fighter_0": 0, "fighter_1": 1, "draw": 2}


@dataclass(frozen=True)
class Scenario:
    """A config with overrides, an env seed, each seat's scripted fighter and random-action rate."""

    name: str
    config: str
    seed: int
    fighters: tuple[str, str]
    explore: float
    overrides: tuple[tuple[str, object], ...] = ()

    def make_env(self) -> vooga_env.FightParallelEnv:
        return vooga_env.parallel_env(config=self.config, backend="engine", **dict(self.overrides))


SCENARIOS = (
    Scenario("brawl", "default", 11, ("rush", "turtle"), 0.2, (("max_cycles", 300),)),
    Scenario("edges", "small", 5, ("edge_guard", "rush"), 0.3, (("max_cycles", 400),)),
    Scenario(
        "platforms",
        "platforms",
        3,
        ("zoner", "random"),
        0.1,
        (("max_cycles", 250), ("stocks", 2), ("arena", {"spawn_jitter": 12.0})),
    ),
    Scenario("water", "water", 8, ("edge_guard", "turtle"), 0.25, (("max_cycles", 500),)),
    Scenario(
        "knockouts",
        "default",
        21,
        ("rush", "zoner"),
        0.15,
        (("max_cycles", 400), ("stocks", 2), ("fighter", {"health": 12.0})),
    ),
)


def _actions_from_policies(scenario: Scenario):
    policies = [
        make_policy(name, scenario.seed + seat) for seat, name in enumerate(scenario.fighters)
    ]
    rng = np.random.default_rng(scenario.seed + 100)

    def choose(observations: dict[str, np.ndarray]) -> tuple[int, int]:
        chosen = []
        for policy, agent in zip(policies, ("fighter_0", "fighter_1")):
            action = policy.act(observations[agent])
            if rng.random() < scenario.explore:
                action = int(rng.integers(10))
            chosen.append(int(action))
        return chosen[0], chosen[1]

    return choose


def record(scenario: Scenario, steps: int = STEPS, actions: np.ndarray | None = None) -> dict:
    """Play `scenario` (or the given `actions`, shape (steps, 2)) for `steps` steps, auto-resetting.

    Returns arrays: actions (T, 2), obs (T, 2, 41) returned by each step, rewards (T, 2),
    terminated and truncated (T,), state (T, 2, 4) x, y, vx, vy of each fighter after the step,
    info (T, 2, len(INFO_KEYS)), winner (T,) (-1 while the episode goes on), and the
    observations of every reset: reset_obs (R, 2, 41) at reset_steps (R,) (-1: the first reset).
    """
    env = scenario.make_env()
    agents = env.possible_agents
    choose = None if actions is not None else _actions_from_policies(scenario)
    observations, _ = env.reset(seed=scenario.seed)
    trace = {key: [] for key in ("actions", "obs", "rewards", "terminated", "truncated")}
    trace.update(state=[], info=[], winner=[], reset_obs=[_stack(observations)], reset_steps=[-1])
    for step in range(steps):
        chosen = choose(observations) if actions is None else tuple(int(a) for a in actions[step])
        observations, rewards, terminations, truncations, infos = env.step(
            dict(zip(agents, chosen))
        )
        trace["actions"].append(chosen)
        trace["obs"].append(_stack(observations))
        trace["rewards"].append([rewards[agent] for agent in agents])
        trace["terminated"].append(terminations[agents[0]])
        trace["truncated"].append(truncations[agents[0]])
        trace["state"].append([[f.x, f.y, f.vx, f.vy] for f in env.fight.fighters])
        trace["info"].append([[float(infos[agent][key]) for key in INFO_KEYS] for agent in agents])
        trace["winner"].append(WINNERS[infos[agents[0]].get("winner")])
        if not env.agents:
            observations, _ = env.reset()
            trace["reset_obs"].append(_stack(observations))
            trace["reset_steps"].append(step)
    dtypes = {
        "actions": np.int8,
        "obs": np.float32,
        "rewards": np.float64,
        "terminated": bool,
        "truncated": bool,
        "state": np.float64,
        "info": np.float64,
        "winner": np.int8,
        "reset_obs": np.float32,
        "reset_steps": np.int64,
    }
    return {key: np.asarray(value, dtype=dtypes[key]) for key, value in trace.items()}


def _stack(observations: dict[str, np.ndarray]) -> np.ndarray:
    return np.stack([observations["fighter_0"], observations["fighter_1"]])


def path(scenario: Scenario) -> Path:
    return DATA / f"{scenario.name}.npz"


def load(scenario: Scenario) -> dict:
    with np.load(path(scenario)) as data:
        return {key: data[key] for key in data.files}


def main() -> None:
    DATA.mkdir(exist_ok=True)
    for scenario in SCENARIOS:
        trace = record(scenario)
        np.savez_compressed(path(scenario), **trace)
        events = summary(trace)
        print(f"{scenario.name}: {path(scenario).stat().st_size} bytes, {events}")


def summary(trace: dict) -> dict[str, int]:
    """How often each event happened in a trace (the tests assert they all did)."""
    info = trace["info"]
    return {
        "hits": int(info[:, :, INFO_KEYS.index("hits_landed")].sum()),
        "blocks": int(info[:, :, INFO_KEYS.index("hits_blocked")].sum()),
        "ring_outs": int(info[:, :, INFO_KEYS.index("rung_out")].sum()),
        "knock_outs": int(info[:, :, INFO_KEYS.index("knocked_out")].sum()),
        "terminations": int(trace["terminated"].sum()),
        "truncations": int(trace["truncated"].sum()),
        "resets": len(trace["reset_steps"]) - 1,
    }


if __name__ == "__main__":
    main()
