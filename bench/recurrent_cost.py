"""What a memory of the opponent costs: the league's learner (PPO, an MLP) against sb3-contrib's
RecurrentPPO (an LSTM), learning on the same batched fights, side by side in one run.

    python -m bench.recurrent_cost                    # 3 interleaved rounds of 32,768 steps
    python -m bench.recurrent_cost --n-epochs 1       # the rollouts' share of the cost
    python -m bench.recurrent_cost --quick            # for CI (seconds)

Every player of a model is stateless today, so its argmax cannot tell shover from its own past
selves within a game (docs/league.md, "Snapshots that slip, and a memory priced"). A recurrent
learner is the principled way to let it; this prices it. Both learn against rush in the default
league's fights (`configs/league/default.toml`, `fights` of them) with its [ppo] settings: ours
with the league's network and frame, the reference an LSTM as wide as the first layer with one
such layer after it. `--n-epochs` and `--batch-size` replace the config's for both. Torch on one
thread for both; steps/s are medians of interleaved rounds. Needs `pip install sb3-contrib` (the
`dev` extra has it; vooga_env does not).
"""

from __future__ import annotations

import argparse
import json
import time
from collections.abc import Callable, Sequence
from dataclasses import replace
from typing import Any

from agents.common import _positive, quiet_logger
from agents.league import _PPO_KEYS, load_league_config
from agents.train import policy_class
from agents.train_config import PPOConfig
from bench.speed import interleaved, machine, print_table, row
from vooga_env.envs.sb3 import FightVecEnv
from vooga_env.game.config import ConfigError, load_config


def learner(kind: str, ppo: PPOConfig, fights: int, fight: str) -> Any:
    """A fresh learner ("mlp": the league's PPO; "lstm": RecurrentPPO) against rush."""
    envs = FightVecEnv(fights, load_config(fight), opponent="rush", seat="alternate")
    settings = {key: getattr(ppo, key) for key in _PPO_KEYS}
    if kind == "mlp":
        from stable_baselines3 import PPO

        network = {"net_arch": list(ppo.net_arch)}
        mlp = PPO(policy_class(ppo), envs, policy_kwargs=network, seed=0, device="cpu", **settings)
        return quiet_logger(mlp)
    from sb3_contrib import RecurrentPPO

    width = ppo.net_arch[0]
    network = {"lstm_hidden_size": width, "net_arch": list(ppo.net_arch[1:])}
    model = RecurrentPPO(
        "MlpLstmPolicy", envs, policy_kwargs=network, seed=0, device="cpu", **settings
    )
    return quiet_logger(model)


def timed(model: Any, steps: int) -> Callable[[], float]:
    """A round: `steps` more steps of `model.learn`, as steps/s."""

    def run() -> float:
        start = time.perf_counter()
        model.learn(steps, reset_num_timesteps=False)
        return steps / (time.perf_counter() - start)

    return run


def main(argv: Sequence[str] | None = None) -> dict:
    parser = argparse.ArgumentParser(
        prog="python -m bench.recurrent_cost", description=__doc__.split("\n")[0]
    )
    parser.add_argument("--rounds", type=_positive, default=3, help="interleaved rounds (3)")
    parser.add_argument("--steps", type=_positive, default=32_768, help="steps a round (32768)")
    parser.add_argument("--n-epochs", type=_positive, help="PPO epochs (the config's: 10)")
    parser.add_argument("--batch-size", type=_positive, help="minibatch (the config's: 2048)")
    parser.add_argument("--quick", action="store_true", help="one short round of 64 fights")
    parser.add_argument("--json", action="store_true", help="print JSON instead of a table")
    args = parser.parse_args(argv)
    try:
        import sb3_contrib
    except ImportError:
        parser.error("the reference is sb3-contrib's RecurrentPPO: pip install sb3-contrib")
    config = load_league_config("default")
    changed = {"n_epochs": args.n_epochs, "batch_size": args.batch_size}
    try:
        ppo = replace(config.ppo, **{key: value for key, value in changed.items() if value})
    except ConfigError as error:  # PPO's own bounds, e.g. a minibatch of one
        parser.error(str(error))
    fights, rounds, steps = config.fights, args.rounds, args.steps
    if args.quick:
        fights, rounds, steps = 64, 1, 64 * ppo.n_steps
    import torch

    torch.set_num_threads(1)  # both alike, as bench.speed's PPO rows
    models = {kind: learner(kind, ppo, fights, config.fight) for kind in ("mlp", "lstm")}
    for model in models.values():  # the first rollout compiles the kernels and warms torch
        model.learn(fights * ppo.n_steps)
    ours, reference, ratio = interleaved(
        timed(models["mlp"], steps), timed(models["lstm"], steps), rounds
    )
    name = f"learn() vs rush, {fights} fights, {ppo.n_epochs} epochs"
    report = {
        "rows": [row(name, ours, reference, ratio, batch_size=ppo.batch_size, steps=steps)],
        "rounds": rounds,
        "machine": {**machine(), "sb3_contrib": sb3_contrib.__version__},
    }
    if args.json:
        print(json.dumps(report, indent=2))
    else:
        print_table(
            "PPO (MLP, ours) and RecurrentPPO (LSTM)", report["rows"], "steps/s", "LSTM steps/s"
        )
    return report


if __name__ == "__main__":
    main()
