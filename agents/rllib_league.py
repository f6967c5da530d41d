"""The self-play league on RLlib: who `main` meets each episode, and how it fares against whom.

The pool is the scripted fighters (non-learning `ScriptedModule`s) plus frozen snapshots of
`main` (`main_v1`, `main_v2`, ..., copies added with `Algorithm.add_module`). The env runners
draw each episode's opponent in the policy-mapping function (`LeagueMapping`) with weights the
driver recomputes every iteration from the tracked win rates and pushes to them; an episode-end
callback (`LeagueCallbacks`) reports the result of every game to the driver through RLlib's
metrics. Ratings use the Elo constants of `vooga_env.tools.elo`.
"""

from __future__ import annotations

import math
import zlib
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from ray.rllib.callbacks.callbacks import RLlibCallback

from vooga_env.envs.parallel import AGENTS
from vooga_env.tools.elo import K_FACTOR, START_RATING, expected_score

from .rllib_config import LeagueConfig

MAIN = "main"
"""The module that learns."""
FLOOR = 0.05
"""Every pool member keeps at least this (unnormalized) weight, so none is forgotten."""
DRAW = "league_draw"
"""The episode's `custom_data` key of its draw: (env runner, vector index, episode number)."""


@dataclass(frozen=True)
class LeagueMapping:
    """The agent-to-module mapping: `main` takes a seat drawn per episode, the other seat goes
    to a pool member drawn with `weights`. Both agents of an episode map from the same draw,
    seeded by the run's seed and the episode's `DRAW` key (set by `LeagueCallbacks`), so they
    always agree and a run with the same seed draws the same; picklable, to ship to env
    runners."""

    pool: tuple[str, ...]
    weights: tuple[float, ...]
    seed: int = 0

    def __call__(self, agent_id: str, episode: Any, **kwargs: Any) -> str:
        rng = np.random.default_rng([self.seed, *self.key(episode)])
        main_seat = int(rng.integers(2))
        if agent_id == AGENTS[main_seat]:
            return MAIN
        return self.pool[int(rng.choice(len(self.pool), p=self.weights))]

    @staticmethod
    def key(episode: Any) -> tuple[int, ...]:
        """The episode's draw key; without one, its id (a random uuid). RLlib asks for a
        mapping it then discards while it cuts an episode, before the episode has `custom_data`
        (`MultiAgentEpisode.__init__` evaluates `agent_module_ids.get(agent, mapping(...))`)."""
        key = getattr(episode, "custom_data", {}).get(DRAW)
        return tuple(key) if key is not None else (zlib.crc32(str(episode.id_).encode()),)


class LeagueCallbacks(RLlibCallback):
    """Logs, per opponent, the games `main` played and the points it scored (win 1, draw 0.5),
    and, per Ray node, the env steps its env runners sampled (where did the sampling happen?)."""

    def __init__(self) -> None:
        super().__init__()
        self.episodes: dict[int, int] = {}  # per vector index: episodes begun (one env runner)

    def on_episode_created(
        self, *, episode: Any, env_runner: Any = None, env_index: int = 0, **kwargs: Any
    ) -> None:
        """Key the episode's opponent draw by where and when it began instead of its id (a
        uuid4, another in every run), so that a run with the same seed draws the same."""
        number = self.episodes.get(env_index, 0)
        self.episodes[env_index] = number + 1
        runner = int(getattr(env_runner, "worker_index", 0) or 0)
        episode.custom_data[DRAW] = (runner, env_index, number)

    def on_sample_end(self, *, samples: Any, metrics_logger: Any = None, **kwargs: Any) -> None:
        import ray

        if metrics_logger is None or not ray.is_initialized():
            return
        steps = sum(episode.env_steps() for episode in samples)
        node = ray.get_runtime_context().get_node_id()
        metrics_logger.log_value(("nodes", node), steps, reduce="sum")

    def on_episode_end(self, *, episode: Any, metrics_logger: Any = None, **kwargs: Any) -> None:
        modules = {agent: episode.module_for(agent) for agent in AGENTS}
        if MAIN not in modules.values() or metrics_logger is None:
            return
        main_agent = next(agent for agent, module in modules.items() if module == MAIN)
        opponent = modules[AGENTS[1 - AGENTS.index(main_agent)]]
        last = episode.get_infos(-1)
        winner = next((info["winner"] for info in last.values() if "winner" in info), "draw")
        score = 1.0 if winner == main_agent else 0.5 if winner == "draw" else 0.0
        metrics_logger.log_value(("league", opponent, "games"), 1, reduce="sum")
        metrics_logger.log_value(("league", opponent, "points"), score, reduce="sum")


@dataclass
class League:
    """The pool, each member's tracked win rate (main's score rate against it) and Elo."""

    config: LeagueConfig
    snapshots: list[str] = field(default_factory=list)
    retired: list[str] = field(default_factory=list)
    win_rates: dict[str, float] = field(default_factory=dict)
    ratings: dict[str, float] = field(default_factory=lambda: {MAIN: START_RATING})
    games: dict[str, int] = field(default_factory=dict)
    versions: int = 0

    @property
    def pool(self) -> tuple[str, ...]:
        return (*self.config.scripted, *self.snapshots)

    def mapping(self, seed: int) -> LeagueMapping:
        """The mapping function that draws opponents as the current win rates say."""
        pool = self.pool
        hardness = [(1.0 - self.win_rates.get(m, 0.5)) ** self.config.pfsp_power for m in pool]
        weights = np.asarray(hardness) + FLOOR
        return LeagueMapping(pool, tuple(float(w) for w in weights / weights.sum()), seed)

    def new_snapshot(self) -> str:
        """The id of the next snapshot of `main`; the oldest beyond the window retires (it
        leaves the pool but stays loaded: an episode begun before may still be mapped to it)."""
        self.versions += 1
        module_id = f"{MAIN}_v{self.versions}"
        self.snapshots.append(module_id)
        self.win_rates[module_id] = 0.5
        self.ratings[module_id] = self.ratings[MAIN]
        if len(self.snapshots) > self.config.window:
            self.retired.append(self.snapshots.pop(0))
        return module_id

    def record(self, results: dict[str, Any]) -> None:
        """Fold one iteration's games (`{opponent: {"games": n, "points": p}}`) into the win
        rates and Elo ratings (one batched Elo update per opponent and iteration)."""
        decay = self.config.win_rate_decay
        for opponent, counts in results.items():
            games, points = float(counts.get("games", 0)), float(counts.get("points", 0.0))
            # `not games > 0`: after a resume RLlib reports NaN for keys of the last session
            if not games > 0 or not math.isfinite(points) or opponent not in self.pool:
                continue
            previous = self.win_rates.get(opponent, 0.5)
            self.win_rates[opponent] = decay * previous + (1.0 - decay) * points / games
            self.games[opponent] = self.games.get(opponent, 0) + int(games)
            rating = self.ratings.setdefault(opponent, START_RATING)
            change = K_FACTOR * (points - games * expected_score(self.ratings[MAIN], rating))
            self.ratings[MAIN] += change
            self.ratings[opponent] = rating - change

    def to_dict(self) -> dict[str, Any]:
        return {
            "snapshots": self.snapshots,
            "retired": self.retired,
            "win_rates": self.win_rates,
            "ratings": self.ratings,
            "games": self.games,
            "versions": self.versions,
        }

    @classmethod
    def from_dict(cls, config: LeagueConfig, data: dict[str, Any]) -> League:
        return cls(config, **{key: data[key] for key in cls(config).to_dict()})
