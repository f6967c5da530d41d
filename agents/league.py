"""Train a fighter in a league: PPO against its snapshots, scripted fighters and exploiters.

Each game's opponent is drawn from the pool by PFSP (harder opponents more often).

    python -m agents.league [--config default] [--out runs/NAME] [--seed N] [--minutes M]
    python -m agents.league --config smoke --out /tmp/league  # seconds
    python -m agents.league --init runs/default/final.zip     # start from a trained model

Config-driven (`configs/league/*.toml`; `[ppo]` as in agents.train, `[league]` below). The learner
sits in seat i % 2 of fight i of `fights` batched fights (`FightVecEnv`, `seat="alternate"`: both
seats in every rollout, whatever the engine does in seat order); fight i's opponent is
`PoolOpponent.assigned[i]`, drawn again from the pool at the end of each game
(`agents.league_pool`: harder opponents more often). Every `save_steps` a snapshot of the learner
joins the pool (the last `window` stay); every `exploiter_every` steps (0: never) an exploiter
trains `exploiter_steps` steps against the frozen learner alone (`agents.league_exploiter`) and
joins the pool (the last `exploiters` stay), starting from a new network, the last exploiter or the
learner (`exploiter_start`); with `exploiter_parallel` it trains in a second process while the
learner goes on, and joins at the next mark. With `join_win_rate` the scripted fighters join one at
a time, weak to strong; with `styles`, that many random-style opponents play from the start, each
drawing a new style once the learner beats it (vooga_env.policies.random_styles); with
`self_play`, the learner's current weights play as one more member ("self"); with
`probe_games`, PFSP weighs an exploiter (with `probe_scripted`, a scripted fighter too) by the
lower of the learner's sampled score and its argmax score in probe games at every snapshot;
with `lead_reward` the learner is paid a little on every step it leads (agents.lead_reward).
With `leagues` > 1, that many leagues train side by side, one process each, and the best final
model is shipped (agents.league_population), each first screened by a fresh exploiter with
`screen_steps`.
Checkpoints, `--resume`, Ctrl-C and `OUT/final.zip` work as in agents.train; the learner's Elo, the
pool's size and the PFSP win rates are logged (TensorBoard when installed).
"""

from __future__ import annotations

import argparse
import importlib.util
import json
import sys
from dataclasses import dataclass, replace
from pathlib import Path
from typing import Any

import numpy as np
import torch
from stable_baselines3 import PPO
from stable_baselines3.common.callbacks import BaseCallback
from stable_baselines3.common.utils import set_random_seed
from stable_baselines3.common.vec_env import VecNormalize

from vooga_env.envs.sb3 import FightVecEnv
from vooga_env.game.config import CONFIG_DIR, ConfigError, build_config, load_config, read_toml
from vooga_env.policies import SCRIPTED
from vooga_env.policies.batched import VectorOpponent
from vooga_env.policies.models import frozen_batch, load_model
from vooga_env.policies.random_styles import RandomStyles
from vooga_env.tools.elo import SCORES
from vooga_env.tools.files import atomic_write

from . import common
from .checkpoints import (
    STATE_FILE,
    BrokenRun,
    Diverged,
    RunLock,
    RunLocked,
    holds_run,
    resume_state,
    start_fresh,
)
from .exploiter_loss import ExploiterLoss
from .lead_reward import LeadReward
from .league_exploiter import ExploiterJob, ExploiterWorker, train_exploiter
from .league_pool import WEIGHTINGS, CurrentSelf, Pool, PoolOpponent, Slipping
from .league_population import (
    LeagueFailed,
    league_folder,
    run_leagues,
    screen_leagues,
    ship_best_league,
)
from .league_select import PLAYS, SELECTION_FILE, league_opponents, outcomes_against, ship_best
from .train import learn_and_save, load_init, policy_class, start_from
from .train_config import PPOConfig

EXPLOITER_PLAYS = ("sampled", "argmax", "alternate")
# The learner's play against a kind of member: its argmax in every n-th fight (0: none).
ARGMAX_EVERY = {"sampled": 0, "argmax": 1, "half": 2, "quarter": 4}
EXPLOITER_STARTS = ("new", "last", "lines", "learner")


