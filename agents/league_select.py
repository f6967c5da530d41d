"""Which model a league ships: its last snapshots and its final model each play fresh games
against every scripted fighter and exploiter of the league, sampling and taking the argmax, and
the one whose worst win rate is highest becomes `final.zip` (ties: the better mean, then the
newer).

A league's policy swings by tens of points from one 1M checkpoint to the next, and the pool's
windows of recent games lag the swings (docs/league.md), so the model the clock stops on is a
draw from them. The games are seeded from the run's seed alone: the same folder gives the same
choice.
"""

from __future__ import annotations

import json
import shutil
from pathlib import Path
from typing import Any

import numpy as np

from vooga_env.policies.batched import VectorOpponent
from vooga_env.policies.models import frozen_batch, load_model
from vooga_env.tools.batch_match import batch_outcomes
from vooga_env.tools.files import atomic_write, atomic_write_text

from .league_pool import Pool, PoolOpponent

PLAYS = {"sampled": False, "argmax": True}  # a way of playing: whether it takes the argmax
SELECTION_FILE = "selection.json"


def scores(
    network: Any, opponents: dict[str, Any], games: int, seed: int, fight: Any = "default"
) -> dict[str, Any]:
    """play -> opponent -> the network's win rate over `games` games against it (half in each
    seat) in `fight`, every opponent in one batch. `opponents`: name -> a function of a seed
    giving a fresh batch player, so that every candidate meets the same players."""
    names = list(opponents)
    fights = games * len(names)
    rates: dict[str, Any] = {}
    for play, deterministic in PLAYS.items():
        pool = Pool(games)
        for offset, name in enumerate(names):
            pool.add(name, opponents[name](seed + 100 + offset))
        mixed = PoolOpponent(pool, fights)
        mixed.assigned = [names[fight % len(names)] for fight in range(fights)]
        candidate = frozen_batch(network, "candidate", deterministic, seed)
        won = np.array(batch_outcomes(candidate, mixed, fights, seed, fight)) == "win"
        rates[play] = {
            name: float(won[offset :: len(names)].mean()) for offset, name in enumerate(names)
        }
    return rates


def league_opponents(
    folder: Path, scripted: list[str], exploiters: list[str], argmax: bool = False, prefix: str = ""
) -> dict[str, Any]:
    """The league's scripted fighters and its exploiters (playing as in the pool: `argmax` or
    sampling), by name; `prefix` goes before each exploiter's name."""
    opponents: dict[str, Any] = {name: _scripted(name) for name in scripted}
    for name in exploiters:
        network = load_model(folder / "exploiters" / f"{name}.zip")
        opponents[prefix + name] = _frozen(network, name, argmax)
    return opponents


def _scripted(name: str) -> Any:
    return lambda seed: VectorOpponent(name, seed)


def _frozen(network: Any, name: str, argmax: bool) -> Any:
    return lambda seed: frozen_batch(network, name, argmax, seed)


def ship_best(
    folder: Path,
    candidates: dict[str, Path],
    opponents: dict[str, Any],
    games: int,
    seed: int,
    fight: Any = "default",
) -> Path:
    """Score each candidate (by name, oldest first), copy the best to `folder/final.zip`, and
    write every score to `folder/selection.json`; returns final.zip's path."""
    table = {}
    for name, path in candidates.items():
        rates = scores(load_model(path), opponents, games, seed, fight)
        every = [rate for play in rates.values() for rate in play.values()]
        table[name] = {"worst": min(every), "mean": float(np.mean(every)), "win_rates": rates}
    names = list(table)
    chosen = max(
        names, key=lambda name: (table[name]["worst"], table[name]["mean"], names.index(name))
    )
    final = folder / "final.zip"
    if candidates[chosen] != final:
        atomic_write(final, lambda temporary: shutil.copyfile(candidates[chosen], temporary))
    report = {"chosen": chosen, "games": games, "candidates": table}
    atomic_write_text(folder / SELECTION_FILE, json.dumps(report, indent=2))
    return final
