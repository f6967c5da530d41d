"""A policy's win rate against each scripted fighter (95% Wilson interval) and its Elo among them.

    python -m agents.evaluate runs/ppo.zip --episodes 200
    python -m agents.evaluate rush --episodes 50 --json

MODEL is a saved model (.zip), an exported fighter (.npz) or any scripted name. It plays
`--episodes` games against every opponent, seats swapped each game; for the Elo the opponents also
play each other (a round-robin, `vooga_env.tools.elo`: K=16, start 1200, a draw scores 0.5).
Draws count as non-wins in the win rate.
"""

from __future__ import annotations

import argparse
import sys
from collections.abc import Sequence
from typing import Any

from vooga_env.policies import SCRIPTED
from vooga_env.tools.elo import Tournament, round_robin
from vooga_env.tools.match import wilson_interval

from . import common, style_report
from .tournament import format_tournament


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="vooga-evaluate",
        description="Win rates (95% Wilson interval) of MODEL against the scripted fighters, "
        "and its Elo among them.",
    )
    parser.add_argument(
        "model",
        metavar="MODEL",
        help="a saved model (.zip), an exported fighter (.npz) or a scripted name",
    )
    parser.add_argument(
        "--opponents",
        nargs="*",
        default=list(SCRIPTED),
        metavar="NAME",
        help=f"opponents (default all scripted: {' '.join(SCRIPTED)})",
    )
    common.add_fight_options(parser, episodes=50)
    style_report.add_style_options(parser)
    parser.add_argument("--out", metavar="FILE", help="also write the JSON report here")
    common.add_output_options(parser)
    return parser


def main(argv: Sequence[str] | None = None) -> int:
    parser = build_parser()
    args = parser.parse_args(argv)
    if args.out:
        common.check_output(parser, "--out", args.out)
    config = common.fight_config(parser, args)
    candidate = common.policy(parser, args.model)
    opponents = {name: common.policy(parser, name) for name in dict.fromkeys(args.opponents)}
    if not opponents:
        parser.error("give at least one opponent")
    label = candidate.name if candidate.name not in opponents else f"{candidate.name} (evaluated)"
    entrants = {label: candidate, **opponents}
    versions = style_report.plays(candidate, args)
    pairings = len(entrants) * (len(entrants) - 1) // 2 + len(opponents) * len(versions)
    advance, close = common.progress_bar(
        pairings * args.episodes, not args.no_progress, f"evaluating {label}"
    )
    try:
        tournament = round_robin(entrants, args.episodes, args.seed, config, progress=advance)
        style = style_report.style_rows(
            versions, opponents, args.episodes, args.seed, config, progress=advance
        )
    finally:
        close()
    report = {**evaluation(tournament, label, args.model), "style": style}
    if args.out:
        common.write_json(args.out, report)
    if args.json:
        common.print_json(report)
    else:
        print(format_report(report, tournament))
        print("\n" + style_report.format_style(style))
        if args.out:
            print(f"written to {args.out}")
    return 0


def evaluation(tournament: Tournament, label: str, model: str) -> dict[str, Any]:
    """The candidate's row against each opponent, its totals, its Elo and rank, the whole table."""
    rows = []
    totals = {"games": 0, "wins": 0, "draws": 0, "losses": 0}
    for (a, b), match in tournament.matches.items():
        if label not in (a, b):
            continue
        side = match.sides[0] if a == label else match.sides[1]
        opponent = b if a == label else a
        low, high = side.win_rate_interval()
        rows.append(
            {
                "opponent": opponent,
                "games": side.games,
                "wins": side.wins,
                "draws": side.draws,
                "losses": side.losses,
                "win_rate": side.win_rate,
                "ci95": [low, high],
            }
        )
        for key in totals:
            totals[key] += getattr(side, key)
    ranking = [name for name, _ in tournament.table.ranking()]
    return {
        "model": model,
        "name": label,
        "opponents": rows,
        "overall": {
            **totals,
            "win_rate": totals["wins"] / totals["games"],
            "ci95": list(wilson_interval(totals["wins"], totals["games"])),
        },
        "elo": tournament.table.rating(label),
        "elo_rank": ranking.index(label) + 1,
        "entrants": len(ranking),
        "tournament": tournament.to_dict(),
    }


def format_report(report: dict[str, Any], tournament: Tournament) -> str:
    rows = [
        (
            row["opponent"],
            row["games"],
            row["wins"],
            row["draws"],
            row["losses"],
            100.0 * row["win_rate"],
            f"{100 * row['ci95'][0]:.1f} - {100 * row['ci95'][1]:.1f}",
        )
        for row in report["opponents"]
    ]
    overall = report["overall"]
    rows.append(
        (
            "all",
            overall["games"],
            overall["wins"],
            overall["draws"],
            overall["losses"],
            100.0 * overall["win_rate"],
            f"{100 * overall['ci95'][0]:.1f} - {100 * overall['ci95'][1]:.1f}",
        )
    )
    wins = common.table(
        ("opponent", "games", "wins", "draws", "losses", "win %", "95% CI (Wilson)"), rows
    )
    return "\n\n".join(
        [
            f"{_title(report)}: win rate against each opponent",
            wins,
            f"Elo {report['elo']:.0f}, rank {report['elo_rank']} of {report['entrants']}",
            format_tournament(tournament, mark=report["name"]),
        ]
    )


def _title(report: dict[str, Any]) -> str:
    name, model = report["name"], report["model"]
    return name if name == model else f"{name} ({model})"


if __name__ == "__main__":
    sys.exit(main())