@dataclass(frozen=True)
class LeagueConfig:
    """The pool: snapshots, scripted fighters, exploiters, and how opponents are drawn."""

    save_steps: int = 200_000
    window: int = 8  # snapshots kept in the pool
    results_window: int = 100  # the last games against a member that give its win rate
    pfsp: str = "squared"
    floor: float = 0.05
    scripted: tuple[str, ...] = tuple(name for name in SCRIPTED if name != "idle")
    exploiter_every: int = 0
    exploiter_steps: int = 200_000
    exploiters: int = 2  # exploiters kept in the pool
    # How the frozen learner plays while an exploiter trains against it: "argmax", "sampled" (as
    # it plays in training), or "alternate" (argmax first, then turn about).
    exploiter_play: str = "argmax"
    # Train each exploiter in a second process (the other core) while the learner trains on; it
    # joins the pool at the next mark.
    exploiter_parallel: bool = False
    # What each exploiter starts from: "new" (a new network, which looks for the learner's holes
    # afresh), "last" (the last exploiter: a line that has trained all the league long against
    # the learner's past selves), "lines" (two such lines, taking turns: each exploiter goes on
    # from the one made two marks before, the first two from new networks) or "learner" (the
    # learner's weights at its mark: it fights as well as the learner from its first step).
    exploiter_start: str = "new"
    # How exploiters play once in the pool: "sampled" (as snapshots do) or "argmax" (as a
    # measuring exploiter is judged).
    exploiter_pool_play: str = "sampled"
    # 0: every scripted fighter is in the pool from the start. Above 0: they join one at a time,
    # in the order of `scripted`, the next once the learner's mean score over the scripted
    # members present (a full `results_window` of games each) reaches this.
    join_win_rate: float = 0.0
    # Above 0: at the end, the last `window` snapshots and the final model each play this many
    # games (even: half in each seat) against every scripted fighter and exploiter, sampled and
    # argmax, and the one with the best worst score (won against a scripted fighter, not lost
    # against an exploiter) is shipped (agents.league_select).
    select_games: int = 0
    # Above 0: the learner gains this on every step it leads (more stocks, then more health) and
    # loses it on every step it trails (agents.lead_reward; training only).
    lead_reward: float = 0.0
    # Above 0: the learner loses this much more at the end of every game it loses to an exploiter
    # of its pool (agents.exploiter_loss; training only).
    exploiter_loss: float = 0.0
    # How the learner plays its training games against the exploiters of its pool: "sampled"
    # (as against everyone else), "argmax" (as the exploiters trained against it), "half"
    # (argmax in the even-numbered fights, so neither play goes untrained against them) or
    # "quarter" (argmax in every fourth fight).
    against_exploiters: str = "sampled"
    # Likewise against every other member (snapshots, scripted fighters, random styles): only
    # the sampled games train, and a late learner's argmax can walk into shover or its own
    # snapshots for whole games while its sampled play wins with a punch now and then
    # (docs/league.md, "A stalemate only the argmax keeps").
    against_others: str = "sampled"
    # The learner's current weights as a member ("self", sampling, copied in at every rollout),
    # drawn by PFSP like the rest: late in a league the learner beats every other member ~100%
    # and PFSP draws them evenly; against itself it scores about 50% whatever it learns.
    self_play: bool = False
    # Above 0 (even): at every snapshot the learner's argmax plays this many games against each
    # exploiter of the pool, and PFSP weighs an exploiter by the lower of that score and the
    # training games' (played sampling): one that beats the argmax alone is drawn as hard.
    probe_games: int = 0
    # With `probe_games`: the scripted fighters that have joined are probed too, so PFSP draws
    # one more often while the argmax loses to it (a late learner's argmax can stand still
    # against idle or lose shover's while its sampled play wins them all: docs/league.md).
    probe_scripted: bool = False
    # This many random-style opponents in the pool from the start (vooga_env.policies.
    # random_styles); each draws a new style once the learner's score against it reaches
    # `styles_redraw` over a full `results_window`.
    styles: int = 0
    styles_redraw: float = 0.9
    # Above 0: each pooled snapshot's every action is replaced by a uniformly random one with
    # this probability (`league_pool.Slipping`). Late in a league the snapshots play close to
    # their argmax; slipping, they lead the learner off their own path (docs/league.md,
    # "Snapshots that slip, and a memory priced").
    snapshot_noise: float = 0.0
    # Above 0, with `leagues` > 1: before the leagues' final models are compared, a fresh
    # exploiter trains this many steps against each one's argmax (one process a league), and
    # every final model meets every league's screen in the comparison (agents.league_population).
    screen_steps: int = 0

    def __post_init__(self) -> None:
        for name in self.scripted:
            if name not in SCRIPTED:
                raise ConfigError(f"scripted = {name!r} is not allowed: one of {list(SCRIPTED)}")
        choices = {
            "pfsp": WEIGHTINGS,
            "exploiter_play": EXPLOITER_PLAYS,
            "exploiter_start": EXPLOITER_STARTS,
            "exploiter_pool_play": tuple(PLAYS),
            "against_exploiters": tuple(ARGMAX_EVERY),
            "against_others": tuple(ARGMAX_EVERY),
        }
        for key, allowed in choices.items():
            if getattr(self, key) not in allowed:
                raise ConfigError(
                    f"{key} = {getattr(self, key)!r} is not allowed: one of {list(allowed)}"
                )
        for key in ("save_steps", "window", "results_window", "exploiter_steps", "exploiters"):
            if getattr(self, key) <= 0:
                raise ConfigError(f"{key} = {getattr(self, key)} is not allowed: must be > 0")
        for key, zero in (("probe_games", "none"), ("select_games", "ship the last model")):
            games = getattr(self, key)
            if games < 0 or games % 2:
                raise ConfigError(
                    f"{key} = {games} is not allowed: an even number >= 0 (0: {zero})"
                )
        if self.exploiter_every < 0:
            raise ConfigError(f"exploiter_every = {self.exploiter_every} is not allowed: >= 0")
        for flag, needed, hint in (
            ("exploiter_parallel", "exploiter_every", ""),
            ("probe_scripted", "probe_games", " (even, e.g. 20)"),
        ):
            if getattr(self, flag) and not getattr(self, needed):
                raise ConfigError(
                    f"{flag} = true is not allowed with {needed} = 0: set {needed} > 0{hint}, "
                    f"or {flag} = false"
                )
        if self.exploiter_start == "lines" and self.exploiters < 2:
            raise ConfigError(
                f"exploiter_start = 'lines' is not allowed with exploiters = {self.exploiters}: "
                "each line goes on from the exploiter two marks back, so keep >= 2"
            )
        if not 0.0 <= self.join_win_rate <= 1.0:
            raise ConfigError(f"join_win_rate = {self.join_win_rate} is not allowed: in [0, 1]")
        if not 0.0 < self.floor <= 1.0:
            raise ConfigError(f"floor = {self.floor} is not allowed: in (0, 1]")
        if self.styles < 0:
            raise ConfigError(f"styles = {self.styles} is not allowed: >= 0 (0: none)")
        if self.screen_steps < 0:
            raise ConfigError(f"screen_steps = {self.screen_steps} is not allowed: >= 0 (0: none)")
        if not 0.0 < self.styles_redraw <= 1.0:
            raise ConfigError(f"styles_redraw = {self.styles_redraw} is not allowed: in (0, 1]")
        if not 0.0 <= self.lead_reward < 1.0:
            raise ConfigError(
                f"lead_reward = {self.lead_reward} is not allowed: in [0, 1) (0: none; "
                "docs/league.md measured 0.005 a step)"
            )
        if not 0.0 <= self.snapshot_noise < 1.0:
            raise ConfigError(
                f"snapshot_noise = {self.snapshot_noise} is not allowed: in [0, 1) (0: none; "
                "docs/league.md measured 0.1)"
            )
        if self.exploiter_loss < 0.0:
            raise ConfigError(
                f"exploiter_loss = {self.exploiter_loss} is not allowed: >= 0 (0: none; "
                "docs/league.md measured 5, a ring-out's worth)"
            )


