"""Speed of the env against Gymnasium's CartPole, measured side by side in one run.

1. Single env steps/s: the PettingZoo ParallelEnv (both fighters acting at random; its default
   backend, and the physics engine's), the AEC env (one step = a full cycle, both fighters) and
   the single-agent Gymnasium env, each against `gymnasium.make("CartPole-v1").step`.
2. The batched engine (`vooga_env.kernel.VectorFight`) at N fights, env-steps/s (one env step of
   one fight counts once), against `gymnasium.make_vec("CartPole-v1", num_envs=N,
   vectorization_mode="vector_entry_point")`.
3. PPO `learn()` steps/s through `vooga_env.envs.sb3.FightVecEnv` (self-play, 2 slots per fight;
   and one learner against a scripted fighter) against PPO on CartPole (SB3's DummyVecEnv) with
   the same n_envs, n_steps and network (torch on one thread for both).
4. Pixel observations (`obs_type="pixels"`, 84x84 grayscale) against the vector ones, on the
   single env and on the batch at N = 256 and 1024, both fighters' images and one a fight
   (`pixel_seats`: what the one-learner faces draw): the cost of drawing what a fighter sees.
5. Memory: the bytes of a 4096-fight batch's state arrays, and this process's peak RSS.

Every figure is the median of several timed rounds, ours and the reference's interleaved so that
a busy machine slows both alike; a ratio is the median of the rounds' ours / reference.

    python -m bench.speed                  # the full run (a couple of minutes)
    python -m bench.speed --quick          # a few rounds each, for CI (seconds)
    python -m bench.speed --json out.json  # also write everything as JSON
"""

from __future__ import annotations

import argparse
import importlib
import json
import os
import platform
import resource
import statistics
import sys
import time
from collections.abc import Callable, Sequence
from pathlib import Path

import gymnasium
import numpy as np

import vooga_env
from vooga_env.kernel import VectorFight

SIZES = (1, 16, 256, 1024, 4096)


def rate(run: Callable[[int], int], seconds: float) -> float:
    """Units per second of `run(k)` (which does k units of work and returns the count)."""
    count, start, elapsed = 0, time.perf_counter(), 0.0
    while elapsed < seconds:
        count += run(64)
        elapsed = time.perf_counter() - start
    return count / elapsed


def interleaved(
    ours: Callable[[], float], reference: Callable[[], float], rounds: int
) -> tuple[float, float, float]:
    """Medians of `rounds` measurements of each, alternating: (ours, reference, ratio)."""
    pairs = [(ours(), reference()) for _ in range(rounds)]
    return (
        statistics.median(a for a, _ in pairs),
        statistics.median(b for _, b in pairs),
        statistics.median(a / b for a, b in pairs),
    )


def side_by_side(
    ours: Callable[[int], int], reference: Callable[[int], int], seconds: float, rounds: int
) -> tuple[float, float, float]:
    """Median rates of `ours` and `reference` over interleaved rounds, and their median ratio."""
    return interleaved(lambda: rate(ours, seconds), lambda: rate(reference, seconds), rounds)


def gymnasium_steps(env: gymnasium.Env) -> Callable[[int], int]:
    """Random-action steps of a Gymnasium env, resetting at episode ends.

    The actions are drawn beforehand, as for the ParallelEnv, so no side pays for sampling.
    """
    env.reset(seed=0)
    actions = np.random.default_rng(0).integers(env.action_space.n, size=4096).tolist()
    position = [0]

    def run(k: int) -> int:
        for _ in range(k):
            _, _, terminated, truncated, _ = env.step(actions[position[0] % 4096])
            position[0] += 1
            if terminated or truncated:
                env.reset()
        return k

    return run


def cartpole_steps() -> Callable[[int], int]:
    return gymnasium_steps(gymnasium.make("CartPole-v1"))


def parallel_steps(backend: str = "auto", obs_type: str = "vector") -> Callable[[int], int]:
    env = vooga_env.parallel_env(backend=backend, obs_type=obs_type)
    env.reset(seed=0)
    actions = np.random.default_rng(0).integers(10, size=(4096, 2)).tolist()
    position = [0]

    def run(k: int) -> int:
        for _ in range(k):
            if not env.agents:
                env.reset()
            first, second = actions[position[0] % 4096]
            position[0] += 1
            env.step({"fighter_0": first, "fighter_1": second})
        return k

    return run


