"""RLlib scaling on this machine: env steps/s and learner steps/s for 0, 1 and 2 env runners,
against SB3 PPO on the same budget (the same env steps, batch, epochs and network).

Each RLlib row trains `--iterations` iterations of `configs/train/rllib_selfplay.toml` (scaled
down: `--batch` env steps an iteration, `--envs` fights per runner) and reports, over all
but the first iteration: env steps/s = steps / sampling time, learner steps/s = steps / learner
update time (both from RLlib's own timers), and the end-to-end rate; plus the env's share of a
runner's step time (RLlib's env-step, module-inference and connector timers). SB3 runs PPO on
`vooga_env.envs.sb3.FightVecEnv` (the batched engine) against a scripted fighter, with its
rollout and training phases timed apart.

    nice -n 10 python -m bench.rllib_scaling                 # ~1 minute on 2 cores (load 4-5)
    nice -n 10 python -m bench.rllib_scaling --runners 0 2   # some rows only
"""

from __future__ import annotations

import argparse
import json
import time
from pathlib import Path
from typing import Any

EMA = 0.01
"""RLlib's timers are exponential averages with this coefficient (`EmaStats`' default)."""


def phase_seconds(timers: list[dict[str, float]], key: str) -> list[float]:
    """Each iteration's own seconds in RLlib timer `key`, undone from its running average
    (x_t = (e_t - (1 - a) e_{t-1}) / a; the first value is the first iteration's own)."""
    values = [timers[0][key]]
    for before, after in zip(timers, timers[1:]):
        values.append((after[key] - (1.0 - EMA) * before[key]) / EMA)
    return values


def rllib_row(runners: int, envs: int, batch: int, iterations: int) -> dict:
    from agents.rllib_config import load_rllib_config
    from agents.rllib_league import League
    from agents.train_rllib import algorithm_config

    config = load_rllib_config(
        "rllib_selfplay",
        env_runners=runners,
        envs_per_runner=envs,
        ppo={"train_batch_size": batch, "minibatch_size": min(512, batch)},
    )
    start = time.perf_counter()
    algo = algorithm_config(config, League(config.league)).build_algo()
    build = time.perf_counter() - start
    try:
        results = [algo.train() for _ in range(iterations)]
    finally:
        algo.stop()
    timers = [dict(result["timers"]) for result in results]
    sample = phase_seconds(timers, "env_runner_sampling_timer")[1:]  # the first: warm-up
    learn = phase_seconds(timers, "learner_update_timer")[1:]
    total = [result["time_this_iter_s"] for result in results][1:]
    steps = [result["env_runners"]["num_env_steps_sampled"] for result in results][1:]
    runner = results[-1]["env_runners"]
    return {
        "env_runners": runners,
        "envs_per_runner": envs,
        "env_steps_per_s": round(sum(steps) / sum(sample)),
        "learner_steps_per_s": round(sum(steps) / sum(learn)),
        "end_to_end_steps_per_s": round(sum(steps) / sum(total)),
        "unaccounted_s": round(sum(total) - sum(sample) - sum(learn), 3),  # the check
        "env_step_ms": round(1e3 * runner["env_step_timer"], 3),
        "inference_ms": round(1e3 * runner["rlmodule_inference_timer"], 3),
        "connectors_ms": round(1e3 * runner["connector_pipeline_timer"], 3),
        "build_s": round(build, 1),
    }


def sb3_row(envs: int, batch: int, iterations: int) -> dict:
    import torch
    from stable_baselines3 import PPO
    from stable_baselines3.common.callbacks import BaseCallback

    from agents.common import quiet_logger
    from vooga_env.envs.sb3 import FightVecEnv

    class Phases(BaseCallback):
        """Times the rollouts; the rest of `learn` is training."""

        def __init__(self) -> None:
            super().__init__()
            self.rollout_s = 0.0

        def _on_rollout_start(self) -> None:
            self._start = time.perf_counter()

        def _on_rollout_end(self) -> None:
            self.rollout_s += time.perf_counter() - self._start

        def _on_step(self) -> bool:
            return True

    torch.set_num_threads(1)
    env = FightVecEnv(envs, opponent="rush")
    model = PPO(
        "MlpPolicy",
        env,
        n_steps=batch // envs,
        batch_size=min(512, batch),
        n_epochs=4,
        policy_kwargs={"net_arch": [64, 64]},
        seed=0,
        device="cpu",
        verbose=0,
    )
    quiet_logger(model)
    model.learn(batch)  # warm-up, as the RLlib rows drop their first iteration
    phases = Phases()
    steps = batch * (iterations - 1)
    start = time.perf_counter()
    model.learn(steps, callback=phases, reset_num_timesteps=False)
    wall = time.perf_counter() - start
    return {
        "sb3_envs": envs,
        "env_steps_per_s": round(steps / phases.rollout_s),
        "learner_steps_per_s": round(steps / (wall - phases.rollout_s)),
        "end_to_end_steps_per_s": round(steps / wall),
    }


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runners", type=int, nargs="+", default=[0, 1, 2])
    parser.add_argument("--envs", type=int, default=8, help="fights per env runner")
    parser.add_argument("--batch", type=int, default=2048, help="env steps per iteration")
    parser.add_argument("--iterations", type=int, default=4)
    parser.add_argument("--json", type=Path, help="also write the rows here")
    args = parser.parse_args(argv)
    import ray
    import torch

    torch.set_num_threads(1)  # as agents.train and agents.train_rllib do
    # SB3 first: measured after a Ray session in the same process it ran 15x slower here.
    rows: list[dict[str, Any]] = [sb3_row(args.envs, args.batch, args.iterations)]
    print(json.dumps(rows[-1]), flush=True)
    ray.init(num_cpus=max(2, *args.runners), include_dashboard=False, logging_level="ERROR")
    try:
        for runners in args.runners:
            rows.append(rllib_row(runners, args.envs, args.batch, args.iterations))
            print(json.dumps(rows[-1]), flush=True)
    finally:
        ray.shutdown()
    if args.json:
        args.json.write_text(json.dumps(rows, indent=2) + "\n")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
