"""The style part of `agents.evaluate`: per opponent and per way of playing (a model's sampled
actions and its argmax), the win/draw/loss with a Wilson interval, how the games ended, the
action distribution, and punches and kicks attempted and landed (`vooga_env.tools.style`)."""

from __future__ import annotations

import argparse
import copy
from collections.abc import Callable
from typing import Any

from vooga_env.game.actions import Action
from vooga_env.game.config import FightConfig
from vooga_env.policies import Policy
from vooga_env.policies.models import MLPPolicy
from vooga_env.tools.match import run_match
from vooga_env.tools.style import ATTACKS, ENDINGS, StyleStats

from . import common

PLAYS = ("sampled", "argmax")


def add_style_options(parser: argparse.ArgumentParser) -> None:
    parser.add_argument(
        "--sampled", action="store_true", help="a model's sampled play only (default: both)"
    )
    parser.add_argument(
        "--argmax", action="store_true", help="a model's argmax play only (default: both)"
    )


def plays(candidate: Policy, args: argparse.Namespace) -> dict[str, Policy]:
    """The ways the candidate plays: a saved model sampled and/or argmax, a scripted one as is."""
    if not isinstance(candidate, MLPPolicy):
        return {"scripted": candidate}
    chosen = [play for play in PLAYS if getattr(args, play)] or list(PLAYS)
    versions = {}
    for play in chosen:
        version = copy.copy(candidate)
        version.deterministic = play == "argmax"
        versions[play] = version
    return versions


def style_rows(
    versions: dict[str, Policy],
    opponents: dict[str, Policy],
    episodes: int,
    seed: int,
    config: FightConfig,
    progress: Callable[[Any], None] | None = None,
) -> list[dict[str, Any]]:
    """One row per (opponent, play): the match's result and the candidate's style in it."""
    rows = []
    for opponent, policy in opponents.items():
        for play, version in versions.items():
            match = run_match(
                version,
                policy,
                episodes,
                seed,
                config,
                record_actions=True,
                record_observations=True,
                progress=progress,
            )
            style = StyleStats()
            for record, seats in zip(match.episodes, match.seats, strict=True):
                style.add(record, seats[0])
            side = match.sides[0]
            rows.append(
                {
                    "opponent": opponent,
                    "play": play,
                    **{key: getattr(side, key) for key in ("games", "wins", "draws", "losses")},
                    "win_rate": side.win_rate,
                    "ci95": list(side.win_rate_interval()),
                    **style.to_dict(),
                }
            )
    return rows


def format_style(rows: list[dict[str, Any]]) -> str:
    """Two tables: results with endings and attacks, then the action shares (%)."""
    results = []
    for row in rows:
        low, high = row["ci95"]
        attacks = [
            f"{row['attacks'][attack]['landed']}/{row['attacks'][attack]['attempted']}"
            for attack in ATTACKS
        ]
        results.append(
            (
                row["opponent"],
                row["play"],
                f"{row['wins']}/{row['draws']}/{row['losses']}",
                100.0 * row["win_rate"],
                f"{100 * low:.1f} - {100 * high:.1f}",
                *(row["endings"][ending] for ending in ENDINGS),
                *attacks,
            )
        )
    headers = ("opponent", "play", "W/D/L", "win %", "95% CI", *ENDINGS)
    headers += ("punches landed/tried", "kicks landed/tried")
    names = [action.name.lower() for action in Action]
    shares = [
        (row["opponent"], row["play"], *(100.0 * row["actions"][name] for name in names))
        for row in rows
    ]
    return "\n\n".join(
        [
            "how it played: results, how the games ended, attacks landed (not blocked) / tried",
            common.table(headers, results),
            "its actions (% of its steps)",
            common.table(("opponent", "play", *names), shares),
        ]
    )
