"""The shipped training recipe, measured: train it, then fight it against every scripted fighter.

    python -m bench.train_recipe [--config default] [--minutes 15] [--games 200] [--out runs/recipe]
    python -m bench.train_recipe --quick      # seconds: proves the path works (CI runs this)

Prints the model's win rate against `rush` over `--games` games (with a 95% Wilson interval) and
an Elo round-robin of the model and every scripted fighter, and writes both to OUT/result.json.
The claim it checks (issue 4): >= 80% against rush, and a higher Elo than every scripted fighter.
"""

from __future__ import annotations

import argparse
import json
import time
from pathlib import Path

from agents.train import train
from agents.train_config import load_train_config
from vooga_env.elo import K_FACTOR, START_RATING, round_robin
from vooga_env.match import run_match, wilson_interval
from vooga_env.policies import SCRIPTED


def measure(model: Path, games: int, round_robin_games: int, seed: int = 12345) -> dict:
    """Win rate against rush, and Elo among all the scripted fighters."""
    match = run_match(str(model), "rush", games, seed, names=("model", "rush"))
    wins = match.sides[0].wins
    low, high = wilson_interval(wins, match.games)
    tournament = round_robin(
        {"model": str(model), **{name: name for name in SCRIPTED}}, round_robin_games, seed
    )
    ratings = tournament.table.to_dict()
    return {
        "vs_rush": {
            "games": match.games,
            "wins": wins,
            "losses": match.sides[0].losses,
            "draws": match.sides[0].draws,
            "win_rate": wins / match.games,
            "wilson95": [low, high],
        },
        "elo": ratings,
    }


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--config", default="default")
    parser.add_argument("--minutes", type=float, default=15.0)
    parser.add_argument("--games", type=int, default=200)
    parser.add_argument("--round-robin-games", type=int, default=40)
    parser.add_argument("--out", type=Path, default=Path("runs/recipe"))
    parser.add_argument("--quick", action="store_true", help="the smoke config and a few games")
    args = parser.parse_args(argv)
    if args.quick:
        args.config, args.minutes, args.games, args.round_robin_games = "smoke", 1.0, 4, 2
    config = load_train_config(args.config)
    start = time.monotonic()
    model = train(config, args.out, progress=not args.quick, minutes=args.minutes)
    trained = time.monotonic() - start
    result = {
        "config": config.name,
        "train_minutes": trained / 60.0,
        **measure(model, args.games, args.round_robin_games),
    }
    (args.out / "result.json").write_text(json.dumps(result, indent=2))
    vs = result["vs_rush"]
    print(f"trained {config.name} for {trained / 60:.1f} min")
    print(
        f"vs rush: {vs['wins']}/{vs['games']} wins ({vs['win_rate']:.0%}, 95% CI "
        f"{vs['wilson95'][0]:.0%}-{vs['wilson95'][1]:.0%}), {vs['draws']} draws"
    )
    print(
        f"Elo (K={K_FACTOR:g}, start {START_RATING:g}, {args.round_robin_games} games a pairing):"
    )
    for row in result["elo"]["ratings"]:
        print(f"  {row['name']:<12} {row['rating']:7.1f}")
    print(f"wrote {args.out / 'result.json'}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
