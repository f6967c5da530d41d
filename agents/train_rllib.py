"""Train a fighter with Ray RLlib: multi-agent PPO on the new API stack, self-play in a league.

    python -m agents.train_rllib --config rllib_selfplay [--out runs/NAME] [--iterations N]
    python -m agents.train_rllib --config rllib_selfplay --env-runners 4 --envs-per-runner 16
    python -m agents.train_rllib --config rllib_selfplay --address HEAD:6379  # join a cluster
    python -m agents.train_rllib --out runs/NAME --export main_v3  # write runs/NAME/main_v3.npz

`main` learns against a pool of the scripted fighters and frozen snapshots of itself
(`agents.rllib_league`). Every iteration logs main's win rate and the Elo of everyone in the pool,
and appends them to `OUT/progress.jsonl`. Every `checkpoint_every` iterations (and on Ctrl-C or a
crash) `OUT/checkpoint/` (an RLlib algorithm checkpoint), `OUT/train_state.json` and
`OUT/main.npz` are rewritten; `--resume` continues from them. `OUT/main.npz` is a fighter that
`agents.match`, `agents.evaluate`, the tournament and `FightEnv(opponent=...)` take. See
docs/rllib.md for the cluster recipe and the scaling figures.
"""

from __future__ import annotations

import argparse
import dataclasses
import json
import math
import shutil
import signal
import socket
import sys
import time
from pathlib import Path
from typing import Any

from vooga_env.game.config import ConfigError

from .common import _minutes, budget_minutes, request_stop, stop_on_signals
from .rllib_config import RLlibTrainConfig, load_rllib_config

CHECKPOINT = "checkpoint"
STATE_FILE = "train_state.json"
PROGRESS_FILE = "progress.jsonl"
CONNECT_TIMEOUT_S = 3.0
# An HTTP/2 client's opening (the preface, then an empty SETTINGS frame): a Ray head (gRPC)
# answers it with a SETTINGS frame of its own at once.
HTTP2_HELLO = b"PRI * HTTP/2.0\r\n\r\nSM\r\n\r\n" + bytes([0, 0, 0, 4, 0, 0, 0, 0, 0])
HTTP2_SETTINGS = 4


def check_address(address: str) -> None:
    """Fail within seconds, naming it, when a cluster address does not answer as Ray does:
    ray.init itself keeps retrying (2.60 was still at it after 150 s against a closed port, and
    after 200 s against a port that accepts and stays silent). "auto" and "local" are left to
    Ray."""
    if address in ("auto", "local"):
        return
    host, _, port = address.removeprefix("ray://").rpartition(":")
    if not host or not port.isdigit():
        raise ConfigError(f"--address {address!r} is not HOST:PORT (or ray://HOST:PORT, auto)")
    try:
        reply = http2_reply(host, int(port))
    except OSError as error:
        raise ConnectionError(
            f"--address {address}: no Ray cluster answers there ({error}); "
            "start one with `ray start --head` or check the host and port"
        ) from None
    if len(reply) < 4 or reply[3] != HTTP2_SETTINGS:
        raise ConnectionError(
            f"--address {address}: something answers there, but not as a Ray cluster does "
            f"(gRPC; it sent {reply[:16]!r}); check the port (`ray start --head` prints it)"
        )


def http2_reply(host: str, port: int) -> bytes:
    """The first bytes a server sends back to an HTTP/2 opening (b"" if it hangs up)."""
    with socket.create_connection((host, port), timeout=CONNECT_TIMEOUT_S) as connection:
        connection.sendall(HTTP2_HELLO)
        reply = b""
        while len(reply) < 4:
            chunk = connection.recv(9)
            if not chunk:
                break
            reply += chunk
        return reply


def needs(config: RLlibTrainConfig) -> dict[str, float]:
    """The Ray resources this run's actors ask for: a CPU per env runner and per learner actor,
    and the learners' GPUs (the driver's own learner too, when `learners` is 0)."""
    learner_cpus = config.learners if config.gpus_per_learner == 0 else 0
    return {
        "CPU": float(config.env_runners + learner_cpus),
        "GPU": max(config.learners, 1) * config.gpus_per_learner,
    }