def aec_cycles() -> Callable[[int], int]:
    env = vooga_env.env()
    env.reset(seed=0)
    rng = np.random.default_rng(0)

    def run(k: int) -> int:
        for _ in range(k):
            for _ in range(2):  # one cycle: both fighters act
                _, _, terminated, truncated, _ = env.last()
                if terminated or truncated:
                    env.step(None)
                    if not env.agents:
                        env.reset()
                else:
                    env.step(int(rng.integers(10)))
        return k

    return run


def gym_steps() -> Callable[[int], int]:
    return gymnasium_steps(gymnasium.make("vooga_env/Fight-v0", opponent="random"))


def batched_steps(
    size: int, threads: int, obs_type: str = "vector", pixel_seats: str | None = None
) -> Callable[[int], int]:
    fights = VectorFight(size, threads=threads, obs_type=obs_type, pixel_seats=pixel_seats)
    fights.reset(seed=0)
    actions = np.random.default_rng(0).integers(10, size=(16, size, 2))
    fights.step(actions[0])  # compiles (or loads) the numba kernel before any timing

    def run(k: int) -> int:
        for j in range(k // 16):
            fights.step(actions[j % 16])
        return (k // 16) * size

    return run


def pixel_rows(sizes: Sequence[int], seconds: float, rounds: int) -> list[dict]:
    """Pixel observations against the vector ones on the same face, interleaved: the single env
    (both backends) and the batch at N = 256 and 1024 (of `sizes`; else its largest)."""
    rows = []
    for backend in ("compiled", "engine"):
        measured = side_by_side(
            parallel_steps(backend, "pixels"), parallel_steps(backend), seconds, rounds
        )
        rows.append(row(f"ParallelEnv.step, backend={backend!r}", *measured, n=1))
    for size in [s for s in sizes if s in (256, 1024)] or [max(sizes)]:
        for seats, label in ((None, "both seats"), ("alternate", "one seat a fight")):
            measured = side_by_side(
                batched_steps(size, 1, "pixels", seats), batched_steps(size, 1), seconds, rounds
            )
            rows.append(row(f"VectorFight N={size} (1 thread, {label})", *measured, n=size))
    return rows


def cartpole_vector_steps(size: int) -> Callable[[int], int]:
    envs = gymnasium.make_vec("CartPole-v1", num_envs=size, vectorization_mode="vector_entry_point")
    envs.reset(seed=0)
    actions = np.random.default_rng(0).integers(2, size=(16, size))

    def run(k: int) -> int:
        for j in range(k // 16):
            envs.step(actions[j % 16])
        return (k // 16) * size

    return run


def ppo_rate(make_env: Callable[[], object], n_steps: int, iterations: int) -> float:
    """Timesteps per second of `PPO.learn` (default hyperparameters but n_steps)."""
    from stable_baselines3 import PPO

    from agents.common import quiet_logger

    env = make_env()
    model = PPO("MlpPolicy", env, n_steps=n_steps, seed=0, device="cpu", verbose=0)
    quiet_logger(model)
    total = iterations * n_steps * env.num_envs
    start = time.perf_counter()
    model.learn(total_timesteps=total)
    return model.num_timesteps / (time.perf_counter() - start)


def ppo_rows(n_envs: int, n_steps: int, iterations: int, rounds: int) -> list[dict]:
    import torch
    from stable_baselines3.common.env_util import make_vec_env

    from vooga_env.envs.sb3 import FightVecEnv

    threads = torch.get_num_threads()
    torch.set_num_threads(1)  # both alike; more threads only fight over a busy machine's cores
    try:
        setups = [
            (f"PPO self-play ({n_envs // 2} fights)", lambda: FightVecEnv(n_envs // 2)),
            (f"PPO vs rush ({n_envs} fights)", lambda: FightVecEnv(n_envs, opponent="rush")),
        ]
        rows = []
        for name, make in setups:
            measured = interleaved(
                lambda make=make: ppo_rate(make, n_steps, iterations),
                lambda: ppo_rate(
                    lambda: make_vec_env("CartPole-v1", n_envs=n_envs), n_steps, iterations
                ),
                rounds,
            )
            rows.append(row(name, *measured, n_envs=n_envs, n_steps=n_steps))
        return rows
    finally:
        torch.set_num_threads(threads)


def row(name: str, ours: float, reference: float, ratio: float, **extra: object) -> dict:
    return {"name": name, "ours": ours, "reference": reference, "ratio": ratio, **extra}


def peak_rss_bytes() -> int:
    usage = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
    return usage if sys.platform == "darwin" else usage * 1024


def machine() -> dict:
    return {
        "python": platform.python_version(),
        "platform": platform.platform(),
        "processor": platform.processor() or platform.machine(),
        "cpus": os.cpu_count(),
        **{name: _version(name) for name in ("numpy", "gymnasium", "stable_baselines3", "torch")},
        "numba": _version("numba"),
    }


def _version(module: str) -> str | None:
    """The installed version of `module`, None when it is not installed."""
    try:
        return importlib.import_module(module).__version__
    except ImportError:
        return None


def print_table(title: str, rows: Sequence[dict], unit: str, reference: str) -> None:
    print(f"\n{title}")
    print(f"{'':40s} {'ours ' + unit:>16s} {reference:>22s} {'ratio':>7s}")
    for r in rows:
        print(f"{r['name']:40s} {r['ours']:16,.0f} {r['reference']:22,.0f} {r['ratio']:7.3f}")


def parse_sizes(text: str) -> tuple[int, ...]:
    try:
        sizes = tuple(int(part) for part in text.split(","))
    except ValueError:
        raise argparse.ArgumentTypeError(f"--sizes must be integers, got {text!r}") from None
    if not sizes or min(sizes) < 1:
        raise argparse.ArgumentTypeError(f"--sizes must be >= 1, got {text!r}")
    return sizes


def main(argv: Sequence[str] | None = None) -> dict:
    parser = argparse.ArgumentParser(
        prog="python -m bench.speed", description=__doc__.split("\n")[0]
    )
    parser.add_argument("--quick", action="store_true", help="a few short rounds, for CI")
    parser.add_argument("--json", type=Path, help="also write the results as JSON here")
    parser.add_argument("--sizes", type=parse_sizes, default=SIZES, help="batch sizes, e.g. 1,16")
    parser.add_argument("--no-ppo", action="store_true", help="skip the PPO comparison")
    args = parser.parse_args(argv)
    seconds, rounds = (0.05, 1) if args.quick else (1.0, 5)

    single = []
    default_backend = vooga_env.parallel_env().backend
    for name, ours in (
        (f"ParallelEnv.step (default: {default_backend})", parallel_steps),
        ("AEC env, one cycle (both fighters)", aec_cycles),
        ("Gymnasium env (vs random)", gym_steps),
        ("ParallelEnv.step, backend='engine'", lambda: parallel_steps("engine")),
    ):
        single.append(row(name, *side_by_side(ours(), cartpole_steps(), seconds, rounds)))
    print_table("single env, steps/s", single, "steps/s", "CartPole-v1 steps/s")

    batched = []
    for size in args.sizes:
        # one thread (the default) everywhere; two as well where a batch is worth cutting
        for threads in (1, 2) if size >= 256 else (1,):
            measured = side_by_side(
                batched_steps(size, threads), cartpole_vector_steps(size), seconds, rounds
            )
            label = f"{threads} thread{'s' if threads > 1 else ''}"
            batched.append(
                row(f"VectorFight N={size} ({label})", *measured, n=size, threads=threads)
            )
    print_table("batched, env-steps/s", batched, "env-steps/s", "CartPole make_vec")

    pixels = pixel_rows(args.sizes, seconds, rounds)
    print_table("pixel observations (84x84 gray), steps/s", pixels, "pixels", "vector obs")

    ppo: list[dict] = []
    if not args.no_ppo and _version("stable_baselines3") is None:
        print("\nPPO: skipped, stable-baselines3 is not installed (the `train` extra)")
    elif not args.no_ppo:
        n_envs, n_steps = 16, 32 if args.quick else 128
        ppo = ppo_rows(n_envs, n_steps, 1 if args.quick else 4, rounds)
        print_table(
            f"PPO learn(), n_envs={n_envs}, n_steps={n_steps}",
            ppo,
            "steps/s",
            "PPO CartPole steps/s",
        )

    batch = VectorFight(4096)
    batch.reset(seed=0)
    memory = {"state_bytes_4096": batch.state.nbytes, "peak_rss_bytes": peak_rss_bytes()}
    print("\nmemory")
    print(f"  4096-fight batch state: {memory['state_bytes_4096'] / 2**20:.2f} MiB")
    print(f"  peak RSS of this run:   {memory['peak_rss_bytes'] / 2**20:.1f} MiB")

    report = {
        "command": "python -m bench.speed " + " ".join(argv if argv is not None else sys.argv[1:]),
        "quick": args.quick,
        "machine": machine(),
        "single": single,
        "batched": batched,
        "pixels": pixels,
        "ppo": ppo,
        "memory": memory,
    }
    if args.json:
        args.json.write_text(json.dumps(report, indent=2) + "\n")
    return report


if __name__ == "__main__":
    main()
