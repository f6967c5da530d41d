"""The league's opponent pool: past snapshots, scripted fighters, exploiters and (`CurrentSelf`)
the learner itself, each fight's opponent drawn by prioritized fictitious self-play (PFSP) from
the win rates the pool tracks.

`PoolOpponent` is the batch opponent of a `FightVecEnv`: fight i plays `assigned[i]`, and
`act(observations)` asks each member for its own rows only. `Pool.draw(rng)` picks a member
with weight `f(p)` of the learner's recent win rate `p` against it: "squared" is AlphaStar's
`(1 - p)^2` (hard opponents far more often), "variance" `p (1 - p)` (AlphaStar's for opponents
that are neither beaten nor out of reach: a curriculum, since a learner that loses every game
learns nothing from it), "linear" `1 - p`, "even" 1; every weight is at least `floor`, so that
beaten (and unbeaten) opponents still come back now and then.
"""

from __future__ import annotations

from collections import deque
from typing import Any

import numpy as np

from vooga_env.game.actions import Action
from vooga_env.policies.models import FrozenPolicy
from vooga_env.tools.elo import START_RATING, update

WEIGHTINGS = ("squared", "variance", "linear", "even")


class Pool:
    """Members (name -> batch actor), their recent results against the learner, and Elo."""

    def __init__(self, window: int, weighting: str = "squared", floor: float = 0.05) -> None:
        if weighting not in WEIGHTINGS:
            raise ValueError(f"pfsp = {weighting!r} is not allowed: one of {WEIGHTINGS}")
        self.window = window
        self.weighting = weighting
        self.floor = floor
        self.members: dict[str, Any] = {}
        self.results: dict[str, deque[float]] = {}
        self.ratings: dict[str, float] = {"learner": START_RATING}
        # name -> the learner's argmax score in probe games against it, when probed
        self.probes: dict[str, float] = {}

    def add(self, name: str, actor: Any, results: list[float] | None = None) -> None:
        self.members[name] = actor
        self.results[name] = deque(results or [], maxlen=self.window)
        self.ratings.setdefault(name, self.ratings["learner"])

    def drop(self, name: str) -> None:
        del self.members[name], self.results[name]
        self.probes.pop(name, None)

    def win_rate(self, name: str) -> float:
        """The learner's recent score against `name` (0.5 before any game: unknown)."""
        results = self.results[name]
        return sum(results) / len(results) if results else 0.5

    def weights(self) -> np.ndarray:
        """PFSP's weights; a probed member counts at the lower of its two scores."""
        p = np.array(
            [min(self.win_rate(name), self.probes.get(name, 1.0)) for name in self.members]
        )
        if self.weighting == "squared":
            weight = (1.0 - p) ** 2
        elif self.weighting == "variance":
            weight = p * (1.0 - p)
        elif self.weighting == "linear":
            weight = 1.0 - p
        else:
            weight = np.ones_like(p)
        weight = np.maximum(weight, self.floor)
        return weight / weight.sum()

    def draw(self, rng: np.random.Generator) -> str:
        names = list(self.members)
        return names[int(rng.choice(len(names), p=self.weights()))]

    def record(self, name: str, score: float) -> None:
        """One finished game of the learner against `name`: 1 win, 0.5 draw, 0 loss."""
        if name in self.results:
            self.results[name].append(score)
        if name in self.ratings:
            self.ratings["learner"], self.ratings[name] = update(
                self.ratings["learner"], self.ratings[name], score
            )

    def state(self) -> dict[str, Any]:
        return {
            "results": {name: list(values) for name, values in self.results.items()},
            "ratings": dict(self.ratings),
            "probes": dict(self.probes),
        }


class Slipping:
    """A batch member whose every action is, with probability `noise`, a uniformly random one
    instead (its own seeded stream): a late snapshot, which plays close to its argmax, then
    shows the learner states off its own path."""

    def __init__(self, player: Any, noise: float, seed: int) -> None:
        self.player = player
        self.noise = noise
        self.rng = np.random.default_rng(seed)

    def act(self, observations: np.ndarray) -> np.ndarray:
        actions = self.player.act(observations)
        slipped = self.rng.random(len(actions)) < self.noise
        actions[slipped] = self.rng.integers(0, len(Action), int(slipped.sum()))
        return actions

    def __repr__(self) -> str:
        return f"Slipping({self.player!r}, {self.noise})"


class CurrentSelf:
    """The learner's current weights as a batch player, sampling: the one member a learner never
    leaves behind. `refresh(model)` copies the weights in (the league does at every rollout)."""

    name = "self"

    def __init__(self, seed: int) -> None:
        self.rng = np.random.default_rng(seed)
        self.player: FrozenPolicy | None = None

    def refresh(self, model: Any) -> None:
        self.player = FrozenPolicy(model, self.name, deterministic=False)
        self.player.rng = self.rng  # one stream over every refresh

    def act(self, observations: np.ndarray) -> np.ndarray:
        return self.player.act_batch(observations)


class PoolOpponent:
    """A batch opponent whose fight i is played by pool member `assigned[i]`."""

    def __init__(self, pool: Pool, fights: int) -> None:
        self.pool = pool
        self.assigned: list[str | None] = [None] * fights  # member names, drawn by the league

    def act(self, observations: np.ndarray) -> np.ndarray:
        actions = np.empty(len(observations), dtype=np.int64)
        names = np.array(self.assigned)
        for name in dict.fromkeys(self.assigned):
            rows = np.flatnonzero(names == name)
            actions[rows] = self.pool.members[name].act(observations[rows])
        return actions

    def __repr__(self) -> str:
        return f"PoolOpponent({len(self.pool.members)} members)"
