"""Matches between two policies: N episodes, seats swapped each game, seeds derived from one seed.

`run_match("rush", "turtle", episodes=200, seed=0)` plays games in pairs: in the first game of a
pair policy A is `fighter_0` and B is `fighter_1`, in the second they swap seats, and both games of
a pair use the same env seed and the same policy seeds, so neither side is favoured by its seat or
by its draw of randomness. Every seed comes from `episode_seeds(seed, pair)`, so the same call gives
the same result. An odd `episodes` leaves A one extra game in seat 0.

`MatchResult` counts, per policy: wins, losses and draws (their sum is always `games`), ring-outs
and KOs it scored (the opponent lost a stock by falling / by health 0), damage dealt (health
points) and hits landed; `mean_length` is in env steps. `EpisodeRecord` is one game, with its
actions (and observations, frames) when asked: a replay (`vooga_env.tools.replay`) is made from one.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from vooga_env.envs.parallel import parallel_env
from vooga_env.game.config import FightConfig
from vooga_env.game.outcome import Outcome
from vooga_env.policies import Policy, make_policy

WILSON_Z95 = 1.959963984540054
"""The standard normal quantile for a two-sided 95% interval."""


def episode_seeds(seed: int, pair: int) -> tuple[int, int, int]:
    """The env seed and the two policies' seeds (A's, B's) of game pair `pair` of a match."""
    if isinstance(seed, bool) or not isinstance(seed, (int, np.integer)) or seed < 0:
        raise ValueError(f"seed must be a non-negative int, got {seed!r}")
    env_seed, seed_a, seed_b = np.random.SeedSequence([int(seed), pair]).generate_state(3)
    return int(env_seed), int(seed_a), int(seed_b)


@dataclass
class EpisodeRecord:
    """One game, seen from the seats: index 0 is `fighter_0`, index 1 is `fighter_1`.

    `ring_outs[i]` / `knock_outs[i]`: stocks fighter i lost by falling / by health 0.
    `damage_dealt[i]`: health points fighter i took off the other. `health`, `stocks` and
    `positions` (top-left x, y in px) are the final state. `winner` is "fighter_0", "fighter_1" or
    "draw", or None when the episode was stopped before its end. `actions[t]` is the pair of
    actions of step t; `observations[t]` the (2, 41) observations before step t (the last one:
    after the last step). `ended_by` is how the game ended: "ring_out" or "ko" (the last stock
    lost by falling / by health 0) or "time". `step_hits[t]`, kept with the observations, is
    each seat's hits landed (not blocked) on step t.
    """

    seed: int
    names: tuple[str, str]
    policy_seeds: tuple[int | None, int | None] = (None, None)
    steps: int = 0
    winner: str | None = None
    ring_outs: list[int] = field(default_factory=lambda: [0, 0])
    knock_outs: list[int] = field(default_factory=lambda: [0, 0])
    damage_dealt: list[float] = field(default_factory=lambda: [0.0, 0.0])
    hits_landed: list[int] = field(default_factory=lambda: [0, 0])
    health: list[float] = field(default_factory=lambda: [0.0, 0.0])
    stocks: list[int] = field(default_factory=lambda: [0, 0])
    positions: list[list[float]] = field(default_factory=lambda: [[0.0, 0.0], [0.0, 0.0]])
    actions: list[tuple[int, int]] | None = None
    observations: list[np.ndarray] | None = None
    frames: list[np.ndarray] | None = None
    ended_by: str | None = None
    step_hits: list[tuple[int, int]] | None = None

    @property
    def finished(self) -> bool:
        return self.winner is not None

    def outcome(self, seat: int) -> str:
        """The outcome for the fighter in `seat`: "win", "loss" or "draw"."""
        if self.winner is None:
            raise ValueError("the episode was stopped before its end; it has no outcome")
        return Outcome.from_info(self.winner).for_seat(seat)

    def add_step(self, actions: tuple[int, int], infos: dict[str, dict[str, Any]]) -> None:
        """Count one env step's actions and events (infos keyed by agent, as the env gives them)."""
        self.steps += 1
        if self.actions is not None:
            self.actions.append(actions)
        for seat in (0, 1):
            info = infos[f"fighter_{seat}"]
            self.ring_outs[seat] += int(info["rung_out"])
            self.knock_outs[seat] += int(info["knocked_out"])
            self.damage_dealt[seat] += float(info["damage_dealt"])
            self.hits_landed[seat] += int(info["hits_landed"])
            if "winner" in info:
                self.winner = info["winner"]
        if self.step_hits is not None:
            self.step_hits.append(tuple(int(infos[f"fighter_{s}"]["hits_landed"]) for s in (0, 1)))
        if self.winner is not None and self.ended_by is None:
            self.ended_by = _ending(infos)

    def close(self, env: Any) -> None:
        """Read the final health, stocks and positions off the env."""
        for seat, status in enumerate(env.fighter_status()):
            self.health[seat] = float(status["health"])
            self.stocks[seat] = int(status["stocks"])
            self.positions[seat] = [float(status["x"]), float(status["y"])]


