"""The league recipe, measured against issue 12's targets: train it, then test it from outside.

    python -m bench.league_recipe                          # train 15 min, then measure (~30 min)
    python -m bench.league_recipe --config selfplay        # self-play from scratch
    python -m bench.league_recipe --model runs/league/final.zip   # measure a trained model only
    python -m bench.league_recipe --quick                  # seconds: proves the path works (CI)
    python -m bench.league_recipe --steps 15300000 --exploit-steps 11500000  # no clock

A run budgeted in minutes stops wherever the clock says, so on a busier machine it trains fewer
steps; `--steps` and `--exploit-steps` take the clock away, and the same seed gives the same
result however loaded the machine is, only later.

For the model it prints and writes to OUT/result.json (OUT: runs/recipe/league_CONFIG):
- its win rate against every scripted fighter over `--games` batched games (half in each seat,
  `batch_match`), sampling its actions and taking the argmax, with 95% Wilson intervals;
- an Elo round-robin of the model (argmax) and every scripted fighter, `--elo-games` a pairing;
- its style over `--style-games` games against each (`agents.style_report`): the punches and kicks
  it landed, summed, and their shares;
- unless `--exploit-minutes 0`: a fresh exploiter's win rate over its training against the
  model's argmax and sampled play (`agents.exploit`), `--exploit-minutes` each, one exploiter
  for each of `--exploit-seeds` (one exploiter held to 0% is no proof: another seed may win),
  `--exploit-jobs` at a time, one core each.
"""

from __future__ import annotations

import argparse
import json
import math
import multiprocessing
import sys
import time
from pathlib import Path
from typing import Any

from agents.common import _non_negative, _positive, one_core, stop_on_signals
from agents.exploit import _even, _positive_float, exploit
from agents.league import load_league_config, train_league
from agents.league_population import league_folder
from agents.league_select import PLAYS, SELECTION_FILE
from agents.style_report import style_rows
from vooga_env.game.config import load_config
from vooga_env.policies import SCRIPTED
from vooga_env.policies.models import BatchPolicy, FrozenPolicy, load_model
from vooga_env.tools.batch_match import batch_match
from vooga_env.tools.elo import round_robin
from vooga_env.tools.files import atomic_write_text


def win_rates(network: Any, games: int, seed: int) -> dict[str, dict[str, Any]]:
    """play -> scripted fighter -> batch_match's result for the model."""
    rates: dict[str, dict[str, Any]] = {}
    for play, deterministic in PLAYS.items():
        rates[play] = {}
        for offset, name in enumerate(SCRIPTED):
            policy = FrozenPolicy(network, "model", deterministic)
            policy.reset(seed + offset)
            rates[play][name] = batch_match(BatchPolicy(policy), name, games, seed + 1000 * offset)
    return rates


def style(network: Any, fight: Any, games: int, seed: int) -> dict[str, Any]:
    """Punches and kicks the model landed and tried against all the scripted fighters."""
    versions = {play: FrozenPolicy(network, "model", det) for play, det in PLAYS.items()}
    opponents = {name: name for name in SCRIPTED}
    rows = style_rows(versions, opponents, games, seed, fight)
    totals = {
        attack: {
            key: sum(row["attacks"][attack][key] for row in rows) for key in ("landed", "attempted")
        }
        for attack in ("punch", "kick")
    }
    landed = max(sum(total["landed"] for total in totals.values()), 1)
    for total in totals.values():
        total["share_of_landed"] = total["landed"] / landed
    return {"games": len(rows) * games, "attacks": totals}


def measure(model: Path, args: argparse.Namespace) -> dict[str, Any]:
    fight = load_config("default")
    network = load_model(model)
    result: dict[str, Any] = {"model": str(model), "win_rates": win_rates(network, args.games, 7)}
    entrants = {"model": str(model), **{name: name for name in SCRIPTED}}
    table = round_robin(entrants, args.elo_games, 11).table
    result["elo"] = [{"name": name, "rating": rating} for name, rating in table.ranking()]
    result["style"] = style(network, fight, args.style_games, 13)
    if args.exploit_minutes:
        result["exploit"] = exploit_curves(model, fight, args)
    return result


