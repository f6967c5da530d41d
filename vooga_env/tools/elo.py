"""Elo ratings, and a round-robin tournament that rates every entrant against every other.

The constants follow ML-Agents' self-play trainer: every entrant starts at `START_RATING` (1200)
and each game moves both ratings by `K_FACTOR` (16) times (score - expected score), where a win
scores 1, a draw `DRAW_SCORE` (0.5) and a loss 0, and the expected score of A against B is
`1 / (1 + 10 ** ((B - A) / 400))`.

`round_robin` plays `episodes` games for every pair of entrants (`vooga_env.tools.match.run_match`,
seats swapped each game), then applies the games to the ratings one round at a time: game 0 of
every pairing, then game 1 of every pairing, and so on, so no pairing's games all come first.
"""

from __future__ import annotations

import math
import numbers
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from vooga_env.game.config import FightConfig, load_config
from vooga_env.policies import make_policy
from vooga_env.tools.match import EpisodeRecord, MatchResult, run_match

K_FACTOR = 16.0
"""How far one game moves a rating (rating points per unit of unexpected score)."""
START_RATING = 1200.0
"""Every entrant's rating before its first game."""
DRAW_SCORE = 0.5
"""What a draw scores (a win scores 1, a loss 0)."""

SCORES = {"win": 1.0, "draw": DRAW_SCORE, "loss": 0.0}


def expected_score(rating_a: float, rating_b: float) -> float:
    """A's expected score against B (0..1)."""
    return 1.0 / (1.0 + 10.0 ** ((rating_b - rating_a) / 400.0))


def update(
    rating_a: float, rating_b: float, score_a: float, k: float = K_FACTOR
) -> tuple[float, float]:
    """Both ratings after one game in which A scored `score_a` (1 win, 0.5 draw, 0 loss)."""
    if not 0.0 <= score_a <= 1.0:
        raise ValueError(f"score must be in [0, 1], got {score_a!r}")
    change = k * (score_a - expected_score(rating_a, rating_b))
    return rating_a + change, rating_b - change


@dataclass
class Entry:
    """One entrant's rating and record."""

    rating: float
    wins: int = 0
    losses: int = 0
    draws: int = 0

    @property
    def games(self) -> int:
        return self.wins + self.losses + self.draws


class EloTable:
    """Ratings by name; `record(a, b, score_a)` after each game, `ranking()` best first."""

    def __init__(
        self, names: Sequence[str] = (), k: float = K_FACTOR, start: float = START_RATING
    ) -> None:
        for name, value, allowed in (("k", k, "> 0"), ("start", start, "finite")):
            if isinstance(value, bool) or not isinstance(value, numbers.Real):
                raise TypeError(f"{name} must be a number {allowed}, got {value!r}")
            if not math.isfinite(value) or (name == "k" and value <= 0):
                raise ValueError(f"{name} must be a number {allowed}, got {value!r}")
        self.k = float(k)
        self.start = float(start)
        self.entries: dict[str, Entry] = {}
        for name in names:
            self.add(name)

    def add(self, name: str) -> None:
        if name in self.entries:
            raise ValueError(f"{name!r} is already rated")
        self.entries[name] = Entry(self.start)

    def rating(self, name: str) -> float:
        return self.entries[name].rating

    def record(self, a: str, b: str, score_a: float) -> None:
        """One game between `a` and `b` in which `a` scored `score_a`."""
        if a == b:
            raise ValueError(f"{a!r} cannot be rated against itself")
        for name in (a, b):
            if name not in self.entries:
                raise KeyError(f"{name!r} is not rated; rated: {', '.join(self.entries)}")
        entry_a, entry_b = self.entries[a], self.entries[b]
        entry_a.rating, entry_b.rating = update(entry_a.rating, entry_b.rating, score_a, self.k)
        for entry, score in ((entry_a, score_a), (entry_b, 1.0 - score_a)):
            entry.wins += score == 1.0
            entry.losses += score == 0.0
            entry.draws += 0.0 < score < 1.0

    def ranking(self) -> list[tuple[str, float]]:
        """(name, rating), highest rating first; ties keep the order the names were added."""
        order = sorted(
            enumerate(self.entries.items()), key=lambda item: (-item[1][1].rating, item[0])
        )
        return [(name, entry.rating) for _, (name, entry) in order]

    def to_dict(self) -> dict[str, Any]:
        return {
            "k_factor": self.k,
            "start_rating": self.start,
            "draw_score": DRAW_SCORE,
            "ratings": [
                {
                    "rank": rank,
                    "name": name,
                    "rating": rating,
                    "games": self.entries[name].games,
                    "wins": self.entries[name].wins,
                    "losses": self.entries[name].losses,
                    "draws": self.entries[name].draws,
                }
                for rank, (name, rating) in enumerate(self.ranking(), start=1)
            ],
        }


@dataclass
class Tournament:
    """A round-robin's ratings and every pairing's match (keyed by the two names, in play order)."""

    names: list[str]
    table: EloTable
    episodes: int
    seed: int
    config: FightConfig
    matches: dict[tuple[str, str], MatchResult] = field(default_factory=dict)

    def to_dict(self) -> dict[str, Any]:
        return {
            **self.table.to_dict(),
            "episodes_per_pairing": self.episodes,
            "seed": self.seed,
            "config": self.config.name,
            "max_cycles": self.config.max_cycles,
            "pairings": [match.to_dict() for match in self.matches.values()],
        }


def round_robin(
    entrants: Mapping[str, Any] | Sequence[Any],
    episodes: int = 10,
    seed: int = 0,
    config: str | Path | FightConfig = "default",
    k: float = K_FACTOR,
    start: float = START_RATING,
    progress: Callable[[EpisodeRecord], None] | None = None,
    **overrides: Any,
) -> Tournament:
    """Every entrant against every other, `episodes` games a pairing; Elo over all the games.

    `entrants`: name -> policy spec (anything `make_policy` takes), or a list of specs named by
    their policies. Each pairing's match seed comes from `seed` and the two entrants' places.
    """
    if isinstance(seed, (bool, np.bool_)) or not isinstance(seed, (int, np.integer)) or seed < 0:
        raise ValueError(f"seed must be a non-negative int, got {seed!r}")
    named = _named(entrants)
    if len(named) < 2:
        raise ValueError(f"a tournament needs at least two entrants, got {list(named)}")
    names = list(named)
    table = EloTable(names, k, start)
    fight_config = load_config(config, **overrides)
    tournament = Tournament(names, table, episodes, seed, fight_config)
    for i, a in enumerate(names):
        for j in range(i + 1, len(names)):
            b = names[j]
            match_seed = int(np.random.SeedSequence([seed, i, j]).generate_state(1)[0])
            tournament.matches[(a, b)] = run_match(
                named[a],
                named[b],
                episodes,
                match_seed,
                fight_config,
                names=(a, b),
                progress=progress,
            )
    for game in range(episodes):
        for (a, b), match in tournament.matches.items():
            seat_a = match.seats[game][0]
            table.record(a, b, SCORES[match.episodes[game].outcome(seat_a)])
    return tournament


def _named(entrants: Mapping[str, Any] | Sequence[Any]) -> dict[str, Any]:
    """Name -> Policy, building each policy once (a saved model is loaded once)."""
    if isinstance(entrants, Mapping):
        return {str(name): make_policy(spec) for name, spec in entrants.items()}
    named: dict[str, Any] = {}
    for spec in entrants:
        policy = make_policy(spec)
        name, suffix = policy.name, 2
        while name in named:
            name, suffix = f"{policy.name}_{suffix}", suffix + 1
        named[name] = policy
    return named
