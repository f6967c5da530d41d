"""A round-robin of every scripted fighter (and any saved models), rated by Elo.

    python -m agents.tournament --episodes 20
    python -m agents.tournament --models runs/ppo.zip runs/selfplay.zip --out runs/elo.json

Every pair of entrants plays `--episodes` games, seats swapped each game. Ratings start at 1200
and move by K=16 per game (a draw scores 0.5), ML-Agents' constants (`vooga_env.tools.elo`).
The table is printed and written to `--out` (JSON) with every pairing's match table.
"""

from __future__ import annotations

import argparse
import sys
from collections.abc import Sequence

from vooga_env.policies import SCRIPTED
from vooga_env.tools.elo import DRAW_SCORE, Tournament, round_robin

from . import common


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="vooga-tournament",
        description="Round-robin of the scripted fighters and saved models, with Elo ratings.",
    )
    parser.add_argument(
        "--scripted",
        nargs="*",
        default=list(SCRIPTED),
        metavar="NAME",
        help=f"scripted entrants (default all: {' '.join(SCRIPTED)})",
    )
    parser.add_argument("--models", nargs="*", default=[], metavar="ZIP", help="saved models")
    common.add_fight_options(parser, episodes=20)
    parser.add_argument(
        "--out", help="write the table and every match to this JSON file (default: none)"
    )
    common.add_output_options(parser)
    return parser


def main(argv: Sequence[str] | None = None) -> int:
    parser = build_parser()
    args = parser.parse_args(argv)
    if args.out:
        common.check_output(parser, "--out", args.out)
    config = common.fight_config(parser, args)
    entrants = [common.policy(parser, spec) for spec in [*args.scripted, *args.models]]
    if len(entrants) < 2:
        parser.error(f"a tournament needs at least two entrants, got {len(entrants)}")
    pairings = len(entrants) * (len(entrants) - 1) // 2
    advance, close = common.progress_bar(
        pairings * args.episodes, not args.no_progress, "tournament"
    )
    try:
        tournament = round_robin(entrants, args.episodes, args.seed, config, progress=advance)
    finally:
        close()
    output = tournament.to_dict()
    if args.out:
        output["out"] = args.out
        common.write_json(args.out, output)
    if args.json:
        common.print_json(output)
    else:
        print(format_tournament(tournament))
        if args.out:
            print(f"written to {args.out}")
    return 0


def format_tournament(tournament: Tournament, mark: str | None = None) -> str:
    """The Elo table (best first) and the cross-table of scores; `mark` flags one entrant."""
    table = tournament.table
    config = tournament.config
    head = (
        f"Elo: K={table.k:g}, start rating {table.start:g}, draw scores {DRAW_SCORE:g}; "
        f"{tournament.episodes} games per pairing, seats swapped each game; "
        f"config {config.name} (max_cycles {config.max_cycles}), seed {tournament.seed}"
    )
    rows = []
    for rank, (name, rating) in enumerate(table.ranking(), start=1):
        entry = table.entries[name]
        score = 100.0 * (entry.wins + DRAW_SCORE * entry.draws) / entry.games
        label = f"{name}  <-" if name == mark else name
        rows.append(
            (rank, label, rating, entry.games, entry.wins, entry.losses, entry.draws, score)
        )
    elo = common.table(
        ("rank", "policy", "Elo", "games", "wins", "losses", "draws", "score %"), rows
    )
    return "\n\n".join(
        [head, elo, "score % of the row against the column:", cross_table(tournament)]
    )


def cross_table(tournament: Tournament) -> str:
    names = [name for name, _ in tournament.table.ranking()]
    scores: dict[tuple[str, str], float] = {}
    for (a, b), match in tournament.matches.items():
        scores[a, b] = 100.0 * match.sides[0].score
        scores[b, a] = 100.0 * match.sides[1].score
    rows = [
        (row, *(f"{scores[row, column]:.0f}" if row != column else "-" for column in names))
        for row in names
    ]
    return common.table(("", *names), rows)


if __name__ == "__main__":
    sys.exit(main())