def connect(address: str | None, config: RLlibTrainConfig, temp_dir: str | None = None) -> bool:
    """Join (or start) Ray; True when this call started it (and so must shut it down).

    Refuses a run whose actors need more CPUs or GPUs than the cluster has: Ray would wait for
    them forever.
    """
    import ray

    if address:
        check_address(address)
    started = not ray.is_initialized()
    if started:
        caller = signal.getsignal(signal.SIGTERM)
        ray.init(
            address=address or None,
            include_dashboard=False if not address else None,
            _temp_dir=temp_dir,
            logging_level="ERROR",
        )
        if caller is request_stop:  # Ray's own handler exits without our checkpoint
            signal.signal(signal.SIGTERM, caller)
    have = ray.cluster_resources()
    short = {kind: n for kind, n in needs(config).items() if n > have.get(kind, 0)}
    if short:
        if started:
            ray.shutdown()
        missing = " and ".join(f"{n:g} {kind}s" for kind, n in short.items())
        has = " and ".join(f"{have.get(kind, 0):g} {kind}s" for kind in short)
        raise ConfigError(
            f"env_runners = {config.env_runners}, learners = {config.learners}, "
            f"gpus_per_learner = {config.gpus_per_learner:g} need {missing}; the Ray cluster "
            f"has {has} (Ray would wait for them forever)"
        )
    return started


def algorithm_config(config: RLlibTrainConfig, league: Any) -> Any:
    """RLlib's PPOConfig for this run, with every pool member (and retired snapshot) a module."""
    from ray.rllib.algorithms.ppo import PPOConfig
    from ray.rllib.core.rl_module.multi_rl_module import MultiRLModuleSpec
    from ray.rllib.core.rl_module.rl_module import RLModuleSpec

    from .rllib_env import FightMultiAgentEnv, ScriptedModule
    from .rllib_league import MAIN, LeagueCallbacks

    ppo = config.ppo
    specs = {MAIN: network_spec(config)}
    for index, name in enumerate(config.league.scripted):
        seed = config.seed * 1000 + index
        specs[name] = RLModuleSpec(
            module_class=ScriptedModule, model_config={"fighter": name, "seed": seed}
        )
    for module_id in (*league.snapshots, *league.retired):
        specs[module_id] = network_spec(config)
    return (
        PPOConfig()
        .environment(FightMultiAgentEnv, env_config={"fight": config.fight, "seed": config.seed})
        .env_runners(
            num_env_runners=config.env_runners,
            num_envs_per_env_runner=config.envs_per_runner,
            num_cpus_per_env_runner=1,
        )
        .multi_agent(
            policies=set(specs),
            policy_mapping_fn=league.mapping(config.seed),
            policies_to_train=[MAIN],
        )
        .rl_module(rl_module_spec=MultiRLModuleSpec(rl_module_specs=specs))
        .training(
            lr=ppo.lr,
            gamma=ppo.gamma,
            lambda_=ppo.gae_lambda,
            train_batch_size_per_learner=ppo.train_batch_size,
            minibatch_size=ppo.minibatch_size,
            num_epochs=ppo.num_epochs,
            entropy_coeff=ppo.entropy_coeff,
            clip_param=ppo.clip_param,
        )
        .learners(num_learners=config.learners, num_gpus_per_learner=config.gpus_per_learner)
        .callbacks(LeagueCallbacks)
        .debugging(seed=config.seed)
    )


def network_spec(config: RLlibTrainConfig) -> Any:
    """The spec of `main` and of every snapshot of it: RLlib's default actor-critic MLP."""
    from ray.rllib.core.rl_module.default_model_config import DefaultModelConfig
    from ray.rllib.core.rl_module.rl_module import RLModuleSpec

    return RLModuleSpec(
        model_config=DefaultModelConfig(
            fcnet_hiddens=list(config.ppo.net_arch), fcnet_activation=config.ppo.activation
        )
    )


