"""The shipped training recipe, measured: train it, then fight it against every scripted fighter.

    python -m bench.train_recipe [--config default] [--minutes 15] [--games 200] [--out DIR]
    python -m bench.train_recipe --config selfplay    # also: latest vs first snapshot
    python -m bench.train_recipe --config selfplay --init runs/recipe/default/final.zip \
        --out runs/recipe/selfplay_after                  # self-play from the recipe's model
    python -m bench.train_recipe --quick [--selfplay] # seconds: proves the path works (CI)

Prints the model's win rate against `rush` over `--games` games (with a 95% Wilson interval) and
an Elo round-robin of the model and every scripted fighter, and writes both to OUT/result.json
(OUT: runs/recipe/CONFIG, emptied first).
The claims it checks (issue 4): >= 80% against rush and a higher Elo than every scripted fighter;
for self-play, the latest snapshot beats the first in >= 70% of games, both sampling their actions
as snapshots do in self-play (and, for reference, both taking the argmax).
"""

from __future__ import annotations

import argparse
import dataclasses
import json
import time
from pathlib import Path
from typing import Any

from stable_baselines3.common.vec_env import VecNormalize

from agents.callbacks import learner_won
from agents.train import make_envs, train
from agents.train_config import TrainConfig, load_train_config
from vooga_env.policies import SCRIPTED
from vooga_env.policies.models import FrozenPolicy, load_model
from vooga_env.tools.elo import K_FACTOR, START_RATING, round_robin
from vooga_env.tools.files import atomic_write_text
from vooga_env.tools.match import MatchResult, run_match, wilson_interval


def summary(match: MatchResult) -> dict[str, Any]:
    """The first side's results in a match, with a 95% Wilson interval on its win rate."""
    side = match.sides[0]
    low, high = wilson_interval(side.wins, match.games)
    return {
        "games": match.games,
        "wins": side.wins,
        "losses": side.losses,
        "draws": side.draws,
        "win_rate": side.wins / match.games,
        "wilson95": [low, high],
    }


def first_snapshot(folder: Path) -> Path | None:
    """A self-play run's first snapshot (the untrained network), if there is one."""
    snapshots = sorted(folder.glob("snapshots/snapshot_*.zip"), key=lambda p: int(p.stem[9:]))
    return snapshots[0] if snapshots else None


def measure(model: Path, games: int, round_robin_games: int, seed: int = 12345) -> dict[str, Any]:
    """Against rush, Elo among the scripted fighters, and (self-play) against the first snapshot."""
    result: dict[str, Any] = {}
    first = first_snapshot(model.parent)
    if first is not None:
        for key, deterministic in (("vs_first_snapshot", False), ("vs_first_argmax", True)):
            latest_policy, first_policy = (
                FrozenPolicy(load_model(path), name, deterministic)
                for path, name in ((model, "latest"), (first, "first"))
            )
            match = run_match(latest_policy, first_policy, games, seed, names=("latest", "first"))
            result[key] = summary(match)
    result["vs_rush"] = summary(run_match(str(model), "rush", games, seed, names=("model", "rush")))
    entrants = {"model": str(model), **{name: name for name in SCRIPTED}}
    result["elo"] = round_robin(entrants, round_robin_games, seed).table.to_dict()
    return result


def measure_pixels(model_path: Path, config: TrainConfig, games: int) -> dict[str, Any]:
    """A pixel model against idle, random and rush, sampling its actions as it did in training
    ("vs_NAME") and taking the argmax ("vs_NAME_argmax"), in the envs it trained in (images,
    frame stack; 16 at once); `run_match` plays vector fighters only."""
    from stable_baselines3 import PPO

    model = PPO.load(model_path, device="cpu")
    model.set_random_seed(12345)
    config = dataclasses.replace(config, n_envs=16)
    result = {}
    for offset, opponent in enumerate(("idle", "random", "rush")):
        for suffix, deterministic in (("", False), ("_argmax", True)):
            envs = make_envs(config, opponent, seed=12345 + 1000 * offset)
            envs = envs.venv if isinstance(envs, VecNormalize) else envs
            scores = _scores(model, envs, games, deterministic)
            wins, draws = scores.count(1.0), scores.count(0.5)
            low, high = wilson_interval(wins, games)
            result[f"vs_{opponent}{suffix}"] = {
                "games": games, "wins": wins, "losses": games - wins - draws, "draws": draws,
                "win_rate": wins / games, "wilson95": [low, high],
            }  # fmt: skip
            envs.close()
    return result