def _ending(infos: dict[str, dict[str, Any]]) -> str:
    """How a game's last step ended it: a stock lost by a ring-out or a KO, else the clock."""
    last = [infos[f"fighter_{seat}"] for seat in (0, 1)]
    if any(info["rung_out"] for info in last):
        return "ring_out"
    if any(info["knocked_out"] for info in last):
        return "ko"
    return "time"


def capture_frame(env: Any) -> np.ndarray:
    """The env's current picture as an HxWx3 uint8 array, in `rgb_array` or `human` mode."""
    if env.render_mode == "rgb_array":
        return env.render()
    import pygame

    surface = pygame.display.get_surface()
    return np.ascontiguousarray(pygame.surfarray.array3d(surface).transpose(1, 0, 2))


def play_episode(
    env: Any,
    policies: Sequence[Policy],
    seed: int,
    policy_seeds: Sequence[int | None] = (None, None),
    record_actions: bool = False,
    record_observations: bool = False,
    record_frames: bool = False,
    step_hook: Callable[[EpisodeRecord], None] | None = None,
) -> EpisodeRecord:
    """Play one game to its end: `policies[i]` is `fighter_i`; each reads its own observation.

    `step_hook(record)` runs after every step (a window's quit button can raise from it).
    """
    agents = env.possible_agents
    names = (policies[0].name, policies[1].name)
    record = EpisodeRecord(seed, names, (policy_seeds[0], policy_seeds[1]))
    record.actions = [] if record_actions else None
    record.observations = [] if record_observations else None
    record.step_hits = [] if record_observations else None
    record.frames = [] if record_frames else None
    for policy, policy_seed in zip(policies, policy_seeds, strict=True):
        policy.reset(policy_seed)
    observations, _ = env.reset(seed=seed)
    while True:
        if record.observations is not None:
            record.observations.append(np.stack([observations[agent] for agent in agents]))
        if record.frames is not None:
            record.frames.append(capture_frame(env))
        if not env.agents:
            break
        actions = (
            int(policies[0].act(observations[agents[0]])),
            int(policies[1].act(observations[agents[1]])),
        )
        observations, _, _, _, infos = env.step(dict(zip(agents, actions, strict=True)))
        record.add_step(actions, infos)
        if step_hook is not None:
            step_hook(record)
    record.close(env)
    return record


@dataclass
class SideStats:
    """One policy's totals over a match (whichever seat it sat in)."""

    name: str
    wins: int = 0
    losses: int = 0
    draws: int = 0
    ring_outs: int = 0
    kos: int = 0
    damage_dealt: float = 0.0
    hits_landed: int = 0

    @property
    def games(self) -> int:
        return self.wins + self.losses + self.draws

    @property
    def mean_damage(self) -> float:
        """Damage dealt per game (health points)."""
        return self.damage_dealt / self.games if self.games else 0.0

    @property
    def win_rate(self) -> float:
        return self.wins / self.games if self.games else 0.0

    @property
    def score(self) -> float:
        """Points per game: 1 a win, 0.5 a draw."""
        return (self.wins + 0.5 * self.draws) / self.games if self.games else 0.0

    def win_rate_interval(self, z: float = WILSON_Z95) -> tuple[float, float]:
        """The Wilson score interval of the win rate (95% by default); draws count as non-wins."""
        return wilson_interval(self.wins, self.games, z)

    def to_dict(self) -> dict[str, Any]:
        low, high = self.win_rate_interval()
        return {
            "name": self.name,
            "games": self.games,
            "wins": self.wins,
            "losses": self.losses,
            "draws": self.draws,
            "ring_outs": self.ring_outs,
            "kos": self.kos,
            "mean_damage": self.mean_damage,
            "hits_landed": self.hits_landed,
            "win_rate": self.win_rate,
            "win_rate_ci95": [low, high],
        }


@dataclass
class MatchResult:
    """A whole match: `sides[0]` is policy A, `sides[1]` policy B; `episodes` in play order."""

    names: tuple[str, str]
    seed: int
    config: FightConfig
    sides: tuple[SideStats, SideStats]
    episodes: list[EpisodeRecord] = field(default_factory=list)
    seats: list[tuple[int, int]] = field(default_factory=list)
    """For each episode, the seat A sat in and the seat B sat in."""

    @property
    def games(self) -> int:
        return len(self.episodes)

    @property
    def mean_length(self) -> float:
        """Mean episode length in env steps."""
        return sum(e.steps for e in self.episodes) / self.games if self.games else 0.0

    def add(self, episode: EpisodeRecord, seats: tuple[int, int]) -> None:
        """Count one finished episode in which side s sat in `seats[s]`."""
        self.episodes.append(episode)
        self.seats.append(seats)
        for side, seat in zip(self.sides, seats, strict=True):
            other = 1 - seat
            outcome = episode.outcome(seat)
            side.wins += outcome == "win"
            side.losses += outcome == "loss"
            side.draws += outcome == "draw"
            side.ring_outs += episode.ring_outs[other]
            side.kos += episode.knock_outs[other]
            side.damage_dealt += episode.damage_dealt[seat]
            side.hits_landed += episode.hits_landed[seat]

    def check(self) -> None:
        """Raise AssertionError unless the table is consistent (both sides, every game counted)."""
        a, b = self.sides
        for side in self.sides:
            assert side.wins + side.losses + side.draws == self.games, side
        assert a.wins == b.losses and a.losses == b.wins and a.draws == b.draws, (a, b)

    def to_dict(self) -> dict[str, Any]:
        return {
            "names": list(self.names),
            "games": self.games,
            "seed": self.seed,
            "config": self.config.name,
            "max_cycles": self.config.max_cycles,
            "mean_length": self.mean_length,
            "sides": [side.to_dict() for side in self.sides],
        }