def add_snapshot(algo: Any, league: Any, seed: int) -> str:
    """Freeze a copy of `main` into the pool (RLlib's add_module pattern) and remap opponents.

    The copy is built on the learner and the env runners, given main's weights there, and the
    env runners get the new mapping. A snapshot pushed out of the window only loses its weight:
    an episode that runs on past the iteration may still be mapped to it.
    """
    from ray.rllib.core.rl_module.rl_module import RLModuleSpec

    from .rllib_league import MAIN

    module_id = league.new_snapshot()
    main = algo.get_module(MAIN)
    algo.add_module(
        module_id=module_id,
        module_spec=RLModuleSpec.from_module(main),
        new_agent_to_module_mapping_fn=league.mapping(seed),
    )
    algo.set_state({"learner_group": {"learner": {"rl_module": {module_id: main.get_state()}}}})
    algo.env_runner_group.sync_weights(
        policies=[module_id], from_worker_or_learner_group=algo.learner_group, inference_only=True
    )
    return module_id


def push_mapping(algo: Any, mapping: Any) -> None:
    """Give every env runner the opponent draw for the current win rates (new episodes use it)."""

    def update(env_runner: Any) -> None:
        env_runner.config.multi_agent(policy_mapping_fn=mapping)

    algo.env_runner_group.foreach_env_runner(update)
    algo.config._is_frozen = False  # RLlib's own add_module unfreezes it the same way
    algo.config.multi_agent(policy_mapping_fn=mapping)
    algo.config.freeze()


def save(algo: Any, folder: Path, state: dict[str, Any]) -> None:
    """Rewrite the checkpoint, the run's state and `main.npz`; a crash midway keeps the old set.

    The new checkpoint is written beside the old one and swapped in, the state file last.
    """
    from .rllib_export import export_module
    from .rllib_league import MAIN

    fresh = folder / f"{CHECKPOINT}.new"
    shutil.rmtree(fresh, ignore_errors=True)
    algo.save_to_path(fresh.resolve())
    old = folder / f"{CHECKPOINT}.old"
    if (folder / CHECKPOINT).exists():
        (folder / CHECKPOINT).rename(old)
    fresh.rename(folder / CHECKPOINT)
    shutil.rmtree(old, ignore_errors=True)
    export_module(algo.get_module(MAIN), folder / f"{MAIN}.npz")
    temporary = folder / f"{STATE_FILE}.new"
    temporary.write_text(json.dumps(state, indent=2))
    temporary.replace(folder / STATE_FILE)


def check_checkpoint(folder: Path) -> None:
    """Before Ray starts: the checkpoint's `main` must read this fight's observations and act
    with its actions (an old checkpoint, or one of another game, is named with both sizes)."""
    from ray.rllib.core.rl_module.rl_module import RLModule

    from vooga_env.game.actions import Action
    from vooga_env.game.observations import OBSERVATION_SIZE

    from .rllib_league import MAIN

    path = folder / CHECKPOINT / "learner_group" / "learner" / "rl_module" / MAIN
    if not path.is_dir():
        raise FileNotFoundError(f"--resume: {folder / CHECKPOINT} holds no module {MAIN!r}")
    module = RLModule.from_checkpoint(path)
    shape = getattr(module.observation_space, "shape", None)
    if shape != (OBSERVATION_SIZE,):
        raise ConfigError(
            f"checkpoint {folder / CHECKPOINT}: module {MAIN!r} reads observations of shape "
            f"{shape}, the fight gives ({OBSERVATION_SIZE},)"
        )
    actions = getattr(module.action_space, "n", None)
    if actions != len(Action):
        raise ConfigError(
            f"checkpoint {folder / CHECKPOINT}: module {MAIN!r} has {actions} actions, "
            f"the fight has {len(Action)}"
        )


def restore(algo: Any, folder: Path) -> None:
    """Load the run's checkpoint into `algo`, or say which checkpoint does not fit and why."""
    try:
        algo.restore_from_path((folder / CHECKPOINT).resolve())
    except (RuntimeError, ValueError, KeyError) as error:
        first = str(error).strip().splitlines()[0] if str(error).strip() else type(error).__name__
        raise ConfigError(
            f"checkpoint {folder / CHECKPOINT} does not fit this run (another observation "
            f"size, net_arch or league?): {first}"
        ) from None


