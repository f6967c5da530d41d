"""Quick matches on the batched engine: every fight of a batch played once to its end.

`batch_match(a, b, games, seed)` plays `games` games of A against B, A in seat 0 in the first
half of the fights and in seat 1 in the rest, all in one batch; A and B are scripted fighters'
names or batch players (`act(observations (n, 41)) -> actions (n,)`). Fight i is seeded with
`seed + i` and the scripted fighters draw from generators seeded from `seed`, so the same call
gives the same games. It counts A's wins, draws and losses.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np

from vooga_env.game.config import FightConfig
from vooga_env.game.outcome import Outcome
from vooga_env.kernel.vector_fight import VectorFight
from vooga_env.policies.batched import batch_opponent
from vooga_env.tools.match import wilson_interval


def batch_match(
    a: Any,
    b: Any,
    games: int,
    seed: int = 0,
    config: str | Path | FightConfig = "default",
    **overrides: Any,
) -> dict[str, Any]:
    """A's wins, draws and losses over `games` games (see the module docstring)."""
    results = batch_outcomes(a, b, games, seed, config, **overrides)
    wins, draws = results.count("win"), results.count("draw")
    return {
        "games": games,
        "wins": wins,
        "draws": draws,
        "losses": games - wins - draws,
        "win_rate": wins / games,
        "ci95": list(wilson_interval(wins, games)),
    }


def batch_outcomes(
    a: Any,
    b: Any,
    games: int,
    seed: int = 0,
    config: str | Path | FightConfig = "default",
    **overrides: Any,
) -> list[str]:
    """A's outcome ("win", "draw" or "loss", as `Outcome.for_seat` gives it) in each fight: for
    a B that plays each fight differently (a mix of opponents, fight by fight)."""
    if isinstance(games, bool) or not isinstance(games, int) or games < 1:
        raise ValueError(f"games must be a positive int, got {games!r}")
    players = (batch_opponent(a, seed + 1), batch_opponent(b, seed + 2))
    fights = VectorFight(games, config, **overrides)
    observations = fights.reset(seed=seed)
    a_seat = np.where(np.arange(games) < (games + 1) // 2, 0, 1)
    rows = np.arange(games)
    results = [""] * games  # until the fight ends
    while "" in results:
        actions = np.empty((games, 2), dtype=np.int64)
        actions[rows, a_seat] = players[0].act(observations[rows, a_seat])
        actions[rows, 1 - a_seat] = players[1].act(observations[rows, 1 - a_seat])
        observations, _, _, _, info = fights.step(actions)
        for fight in info["done_index"].tolist():
            if not results[fight]:
                outcome = Outcome(int(info["winner"][fight]))
                results[fight] = outcome.for_seat(int(a_seat[fight]))
    return results