def run_match(
    policy_a: Any,
    policy_b: Any,
    episodes: int = 100,
    seed: int = 0,
    config: str | Path | FightConfig = "default",
    render_mode: str | None = None,
    names: tuple[str, str] | None = None,
    record_actions: bool = False,
    record_observations: bool = False,
    record_frames: int = 0,
    progress: Callable[[EpisodeRecord], None] | None = None,
    step_hook: Callable[[EpisodeRecord], None] | None = None,
    **overrides: Any,
) -> MatchResult:
    """Play `episodes` games of A against B, seats swapped each game (see the module docstring).

    `policy_a`, `policy_b`: anything `make_policy` takes (a scripted name, a saved model's path, a
    Policy, a callable, a predict-er). `render_mode="human"` shows every game in a window.
    `record_actions` keeps every game's actions (`record_observations` its observations and
    hits, for `vooga_env.tools.style`); `record_frames=n` keeps the pictures of the first
    n games. `progress(record)` runs after each game; `step_hook(record)` after each step.
    Config overrides (`max_cycles=200`, ...) go to the env.
    """
    _check_arguments(episodes, seed, names, record_frames, progress, step_hook)
    policies = (make_policy(policy_a), make_policy(policy_b))
    if policies[0] is policies[1]:
        raise ValueError("the two sides need two policy objects (the same one was given twice)")
    names = names or (policies[0].name, policies[1].name)
    if render_mode is None and record_frames > 0:
        render_mode = "rgb_array"
    env = parallel_env(config=config, render_mode=render_mode, **overrides)
    result = MatchResult(names, seed, env.config, (SideStats(names[0]), SideStats(names[1])))
    try:
        for game in range(episodes):
            env_seed, seed_a, seed_b = episode_seeds(seed, game // 2)
            seats = (0, 1) if game % 2 == 0 else (1, 0)
            in_seat = [policies[0], policies[1]] if seats == (0, 1) else [policies[1], policies[0]]
            seat_seeds = (seed_a, seed_b) if seats == (0, 1) else (seed_b, seed_a)
            record = play_episode(
                env,
                in_seat,
                env_seed,
                seat_seeds,
                record_actions=record_actions,
                record_observations=record_observations,
                record_frames=game < record_frames,
                step_hook=step_hook,
            )
            record.names = (names[0], names[1]) if seats == (0, 1) else (names[1], names[0])
            result.add(record, seats)
            if progress is not None:
                progress(record)
    finally:
        env.close()
    return result


def _check_arguments(
    episodes: Any, seed: Any, names: Any, record_frames: Any, progress: Any, step_hook: Any
) -> None:
    """run_match's own arguments, checked before any game starts."""
    for name, value, low in (
        ("episodes", episodes, 1),
        ("seed", seed, 0),
        ("record_frames", record_frames, 0),
    ):
        if (
            isinstance(value, (bool, np.bool_))
            or not isinstance(value, (int, np.integer))
            or value < low
        ):
            raise ValueError(f"{name} must be an int >= {low}, got {value!r}")
    if names is not None and (
        not isinstance(names, (tuple, list))
        or len(names) != 2
        or not all(isinstance(n, str) for n in names)
    ):
        raise TypeError(f"names must be None or two strings (A's, B's), got {names!r}")
    for name, hook in (("progress", progress), ("step_hook", step_hook)):
        if hook is not None and not callable(hook):
            raise TypeError(
                f"{name} must be None or a callable taking an EpisodeRecord, got {hook!r}"
            )


def wilson_interval(successes: int, trials: int, z: float = WILSON_Z95) -> tuple[float, float]:
    """The Wilson score interval for a binomial proportion; (0, 1) when there are no trials."""
    if trials < 0 or not 0 <= successes <= trials:
        raise ValueError(f"need 0 <= successes <= trials, got {successes} of {trials}")
    if trials == 0:
        return 0.0, 1.0
    p = successes / trials
    denominator = 1.0 + z * z / trials
    centre = (p + z * z / (2 * trials)) / denominator
    half = z * math.sqrt(p * (1 - p) / trials + z * z / (4 * trials * trials)) / denominator
    low = 0.0 if successes == 0 else max(0.0, centre - half)
    high = 1.0 if successes == trials else min(1.0, centre + half)
    return low, high