@dataclass(frozen=True)
class LeagueRunConfig:
    """One league run: the fight, the budget, the batch, PPO and the pool."""

    fight: str = "default"
    total_timesteps: int = 20_000_000
    minutes: float = 0.0  # wall-time budget (0: none)
    fights: int = 128
    seed: int = 0
    checkpoint_every: int = 500_000
    ppo: PPOConfig = PPOConfig()
    league: LeagueConfig = LeagueConfig()
    name: str = "league"
    init: str = ""  # a saved model (.zip) to start from; "": a new network
    # Above 1: this many leagues, one process each (seed, seed + 1, ...), the best final model
    # over `select_games` games shipped (agents.league_population).
    leagues: int = 1

    def __post_init__(self) -> None:
        for key in ("total_timesteps", "fights", "checkpoint_every", "leagues"):
            if getattr(self, key) <= 0:
                raise ConfigError(f"{key} = {getattr(self, key)} is not allowed: must be > 0")
        if self.minutes < 0:
            raise ConfigError(f"minutes = {self.minutes} is not allowed: must be >= 0 (0: none)")
        if self.leagues > 1 and not self.league.select_games:
            raise ConfigError(
                f"leagues = {self.leagues} is not allowed with [league] select_games = 0: the "
                "leagues' final models are compared over select_games games (set it > 0, e.g. 40)"
            )
        for key in ("against_exploiters", "against_others"):
            if getattr(self.league, key) != "sampled" and self.ppo.frame != "opponent":
                raise ConfigError(
                    f"[league] {key} = {getattr(self.league, key)!r} is not allowed with [ppo] "
                    f'frame = {self.ppo.frame!r}: only the facing learner (frame = "opponent") '
                    "plays it"
                )
        if self.league.screen_steps and self.leagues == 1:
            raise ConfigError(
                f"[league] screen_steps = {self.league.screen_steps} is not allowed with leagues = "
                "1: the screens choose between leagues (set leagues >= 2, or screen_steps = 0)"
            )

    @property
    def exploiter_fights(self) -> int:
        """The batched fights an exploiter (or a screen) trains in: half the learner's."""
        return max(self.fights // 2, 1)


LEAGUE_DIR = CONFIG_DIR / "league"


def load_league_config(config: str | Path, **overrides: Any) -> LeagueRunConfig:
    """A LeagueRunConfig from a name in configs/league/ or a .toml path, plus overrides."""
    data, path = read_toml(config, LEAGUE_DIR, "league config")
    data.update({key: value for key, value in overrides.items() if value is not None})
    return build_config(LeagueRunConfig, data, str(path))


class LeagueCallback(BaseCallback):
    """Records each game against its opponent, draws the next one, adds snapshots and
    exploiters; its `state()` goes into the checkpoints."""

    def __init__(self, config: LeagueRunConfig, folder: Path, state: dict[str, Any]) -> None:
        super().__init__()
        self.config = config
        self.league = config.league
        self.folder = folder
        self.rng = np.random.default_rng([config.seed, 1])
        self.pool = Pool(self.league.results_window, self.league.pfsp, self.league.floor)
        self.pool.ratings.update(state.get("ratings", {}))
        self.pool.probes.update(state.get("probes", {}))
        results = state.get("results", {})
        everyone = len(self.league.scripted) if not self.league.join_win_rate else 1
        self.joined = 0
        for _ in range(state.get("scripted_joined", everyone)):
            self._join_scripted(results)
        self.styles = {}
        for index in range(self.league.styles):
            name = f"styles_{index}"
            # seeded apart from the scripted members (seed + 10 + i) and the other leagues
            self.styles[name] = RandomStyles(config.seed * 1000 + 100 + index)
            if name in state.get("styles", {}):
                self.styles[name].load_state(state["styles"][name])
            self.pool.add(name, self.styles[name], results.get(name))
        self.styles_redrawn = state.get("styles_redrawn", 0)
        self.current_self: CurrentSelf | None = None
        if self.league.self_play:
            self.current_self = CurrentSelf(config.seed * 1000 + 99)
            self.pool.add(CurrentSelf.name, self.current_self, results.get(CurrentSelf.name))
        self.snapshots: list[str] = []
        self.exploiters: list[str] = []
        for kind in ("snapshots", "exploiters"):
            for name in state.get(kind, []):
                self._join(kind, name, results.get(name))
        self.last_save = state.get("last_save", 0)
        self.last_exploiter = state.get("last_exploiter", 0)
        self.exploiters_made = state.get("exploiters_made", 0)
        # each pooled exploiter's best share won against the learner it trained on
        self.exploiter_win_rates: dict[str, float] = state.get("exploiter_win_rates", {})
        self.opponent: PoolOpponent | None = None
        self.worker = ExploiterWorker() if self.league.exploiter_parallel else None
        # the parallel exploiter training now, as `_job`'s arguments (resubmitted on resume)
        self.pending: dict[str, Any] | None = state.get("pending_exploiter")
        if self.worker is not None:
            self.worker.waited = state.get("exploiter_wait_s", 0.0)
            if self.pending:
                self.worker.submit(self._job(**self.pending))

    def attach(self, opponent: PoolOpponent) -> None:
        self.opponent = opponent
        opponent.assigned = [self.pool.draw(self.rng) for _ in opponent.assigned]

    def _join_scripted(self, results: dict[str, list[float]]) -> None:
        """Add the next scripted fighter of `scripted` to the pool."""
        name = self.league.scripted[self.joined]
        member = VectorOpponent(name, self.config.seed + 10 + self.joined)
        self.pool.add(name, member, results.get(name))
        self.joined += 1

    def _ready_for_next(self) -> bool:
        """Whether the learner beats the scripted members present well enough for another."""
        if not self.league.join_win_rate or self.joined == len(self.league.scripted):
            return False
        present = self.league.scripted[: self.joined]
        if any(len(self.pool.results[name]) < self.league.results_window for name in present):
            return False
        mean = np.mean([self.pool.win_rate(name) for name in present])
        return bool(mean >= self.league.join_win_rate)

    def _on_step(self) -> bool:
        for slot in np.flatnonzero(self.locals["dones"]):
            winner = self.locals["infos"][slot].get("winner")
            if winner is not None:
                self.pool.record(self.opponent.assigned[slot], SCORES[winner])
            self.opponent.assigned[slot] = self.pool.draw(self.rng)
        self._redraw_beaten_styles()
        if self._ready_for_next():
            self._join_scripted({})
        if self.num_timesteps - self.last_save >= self.league.save_steps:
            self.snapshot(self.model, self.num_timesteps)
        every = self.league.exploiter_every
        if every and self.num_timesteps - self.last_exploiter >= every:
            self._exploiter()
        self._argmax_rows()
        self.logger.record("league/learner_elo", self.pool.ratings["learner"])
        self.logger.record("league/pool_size", len(self.pool.members))
        self.logger.record("league/scripted_joined", self.joined)
        if self.styles:
            self.logger.record("league/styles_redrawn", self.styles_redrawn)
        if self.worker is not None:
            self.logger.record("league/exploiter_wait_s", self.worker.waited)
        if self.exploiter_win_rates:
            latest = next(reversed(self.exploiter_win_rates.values()))
            self.logger.record("league/exploiter_win_rate", latest)
        if self.pool.probes:
            self.logger.record("league/argmax_probe_min", min(self.pool.probes.values()))
        return True

    def _on_training_start(self) -> None:
        self._argmax_rows()

    def _on_rollout_start(self) -> None:
        if self.current_self is not None:
            self.current_self.refresh(self.model)

    def _argmax_rows(self) -> None:
        """Have the learner take its argmax in the fights `against_exploiters` and
        `against_others` say ("half": the even-numbered ones, "quarter": every fourth), if
        either is set."""
        exploiters, others = self.league.against_exploiters, self.league.against_others
        if exploiters == others == "sampled":
            return
        rows = []
        for row, name in enumerate(self.opponent.assigned):
            play = exploiters if name in self.exploiters else others
            every = ARGMAX_EVERY[play]
            rows.append(every > 0 and row % every == 0)
        self.model.policy.argmax_rows = torch.as_tensor(rows)

    def _redraw_beaten_styles(self) -> None:
        """A random-style member the learner beats often enough plays a new style, its record
        started again."""
        for name, member in self.styles.items():
            results = self.pool.results[name]
            if len(results) == results.maxlen and self.pool.win_rate(name) >= (
                self.league.styles_redraw
            ):
                member.redraw()
                results.clear()
                self.styles_redrawn += 1

    def _join(self, kind: str, name: str, results: list[float] | None = None) -> None:
        """Load a saved snapshot (sampling its actions) or exploiter (`exploiter_pool_play`)
        into the pool."""
        argmax = kind == "exploiters" and PLAYS[self.league.exploiter_pool_play]
        model = load_model(self.folder / kind / f"{name}.zip")
        player = frozen_batch(model, name, argmax, int(self.rng.integers(2**31)))
        if kind == "snapshots" and self.league.snapshot_noise:
            player = Slipping(player, self.league.snapshot_noise, int(self.rng.integers(2**31)))
        self.pool.add(name, player, results)
        kept = getattr(self, kind)
        kept.append(name)
        limit = self.league.window if kind == "snapshots" else self.league.exploiters
        while len(kept) > limit:
            self._leave(kept.pop(0))

    def _leave(self, name: str) -> None:
        self.pool.drop(name)
        if self.opponent is not None:  # its fights take a new opponent now
            self.opponent.assigned = [
                self.pool.draw(self.rng) if member == name else member
                for member in self.opponent.assigned
            ]

    def snapshot(self, model: PPO, steps: int) -> None:
        """Save the learner as it is now and add it to the pool."""
        name = f"snapshot_{steps}"
        (self.folder / "snapshots").mkdir(parents=True, exist_ok=True)
        atomic_write(self.folder / "snapshots" / f"{name}.zip", model.save)
        self._join("snapshots", name)
        self.last_save = steps
        self._probe(model, steps)

    def _probe(self, model: PPO, steps: int) -> None:
        """The learner's argmax against each pooled exploiter (and with `probe_scripted` each
        joined scripted fighter), `probe_games` games each, as the pool's probes (PFSP then draws
        a member that beats the argmax more often)."""
        games = self.league.probe_games
        names = list(self.exploiters)
        if self.league.probe_scripted:
            names += self.league.scripted[: self.joined]
        if not games or not names:
            return
        learner = frozen_batch(model, "learner", True, self.config.seed)
        outcomes = outcomes_against(learner, self.pool, names, games, steps, self.config.fight)
        for name, played in outcomes.items():
            self.pool.probes[name] = float(np.mean([SCORES[outcome] for outcome in played]))

    def exploiter_argmax(self) -> bool:
        """Whether the next exploiter trains against the learner's argmax play, as
        `exploiter_play` says ("alternate": argmax for the first exploiter, sampled next, ...)."""
        play = self.league.exploiter_play
        if play == "alternate":
            play = ("argmax", "sampled")[self.exploiters_made % 2]
        return play == "argmax"

    def _exploiter(self) -> None:
        """Pool an exploiter trained against the learner as it is now; in parallel, pool the one
        trained since the last mark and start the next."""
        if self.worker is not None and self.pending is not None:
            self.worker.collect()
            self._pool_exploiter(f"exploiter_{self.pending['steps']}")
        steps = self.num_timesteps
        (self.folder / "exploiters").mkdir(parents=True, exist_ok=True)
        atomic_write(self.folder / "exploiters" / f"target_{steps}.zip", self.model.save)
        target_seed, seed = (int(self.rng.integers(2**31)) for _ in range(2))
        args = {"steps": steps, "argmax": self.exploiter_argmax(), "init": self._start(steps)}
        job = self._job(**args, target_seed=target_seed, seed=seed)
        if self.worker is None:
            self._pool_exploiter(Path(train_exploiter(job)).stem)
        else:
            self.worker.submit(job)
            self.pending = {**args, "target_seed": target_seed, "seed": seed}
        self.last_exploiter = steps
        self.exploiters_made += 1

    def _pool_exploiter(self, name: str) -> None:
        """Add a trained exploiter to the pool and keep its score against its own target."""
        self._join("exploiters", name)
        result = json.loads((self.folder / "exploiters" / f"{name}.json").read_text())
        self.exploiter_win_rates[name] = result["best_win_rate"]

    def _start(self, steps: int) -> str:
        """The file (in OUT/exploiters) the exploiter made at `steps` starts from; "": a new
        network."""
        start = self.league.exploiter_start
        if start == "learner":
            return f"target_{steps}.zip"  # the learner as it is now
        lines = {"last": 1, "lines": 2}.get(start, 0)  # how many lines take turns
        return f"{self.exploiters[-lines]}.zip" if 0 < lines <= len(self.exploiters) else ""

    def _job(
        self, steps: int, argmax: bool, target_seed: int, seed: int, init: str
    ) -> ExploiterJob:
        """The exploiter job made at `steps` (its files in OUT/exploiters, named by `steps`)."""
        folder = self.folder / "exploiters"
        return ExploiterJob(
            target=str(folder / f"target_{steps}.zip"),
            argmax=argmax,
            target_seed=target_seed,
            seed=seed,
            steps=self.league.exploiter_steps,
            fight=self.config.fight,
            fights=self.config.exploiter_fights,
            out=str(folder / f"exploiter_{steps}.zip"),
            init=str(folder / init) if init else "",
        )

    def close(self) -> None:
        """Stop the exploiters' process, if there is one."""
        if self.worker is not None:
            self.worker.close()

    def state(self) -> dict[str, Any]:
        return {
            **self.pool.state(),
            "snapshots": list(self.snapshots),
            "exploiters": list(self.exploiters),
            "scripted_joined": self.joined,
            "styles": {name: member.state() for name, member in self.styles.items()},
            "styles_redrawn": self.styles_redrawn,
            "last_save": self.last_save,
            "last_exploiter": self.last_exploiter,
            "exploiters_made": self.exploiters_made,
            "exploiter_win_rates": dict(self.exploiter_win_rates),
            "pending_exploiter": self.pending,
            "exploiter_wait_s": self.worker.waited if self.worker is not None else 0.0,
        }


def build(config: LeagueRunConfig, folder: Path, state: dict[str, Any], resume: bool, saved: Any):
    """The envs, the learner (new, from `saved`'s weights, or resumed) and the league callback."""
    league = LeagueCallback(config, folder, state)
    opponent = PoolOpponent(league.pool, config.fights)  # assigned when the pool is full
    envs: Any = FightVecEnv(
        config.fights, load_config(config.fight), opponent=opponent, seat="alternate"
    )
    if config.league.lead_reward:
        envs = LeadReward(envs, config.league.lead_reward)
    if config.league.exploiter_loss:
        envs = ExploiterLoss(envs, config.league.exploiter_loss, opponent, league.exploiters)
    ppo = config.ppo
    if ppo.normalize_reward:
        envs = VecNormalize(envs, norm_obs=False, norm_reward=True, gamma=ppo.gamma)
    if resume:
        if isinstance(envs, VecNormalize) and "normalizer" in state:
            envs = VecNormalize.load(str(folder / state["normalizer"]), envs.venv)
        model = PPO.load(folder / state["checkpoint"], env=envs, device="cpu")
    else:
        tensorboard = str(folder / "tb") if importlib.util.find_spec("tensorboard") else None
        model = PPO(
            policy_class(ppo),
            envs,
            **{key: getattr(ppo, key) for key in _PPO_KEYS},
            policy_kwargs={"net_arch": list(ppo.net_arch)},
            tensorboard_log=tensorboard,
            seed=config.seed,
            device="cpu",
            verbose=0,
        )
        if saved is not None:
            start_from(model, saved)
    common.quiet_logger(model)
    if not league.snapshots:  # the untrained network is the first snapshot
        league.snapshot(model, model.num_timesteps)
    league.attach(opponent)
    return model, league


_PPO_KEYS = (
    "learning_rate",
    "n_steps",
    "batch_size",
    "n_epochs",
    "gamma",
    "gae_lambda",
    "ent_coef",
    "clip_range",
)


def train_league(
    config: LeagueRunConfig,
    folder: Path,
    resume: bool = False,
    progress: bool = True,
    minutes: float | None = None,
    overwrite: bool = False,
) -> Path:
    """Run (or continue) a league for at most `minutes`; returns the final model's path.

    The folder is locked and checkpointed as agents.train does it (`agents.checkpoints`); a
    fresh run refuses a folder that holds one, unless `overwrite`.
    """
    budget = common.budget_minutes(minutes, config.minutes)
    if resume and not folder.is_dir():
        raise FileNotFoundError(f"--resume: no run folder at {folder}")
    saved = None if resume else load_init(config)
    if config.leagues > 1:
        return _train_leagues(config, folder, resume, progress, minutes, overwrite)
    with RunLock(folder):
        state = _prepare(folder, resume, overwrite, config)
        return _run(config, folder, state, saved, progress, budget)


def _train_leagues(
    config: LeagueRunConfig,
    folder: Path,
    resume: bool,
    progress: bool,
    minutes: float | None,
    overwrite: bool,
) -> Path:
    """`config.leagues` leagues side by side in OUT/league_i, then the best final model
    shipped as OUT/final.zip (agents.league_population)."""
    folders = [league_folder(folder, index) for index in range(config.leagues)]
    with RunLock(folder):
        for league in folders:  # every league's folder checked before any process starts
            if resume and not holds_run(league):
                raise FileNotFoundError(f"--resume: no checkpoint in {league}")
            if not resume:
                start_fresh(league, overwrite, config, "league_config.json")
        for stale in (folder / "final.zip", folder / SELECTION_FILE):
            stale.unlink(missing_ok=True)
        one = replace(config, leagues=1, league=replace(config.league, screen_steps=0))
        runs = [
            (replace(one, seed=config.seed + index), league, resume, False, minutes, overwrite)
            for index, league in enumerate(folders)
        ]
        run_leagues(train_league, runs, config.total_timesteps * config.leagues, progress)
        pool = config.league
        if pool.screen_steps:
            screen_leagues(
                folder,
                config.leagues,
                pool.screen_steps,
                config.fight,
                config.exploiter_fights,
                config.seed,
            )
        with common.one_core():
            return ship_best_league(
                folder,
                config.leagues,
                list(pool.scripted),
                PLAYS[pool.exploiter_pool_play],
                pool.select_games,
                config.seed,
                load_config(config.fight),
                screened=bool(pool.screen_steps),
            )


def _prepare(
    folder: Path, resume: bool, overwrite: bool, config: LeagueRunConfig
) -> dict[str, Any]:
    """The committed state to resume from ({} for a fresh run, in an emptied folder if asked)."""
    if resume:
        if not holds_run(folder):
            raise FileNotFoundError(f"--resume: no checkpoint in {folder}")
        return resume_state(folder)
    start_fresh(folder, overwrite, config, "league_config.json")
    return {}


def _run(
    config: LeagueRunConfig,
    folder: Path,
    state: dict[str, Any],
    saved: Any,
    progress: bool,
    minutes: float,
) -> Path:
    set_random_seed(config.seed)
    with common.one_core():
        model, league = build(config, folder, state, bool(state), saved)
        every = max(config.checkpoint_every // config.fights, 1)
        try:
            learn_and_save(model, folder, league, every, config, not state, progress, minutes)
        finally:
            league.close()
        return select(config, folder, league.snapshots, league.exploiters)


def select(
    config: LeagueRunConfig, folder: Path, snapshots: list[str], exploiters: list[str]
) -> Path:
    """final.zip as it is, or with `select_games` the best of it and the pool's `snapshots`
    against the scripted fighters and `exploiters` (agents.league_select)."""
    final = folder / "final.zip"
    games = config.league.select_games
    if not games or not (config.league.scripted or exploiters):
        return final
    argmax = PLAYS[config.league.exploiter_pool_play]
    opponents = league_opponents(folder, list(config.league.scripted), exploiters, argmax)
    candidates = {f"{name}.zip": folder / "snapshots" / f"{name}.zip" for name in snapshots}
    candidates["final.zip"] = final
    fight = load_config(config.fight)
    return ship_best(folder, candidates, opponents, games, config.seed, fight, exploiters)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="vooga-league", description=__doc__.splitlines()[0])
    parser.add_argument("--config", default="default", help="a name in configs/league or a path")
    parser.add_argument("--out", type=Path, help="run folder (default runs/CONFIG)")
    parser.add_argument("--seed", type=int)
    parser.add_argument("--steps", type=int, help="total timesteps (overrides the config)")
    parser.add_argument("--init", help="start from this saved model's weights (overrides)")
    parser.add_argument("--resume", action="store_true", help="continue from OUT/latest.zip")
    parser.add_argument("--overwrite", action="store_true", help="start over in a used OUT")
    parser.add_argument(
        "--minutes", type=common._minutes, help="stop after this much wall time (0: no budget)"
    )
    parser.add_argument("--no-progress", action="store_true", help="no progress bar")
    args = parser.parse_args(argv)
    try:
        config = load_league_config(
            args.config, seed=args.seed, total_timesteps=args.steps, init=args.init
        )
    except ConfigError as error:
        parser.error(str(error))
    folder = args.out or Path("runs") / config.name
    common.stop_on_signals()  # `kill`, a job scheduler: as Ctrl-C, its exploiter ended too
    try:
        final = train_league(
            config, folder, args.resume, not args.no_progress, args.minutes, args.overwrite
        )
    except KeyboardInterrupt:
        latest = folder / ("league_*" if config.leagues > 1 else "") / "latest.zip"
        print(
            f"\ninterrupted: the last checkpoint is {latest}; "
            f"continue with --resume --out {folder}",
            file=sys.stderr,
        )
        return 130
    except (Diverged, LeagueFailed) as error:
        print(f"stopped: {error}", file=sys.stderr)
        return 1
    except (FileNotFoundError, FileExistsError, ConfigError, BrokenRun, RunLocked) as error:
        parser.error(str(error))
    runs = [league_folder(folder, index) for index in range(config.leagues)]
    for run in runs if config.leagues > 1 else [folder]:
        print(f"{run}: {format_pool(json.loads((run / STATE_FILE).read_text()))}")
    if (folder / SELECTION_FILE).is_file():
        print(format_selection(json.loads((folder / SELECTION_FILE).read_text())))
    print(f"trained: {final}")
    return 0


def format_pool(state: dict[str, Any]) -> str:
    """The pool at the end: each member's recent games, the learner's score there, its Elo, for
    an exploiter its own win rate against the learner it trained on and, for a probed member
    (`probe_games`, `probe_scripted`), the learner's argmax score in the last probe."""
    rows = []
    own, probes = state.get("exploiter_win_rates", {}), state.get("probes", {})
    for name, results in state["results"].items():
        score = 100.0 * sum(results) / len(results) if results else "-"
        won = 100.0 * own[name] if name in own else "-"
        probe = 100.0 * probes[name] if name in probes else "-"
        rows.append((name, len(results), score, state["ratings"].get(name, 0.0), won, probe))
    learner = state["ratings"]["learner"]
    header = (
        "opponent",
        "recent games",
        "learner score %",
        "Elo",
        "won vs its target %",
        "argmax probe %",
    )
    return "\n\n".join(
        [
            f"the pool after {state['num_timesteps']} steps (learner Elo {learner:.0f})",
            common.table(header, rows),
        ]
    )


def format_selection(selection: dict[str, Any]) -> str:
    """Each candidate's worst and mean score over the selection's games (won against a scripted
    fighter, not lost against an exploiter), and the one shipped."""
    rows = [
        (name, 100.0 * row["worst"], 100.0 * row["mean"])
        for name, row in selection["candidates"].items()
    ]
    return "\n\n".join(
        [
            f"shipped {selection['chosen']} as final.zip ({selection['games']} games against each"
            " scripted fighter and exploiter, sampled and argmax)",
            common.table(("candidate", "worst score %", "mean score %"), rows),
        ]
    )


if __name__ == "__main__":
    raise SystemExit(main())