def exploit_curves(model: Path, fight: Any, args: argparse.Namespace) -> dict[str, Any]:
    """play -> one exploiter's curve a seed, trained `--exploit-jobs` at a time (one process and
    one core each, as docs/league.md measures them: two at a time on this 2-core machine)."""
    context = multiprocessing.get_context("spawn")  # no copy of torch's threads
    # A Pool's exit terminates its workers, a Ctrl-C's or SIGTERM's too (an executor's waits for
    # them: SIGTERM left the exploiters training on).
    with context.Pool(args.exploit_jobs, initializer=one_core) as pool:
        runs = {
            play: [
                (seed, pool.apply_async(exploit_curve, (model, fight, not det, seed, args)))
                for seed in args.exploit_seeds
            ]
            for play, det in PLAYS.items()
        }
        return {
            play: [{"seed": seed, "curve": curve.get()} for seed, curve in seeds]
            for play, seeds in runs.items()
        }


def exploit_curve(
    model: Path, fight: Any, sampled: bool, seed: int, args: argparse.Namespace
) -> Any:
    """A fresh exploiter's win rates at each mark against the model's sampled or argmax play."""
    minutes = math.inf if args.exploit_steps else args.exploit_minutes
    return exploit(
        str(model), fight, minutes, steps=args.exploit_steps, evals=args.exploit_evals,
        eval_games=args.exploit_games, seed=seed, sampled=sampled,
    )["curve"]  # fmt: skip


def report(result: dict[str, Any]) -> str:
    lines = []
    if "steps" in result:
        lines.append(f"trained {result['steps']} steps in {result['train_minutes']:.1f} minutes")
    if "selection" in result:
        chosen = result["selection"]["chosen"]
        worst = result["selection"]["candidates"][chosen]["worst"]
        lines.append(f"shipped {chosen}: worst score {100 * worst:.0f}% over the selection's games")
    lines.append(f"{result['model']}: win % against each scripted fighter (95% CI)")
    for play, rates in result["win_rates"].items():
        cells = [
            f"{name} {100 * r['win_rate']:.0f} ({100 * r['ci95'][0]:.0f}-{100 * r['ci95'][1]:.0f})"
            for name, r in rates.items()
        ]
        lines.append(f"  {play}: " + ", ".join(cells))
    ranks = [row["name"] for row in result["elo"]]
    lines.append(
        f"Elo: rank {ranks.index('model') + 1} of {len(ranks)}: "
        + ", ".join(f"{row['name']} {row['rating']:.0f}" for row in result["elo"])
    )
    attacks = result["style"]["attacks"]
    landed = [
        f"{plural} {a['landed']} of {a['attempted']} tried ({100 * a['share_of_landed']:.1f}% of "
        "its hits)"
        for plural, a in (("punches", attacks["punch"]), ("kicks", attacks["kick"]))
    ]
    lines.append(f"landed over {result['style']['games']} games: " + ", ".join(landed))
    for play, runs in result.get("exploit", {}).items():
        for run in runs:
            marks = ", ".join(
                f"{r['minutes']:.1f} min ({r['steps']:,} steps) {100 * _best(r):.0f}%"
                for r in run["curve"]
            )
            lines.append(
                f"exploiter (seed {run['seed']}) against its {play} play (its better of "
                f"sampled/argmax): {marks}"
            )
    return "\n".join(lines)


def train(config: Any, args: argparse.Namespace, result: dict[str, Any]) -> Path:
    """Train the league into `args.out`, noting its minutes, steps and choosing in `result`."""
    start = time.monotonic()
    model = train_league(config, args.out, progress=not args.quick, minutes=args.minutes,
                         overwrite=True)  # fmt: skip
    result["train_minutes"] = (time.monotonic() - start) / 60.0
    if (args.out / SELECTION_FILE).is_file():
        result["selection"] = json.loads((args.out / SELECTION_FILE).read_text())
    runs = [league_folder(args.out, index) for index in range(config.leagues)]
    result["steps"] = [_steps(run) for run in runs] if config.leagues > 1 else _steps(args.out)
    return model