def _scores(model: Any, envs: Any, games: int, deterministic: bool) -> list[float]:
    """The learner's first `games` results (1 win, 0.5 draw, 0 loss) in `envs`."""
    scores: list[float] = []
    observations = envs.reset()
    while len(scores) < games:
        actions, _ = model.predict(observations, deterministic=deterministic)
        observations, _, dones, infos = envs.step(actions)
        scores += [learner_won(info) for done, info in zip(dones, infos) if done]
    return scores[:games]


def describe(label: str, result: dict[str, Any]) -> str:
    low, high = result["wilson95"]
    return (
        f"{label}: {result['wins']}/{result['games']} wins ({result['win_rate']:.0%}, "
        f"95% CI {low:.0%}-{high:.0%}), {result['draws']} draws"
    )


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--config", default="default")
    parser.add_argument("--minutes", type=float, default=15.0)
    parser.add_argument("--games", type=int, default=200)
    parser.add_argument("--round-robin-games", type=int, default=40)
    parser.add_argument("--out", type=Path, help="run folder (default runs/recipe/CONFIG)")
    parser.add_argument("--init", help="start from this saved model (then self-play)")
    parser.add_argument("--quick", action="store_true", help="a smoke config and a few games")
    parser.add_argument("--selfplay", action="store_true", help="with --quick: the self-play path")
    parser.add_argument("--pixels", action="store_true", help="with --quick: the pixel path")
    args = parser.parse_args(argv)
    if args.quick:
        args.config = "smoke_selfplay" if args.selfplay else "smoke"
        args.config = "smoke_pixels" if args.pixels else args.config
        args.minutes, args.games, args.round_robin_games = 1.0, 4, 2
    config = load_train_config(args.config, init=args.init)
    args.out = args.out or Path("runs/recipe") / config.name
    start = time.monotonic()
    # a benchmark starts over: its folder is its own
    model = train(config, args.out, progress=not args.quick, minutes=args.minutes, overwrite=True)
    trained = time.monotonic() - start
    result: dict[str, Any] = {"config": config.name, "train_minutes": trained / 60.0}
    if config.obs_type == "pixels":
        result.update(measure_pixels(model, config, args.games))
        atomic_write_text(args.out / "result.json", json.dumps(result, indent=2))
        print(f"trained {config.name} for {trained / 60:.1f} min")
        for opponent in ("idle", "random", "rush"):
            print(describe(f"vs {opponent}, sampled", result[f"vs_{opponent}"]))
            print(describe(f"vs {opponent}, argmax", result[f"vs_{opponent}_argmax"]))
        print(f"wrote {args.out / 'result.json'}")
        return 0
    result.update(measure(model, args.games, args.round_robin_games))
    atomic_write_text(args.out / "result.json", json.dumps(result, indent=2))
    print(f"trained {config.name} for {trained / 60:.1f} min")
    if "vs_first_snapshot" in result:
        print(
            describe(
                "latest vs first snapshot, sampling as in self-play", result["vs_first_snapshot"]
            )
        )
        print(describe("latest vs first snapshot, both argmax", result["vs_first_argmax"]))
    print(describe("vs rush", result["vs_rush"]))
    print(
        f"Elo (K={K_FACTOR:g}, start {START_RATING:g}, {args.round_robin_games} games a pairing):"
    )
    for row in result["elo"]["ratings"]:
        print(f"  {row['name']:<12} {row['rating']:7.1f}")
    print(f"wrote {args.out / 'result.json'}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