def iteration_report(iteration: int, result: dict[str, Any], league: Any) -> dict[str, Any]:
    """One line of progress: steps, speed, main's win rates and everyone's Elo."""
    runners = result.get("env_runners", {})
    steps = int(runners.get("num_env_steps_sampled", 0))
    seconds = float(result.get("time_this_iter_s", 0.0))
    return {
        "iteration": iteration,
        "env_steps": steps,
        "seconds": round(seconds, 3),
        "env_steps_per_s": round(steps / seconds, 1) if seconds else 0.0,
        # per vector step of one runner (means over its steps): the env's share of sampling
        "env_step_ms": round(1e3 * float(runners.get("env_step_timer", 0.0)), 3),
        "inference_ms": round(1e3 * float(runners.get("rlmodule_inference_timer", 0.0)), 3),
        "connectors_ms": round(1e3 * float(runners.get("connector_pipeline_timer", 0.0)), 3),
        "pool": list(league.pool),
        "win_rates": {k: round(v, 3) for k, v in league.win_rates.items()},
        "elo": {k: round(v, 1) for k, v in league.ratings.items()},
        "nodes": {  # a node of a resumed run's last session reports NaN (no samples here)
            node: int(n) for node, n in runners.get("nodes", {}).items() if math.isfinite(n)
        },
    }


def format_report(report: dict[str, Any]) -> str:
    rates = " ".join(f"{m}={report['win_rates'].get(m, 0.5):.2f}" for m in report["pool"])
    return (
        f"iter {report['iteration']:4d}  {report['env_steps']:6d} steps  "
        f"{report['env_steps_per_s']:7.0f}/s  main Elo {report['elo']['main']:.0f}  "
        f"win rates: {rates}"
    )


def prepare(folder: Path, resume: bool, overwrite: bool) -> dict[str, Any]:
    """The saved state to resume from ({} for a fresh run), refusing to mix two runs."""
    if resume:
        if not (folder / STATE_FILE).is_file() or not (folder / CHECKPOINT).is_dir():
            raise FileNotFoundError(f"--resume: no checkpoint in {folder}")
        return json.loads((folder / STATE_FILE).read_text())
    if (folder / STATE_FILE).exists() or (folder / CHECKPOINT).exists():
        if not overwrite:
            raise FileExistsError(
                f"{folder} holds a run already: --resume continues it, --overwrite starts over "
                "(deleting it), or pick another --out"
            )
        shutil.rmtree(folder)
    return {}


def train(
    config: RLlibTrainConfig,
    folder: Path,
    resume: bool = False,
    overwrite: bool = False,
    address: str | None = None,
    minutes: float | None = None,
    temp_dir: str | None = None,
    echo: bool = True,
) -> dict[str, Any]:
    """Run (or continue) one training; returns the final state (what train_state.json holds)."""
    budget = budget_minutes(minutes, config.minutes)  # before Ray and torch are imported
    import ray
    import torch

    from .rllib_league import League

    # As agents.train: small networks, and the driver's own sampling (0 env runners) spends 20x
    # longer in inference when torch's thread pool fights the learner and the env for 2 cores.
    torch.set_num_threads(1)
    saved = prepare(folder, resume, overwrite)
    if saved:
        check_checkpoint(folder)
    folder.mkdir(parents=True, exist_ok=True)
    if not saved:
        (folder / "train_config.json").write_text(json.dumps(dataclasses.asdict(config), indent=2))
    league = League.from_dict(config.league, saved["league"]) if saved else League(config.league)
    if not league.pool:  # no scripted fighters: main starts against a copy of itself
        league.new_snapshot()
    started = connect(address, config, temp_dir)
    try:
        algo = algorithm_config(config, league).build_algo()
        try:
            if saved:
                restore(algo, folder)
            else:
                algo.set_state(
                    {"learner_group": {"learner": {"rl_module": _snapshot_weights(algo, league)}}}
                )
                algo.env_runner_group.sync_weights(
                    from_worker_or_learner_group=algo.learner_group, inference_only=True
                )
            return _loop(algo, config, folder, league, saved, budget, echo)
        finally:
            algo.stop()
    finally:
        if started:
            ray.shutdown()


def _snapshot_weights(algo: Any, league: Any) -> dict[str, Any]:
    """Main's weights for every snapshot that exists before training (a fresh self-play run)."""
    from .rllib_league import MAIN

    weights = algo.get_module(MAIN).get_state()
    return {module_id: weights for module_id in league.snapshots}