def _steps(run: Path) -> int:
    return json.loads((run / "train_state.json").read_text())["num_timesteps"]


def _best(row: dict[str, Any]) -> float:
    return max(row["sampled"]["win_rate"], row["argmax"]["win_rate"])


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--config", default="default", help="a name in configs/league or a path")
    parser.add_argument("--model", type=Path, help="measure this model; no training")
    parser.add_argument("--seed", type=_non_negative, help="the league's seed (default: config's)")
    parser.add_argument(
        "--minutes", type=_positive_float, help="the league's time budget (default: the config's)"
    )
    parser.add_argument(
        "--steps", type=_positive, help="train the league this many steps, no clock"
    )
    parser.add_argument("--games", type=_positive, default=200)
    parser.add_argument("--elo-games", type=_positive, default=20)
    parser.add_argument("--style-games", type=_positive, default=20)
    parser.add_argument("--exploit-minutes", type=float, default=5.0, help="0: no exploiter")
    parser.add_argument(
        "--exploit-steps", type=_positive, help="each exploiter trains this many steps, no clock"
    )
    parser.add_argument("--exploit-evals", type=_positive, default=5, help="marks in its budget")
    parser.add_argument("--exploit-games", type=_even, default=100, help="games a mark (even)")
    parser.add_argument(
        "--exploit-seeds", type=_non_negative, nargs="+", default=[3, 4], metavar="SEED",
        help="one exploiter a seed, against each play (default: 3 4)",
    )  # fmt: skip
    parser.add_argument(
        "--exploit-jobs", type=_positive, default=2, help="exploiters trained at a time (default 2)"
    )
    parser.add_argument("--out", type=Path, help="run folder (default runs/recipe/league_CONFIG)")
    parser.add_argument("--quick", action="store_true", help="the smoke league, a few games")
    args = parser.parse_args(argv)
    if args.exploit_minutes < 0:
        parser.error(
            f"--exploit-minutes: must be >= 0 (0: no exploiter), got {args.exploit_minutes}"
        )
    if args.steps and args.minutes:
        parser.error("--steps: not with --minutes (a budget of steps has no clock)")
    if args.steps and args.model:
        parser.error("--steps: not with --model (a model to measure is not trained)")
    if args.exploit_steps and not args.exploit_minutes:
        parser.error("--exploit-steps: not with --exploit-minutes 0 (no exploiter)")
    if args.quick:
        args.config, args.games = "smoke", 4
        args.minutes = None if args.steps else 1.0
        args.elo_games, args.style_games, args.exploit_minutes = 1, 1, 0.02
        args.exploit_evals, args.exploit_games, args.exploit_seeds = 1, 4, [3]
    clock = 0.0 if args.steps else None  # 0: no clock
    config = load_league_config(
        args.config, seed=args.seed, total_timesteps=args.steps, minutes=clock
    )
    one_core()  # as agents.league and agents.exploit run: one core each, two runs at a time
    stop_on_signals()  # `kill`, a job scheduler: as Ctrl-C, the exploiters' processes ended too
    args.out = args.out or Path("runs/recipe") / f"league_{args.config}"
    result: dict[str, Any] = {"config": config.name}
    model = args.model
    if model is None:
        try:
            model = train(config, args, result)
        except KeyboardInterrupt:
            steps = f" --steps {args.steps}" if args.steps else ""
            print(
                f"\ninterrupted: the league's last checkpoint is in {args.out}; continue it with "
                f"`python -m agents.league --config {args.config} --seed {config.seed}{steps} "
                f"--resume --out {args.out}` and measure its final.zip with --model",
                file=sys.stderr,
            )
            return 130
    args.out.mkdir(parents=True, exist_ok=True)
    try:
        result.update(measure(model, args))
    except KeyboardInterrupt:
        print(f"\ninterrupted: nothing measured; measure {model} again with --model",
              file=sys.stderr)  # fmt: skip
        return 130
    atomic_write_text(args.out / "result.json", json.dumps(result, indent=2))
    print(report(result))
    print(f"wrote {args.out / 'result.json'}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
