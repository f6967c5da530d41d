"""Which model a league ships: its last snapshots and its final model each play fresh games
against every scripted fighter and exploiter of the league, sampling and taking the argmax, and
the one whose worst score is highest becomes `final.zip` (ties: the better mean, then the
newer). The score against a scripted fighter is the share of games won; against an exploiter,
the share not lost: issue 12 asks for wins over the scripted fighters and for exploiters that
win under half their games, and a draw with an exploiter is not its win.

A league's policy swings by tens of points from one 1M checkpoint to the next, and the pool's
windows of recent games lag the swings (docs/league.md), so the model the clock stops on is a
draw from them. The games are seeded from the run's seed alone: the same folder gives the same
choice.
"""

from __future__ import annotations

import json
import shutil
from collections.abc import Collection
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
    network: Any,
    opponents: dict[str, Any],
    games: int,
    seed: int,
    fight: Any = "default",
    exploiters: Collection[str] = (),
) -> dict[str, Any]:
    """play -> opponent -> the network's score over `games` games against it (half in each
    seat) in `fight`, every opponent in one batch: the share won, or against the `exploiters`
    the share not lost. `opponents`: name -> a function of a seed giving a fresh batch player,
    so that every candidate meets the same players."""
    names = list(opponents)
    rates: dict[str, Any] = {}
    for play, deterministic in PLAYS.items():
        pool = Pool(games)
        for offset, name in enumerate(names):
            pool.add(name, opponents[name](seed + 100 + offset))
        candidate = frozen_batch(network, "candidate", deterministic, seed)
        outcomes = outcomes_against(candidate, pool, names, games, seed, fight)
        rates[play] = {
            name: float(_scored(outcomes[name], name in exploiters).mean()) for name in names
        }
    return rates


def outcomes_against(
    player: Any, pool: Pool, names: list[str], games: int, seed: int, fight: Any
) -> dict[str, np.ndarray]:
    """name -> `player`'s outcomes ("win", "draw", "loss") in `games` games against that member
    of `pool`, every member in one batch, each in both seats."""
    fights = games * len(names)
    mixed = PoolOpponent(pool, fights)
    mixed.assigned = [names[index % len(names)] for index in range(fights)]
    outcomes = np.array(batch_outcomes(player, mixed, fights, seed, fight))
    return {name: outcomes[offset :: len(names)] for offset, name in enumerate(names)}


def _scored(outcomes: np.ndarray, exploiter: bool) -> np.ndarray:
    return outcomes != "loss" if exploiter else outcomes == "win"


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
    exploiters: Collection[str] = (),
) -> Path:
    """Score each candidate (by name, oldest first; `exploiters` names the opponents scored by
    the games not lost), copy the best to `folder/final.zip`, and write every score to
    `folder/selection.json`; returns final.zip's path."""
    table = {}
    for name, path in candidates.items():
        rates = scores(load_model(path), opponents, games, seed, fight, exploiters)
        every = [rate for play in rates.values() for rate in play.values()]
        table[name] = {"worst": min(every), "mean": float(np.mean(every)), "scores": rates}
    names = list(table)
    chosen = max(
        names, key=lambda name: (table[name]["worst"], table[name]["mean"], names.index(name))
    )
    final = folder / "final.zip"
    if candidates[chosen] != final:
        atomic_write(final, lambda temporary: shutil.copyfile(candidates[chosen], temporary))
    report = {
        "chosen": chosen,
        "games": games,
        "exploiters": sorted(exploiters),
        "candidates": table,
    }
    atomic_write_text(folder / SELECTION_FILE, json.dumps(report, indent=2))
    return final