def _loop(
    algo: Any,
    config: RLlibTrainConfig,
    folder: Path,
    league: Any,
    saved: dict[str, Any],
    minutes: float,
    echo: bool,
) -> dict[str, Any]:
    """The iterations: train, score the league, snapshot, checkpoint (also on Ctrl-C / crash)."""
    state = {"iteration": saved.get("iteration", 0), "nodes": saved.get("nodes", {})}
    deadline = time.monotonic() + 60.0 * minutes if minutes else float("inf")

    def snapshot() -> dict[str, Any]:
        return {**state, "league": league.to_dict(), "config": config.name}

    try:
        while state["iteration"] < config.iterations and time.monotonic() < deadline:
            result = algo.train()
            state["iteration"] += 1
            iteration = state["iteration"]
            league.record(result.get("env_runners", {}).get("league", {}))
            if iteration % config.league.snapshot_every == 0:
                add_snapshot(algo, league, config.seed)
            else:
                push_mapping(algo, league.mapping(config.seed))
            report = iteration_report(iteration, result, league)
            for node, steps in report["nodes"].items():
                state["nodes"][node] = state["nodes"].get(node, 0) + steps
            with (folder / PROGRESS_FILE).open("a") as file:
                file.write(json.dumps(report) + "\n")
            if echo:
                print(format_report(report), flush=True)
            if iteration % config.checkpoint_every == 0:
                save(algo, folder, snapshot())
    except BaseException:
        save(algo, folder, snapshot())
        raise
    save(algo, folder, snapshot())
    return snapshot()


def export(folder: Path, module_id: str) -> Path:
    """`--export`: write module `module_id` of the run's checkpoint to OUT/MODULE.npz."""
    from .rllib_export import export_checkpoint

    return export_checkpoint(folder / CHECKPOINT, module_id, folder / f"{module_id}.npz")


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--config", default="rllib_selfplay", help="a configs/train name or path")
    parser.add_argument("--out", type=Path, help="run folder (default runs/CONFIG)")
    parser.add_argument("--seed", type=int, help="the same seed repeats a run (docs/rllib.md)")
    parser.add_argument("--iterations", type=int, help="training iterations (overrides)")
    parser.add_argument("--env-runners", type=int, help="env runner processes (overrides)")
    parser.add_argument("--envs-per-runner", type=int, help="fights each runner steps (overrides)")
    parser.add_argument("--address", help="join this Ray cluster (HOST:PORT, ray://..., auto)")
    parser.add_argument("--resume", action="store_true", help="continue from OUT/checkpoint")
    parser.add_argument("--overwrite", action="store_true", help="start over in a used OUT")
    parser.add_argument(
        "--minutes", type=_minutes, help="stop after this much wall time (0: no budget)"
    )
    parser.add_argument("--export", metavar="MODULE", help="write OUT/MODULE.npz and exit")
    return parser


def main(argv: list[str] | None = None) -> int:
    parser = build_parser()
    args = parser.parse_args(argv)
    overrides = {
        "seed": args.seed,
        "iterations": args.iterations,
        "env_runners": args.env_runners,
        "envs_per_runner": args.envs_per_runner,
    }
    try:
        config = load_rllib_config(args.config, **overrides)
    except ConfigError as error:
        parser.error(str(error))
    folder = args.out or Path("runs") / config.name
    stop_on_signals()  # `kill`, a job scheduler: as Ctrl-C (kept across ray.init)
    try:
        if args.export:
            print(f"exported: {export(folder, args.export)}")
            return 0
        state = train(config, folder, args.resume, args.overwrite, args.address, args.minutes)
    except KeyboardInterrupt:
        print(
            f"\ninterrupted: the last checkpoint is {folder / CHECKPOINT}; "
            f"continue with --resume --out {folder}",
            file=sys.stderr,
        )
        return 130
    except (FileNotFoundError, FileExistsError, ConfigError, ConnectionError, KeyError) as error:
        parser.error(str(error).strip("\"'"))
    print(f"trained {state['iteration']} iterations: {folder / 'main.npz'}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
