"""The game of `agents.play` as a state machine, one frame at a time, with no window in it.

A match is best of `rounds` rounds; each round is one env episode (one replay). Each round opens
with a countdown, is fought a step per frame, and ends on a result screen; the last round's
screen is the match's. `Game.frame(events, elapsed_ms)` takes that frame's pygame events and the
milliseconds since the last one, so a test drives the whole game with a scripted key source and
a fake clock; `run` is the loop that feeds it a window's events and a real clock.
"""

from __future__ import annotations

import enum
import math
from collections.abc import Callable, Iterable
from dataclasses import dataclass, field
from typing import Any, Protocol

import pygame

from vooga_env.policies import Policy
from vooga_env.tools.match import EpisodeRecord, episode_seeds

from .play_keys import FIGHT_KEYS, NEXT_KEYS, PAUSE_KEYS, QUIT_KEYS, RESTART_KEYS, InputHandler

SPEED_RANGE = (0.5, 2.0)
"""The allowed `speed`: a multiple of the env's render_fps (env steps per second)."""


class Phase(enum.Enum):
    COUNTDOWN = "countdown"
    FIGHT = "fight"
    ROUND_OVER = "round over"
    MATCH_OVER = "match over"
    QUIT = "quit"


@dataclass(frozen=True)
class PlaySettings:
    """How the person plays: `seat` 0 (red, left) or 1 (blue, right); a match is best of `rounds`;
    `speed` times the env's render_fps; `seed` seeds every round (spawn jitter, the opponent).

    `countdown_ms` of countdown open each round; result screens ignore keys for `lockout_ms`, so
    that a key mashed as the round ends does not skip its result.
    """

    seat: int = 0
    rounds: int = 1
    speed: float = 1.0
    seed: int = 0
    countdown_ms: float = 3000.0
    lockout_ms: float = 800.0

    def __post_init__(self) -> None:
        if self.seat not in (0, 1) or isinstance(self.seat, bool):
            raise ValueError(f"seat must be 0 or 1, got {self.seat!r}")
        if isinstance(self.rounds, bool) or not isinstance(self.rounds, int) or self.rounds < 1:
            raise ValueError(f"rounds must be a positive int, got {self.rounds!r}")
        check_speed(self.speed)
        if isinstance(self.seed, bool) or not isinstance(self.seed, int) or self.seed < 0:
            raise ValueError(f"seed must be a non-negative int, got {self.seed!r}")
        for name in ("countdown_ms", "lockout_ms"):
            if not getattr(self, name) >= 0:
                raise ValueError(f"{name} must be >= 0, got {getattr(self, name)!r}")

    @property
    def wins_needed(self) -> int:
        """Round wins that take the match: a majority of `rounds`."""
        return self.rounds // 2 + 1


def check_speed(speed: Any) -> float:
    """`speed` as a float, or a ValueError naming it and the allowed range."""
    low, high = SPEED_RANGE
    if isinstance(speed, bool) or not isinstance(speed, (int, float)) or not low <= speed <= high:
        raise ValueError(
            f"speed must be a number in {low}..{high} (times render_fps), got {speed!r}"
        )
    return float(speed)


@dataclass
class RoundResult:
    """One finished round, from the person's side: `outcome` "win", "loss" or "draw"; `how` it
    ended: "ring-out" or "KO" (the loser's last stock), or "time up, more stocks" / "time up,
    more health" (the winner's lead) / "time up, level"."""

    number: int
    outcome: str
    how: str
    steps: int


@dataclass
class MatchScore:
    """Round wins of the person and of the opponent, and drawn rounds, in one match."""

    number: int
    rounds: list[RoundResult] = field(default_factory=list)

    def count(self, outcome: str) -> int:
        return sum(result.outcome == outcome for result in self.rounds)

    @property
    def outcome(self) -> str:
        """The match's outcome for the person (more round wins), "win", "loss" or "draw"."""
        wins, losses = self.count("win"), self.count("loss")
        return "draw" if wins == losses else ("win" if wins > losses else "loss")


class Clock(Protocol):
    """What `run` needs of pygame.time.Clock: wait for the next frame, return the ms it took."""

    def tick(self, framerate: float = 0) -> int: ...


RoundHook = Callable[[EpisodeRecord, "Game"], Any]


class Game:
    """The person (keyboard, in `settings.seat`) against `opponent` on `env`, a frame at a time.

    `env` is a FightParallelEnv (any config). `on_round_end(record, game)` runs as each round ends
    or is cut short (restart, quit) with at least one step played; what it returns (the saved
    replay's path) is kept as `last_saved`. `opponent_name` labels the opponent on screen.
    """

    def __init__(
        self,
        env: Any,
        opponent: Policy,
        settings: PlaySettings | None = None,
        on_round_end: RoundHook | None = None,
        opponent_name: str | None = None,
    ) -> None:
        self.env = env
        self.opponent = opponent
        self.settings = settings or PlaySettings()
        self.on_round_end = on_round_end
        self.opponent_name = opponent_name or opponent.name
        self.keys = InputHandler(self.settings.seat)
        self.fps = env.metadata["render_fps"] * self.settings.speed
        """Frames (env steps) per second of the fight."""
        self.help_visible = True
        self.paused = False
        self.games = 0
        """Rounds started this session; round k is seeded by `episode_seeds(seed, k)`."""
        self.matches: list[MatchScore] = []
        self.last_saved: Any = None
        self.phase = Phase.COUNTDOWN
        self.phase_ms = 0.0
        self._last_infos: dict[str, dict[str, Any]] = {}
        self.new_match()

    @property
    def match(self) -> MatchScore:
        return self.matches[-1]

    @property
    def round_number(self) -> int:
        """The round on screen (1-based) of the match."""
        return len(self.match.rounds) + (self.phase in (Phase.COUNTDOWN, Phase.FIGHT))

    @property
    def accepts_keys(self) -> bool:
        """Whether a result screen is past its lockout and takes R / Enter."""
        return self.phase_ms >= self.settings.lockout_ms

    def new_match(self) -> None:
        """Start a new match (score 0-0) at its first round's countdown."""
        self.matches.append(MatchScore(len(self.matches) + 1))
        self._start_round()

    def frame(self, events: Iterable[Any], elapsed_ms: float) -> None:
        """Handle this frame's events, then advance: count down, fight one step, or wait."""
        for event in events:
            self.handle(event)
            if self.phase is Phase.QUIT:
                return
        if self.paused:
            return
        self.phase_ms += elapsed_ms
        if self.phase is Phase.COUNTDOWN and self.phase_ms >= self.settings.countdown_ms:
            self._enter(Phase.FIGHT)
        elif self.phase is Phase.FIGHT:
            self._step()

    def handle(self, event: Any) -> None:
        """One pygame event: held keys, then the controls of the phase."""
        self.keys.handle(event)
        fighting = self.phase in (Phase.COUNTDOWN, Phase.FIGHT)
        if event.type == pygame.QUIT:
            self.quit()
        elif event.type == pygame.WINDOWFOCUSLOST and fighting:
            self.paused = True
        elif event.type == pygame.KEYDOWN:
            self._key(event.key, fighting)

    def quit(self) -> None:
        """Stop: a round cut short still reaches `on_round_end`."""
        self._cut_short()
        self._enter(Phase.QUIT)

    def _key(self, key: int, fighting: bool) -> None:
        if key in FIGHT_KEYS and fighting and not self.paused:
            self.help_visible = False
        if key in QUIT_KEYS:
            self.quit()
        elif key in PAUSE_KEYS and fighting:
            self.paused = not self.paused
        elif key in RESTART_KEYS and (self.paused or (not fighting and self.accepts_keys)):
            self._cut_short()
            self.paused = False
            self.new_match()
        elif key in NEXT_KEYS and self.accepts_keys:
            if self.phase is Phase.ROUND_OVER:
                self._start_round()
            elif self.phase is Phase.MATCH_OVER:
                self.new_match()

    def _enter(self, phase: Phase) -> None:
        self.phase = phase
        self.phase_ms = 0.0

    def _start_round(self) -> None:
        seat = self.settings.seat
        env_seed, _, opponent_seed = episode_seeds(self.settings.seed, self.games)
        self.games += 1
        names = ("human", self.opponent.name) if seat == 0 else (self.opponent.name, "human")
        seeds = (None, opponent_seed) if seat == 0 else (opponent_seed, None)
        self.record = EpisodeRecord(env_seed, names, seeds, actions=[])
        self.opponent.reset(opponent_seed)
        self.observations, _ = self.env.reset(seed=env_seed)
        self._enter(Phase.COUNTDOWN)

    def _step(self) -> None:
        seat, agents = self.settings.seat, self.env.possible_agents
        mine = int(self.keys.action())
        theirs = int(self.opponent.act(self.observations[agents[1 - seat]]))
        actions = (mine, theirs) if seat == 0 else (theirs, mine)
        self.observations, _, _, _, infos = self.env.step(dict(zip(agents, actions)))
        self.record.add_step(actions, infos)
        self._last_infos = infos
        if not self.env.agents:
            self._end_round()

    def _end_round(self) -> None:
        record = self.record
        record.close(self.env)
        outcome = record.outcome(self.settings.seat)
        loser = {"win": 1 - self.settings.seat, "loss": self.settings.seat}.get(outcome)
        if loser is None:
            how = "time up, level"
        elif record.stocks[loser] == 0:
            info = self._last_infos[f"fighter_{loser}"]
            how = "ring-out" if info["rung_out"] else "KO"
        else:
            how = "time up, " + (
                "more stocks" if record.stocks[0] != record.stocks[1] else "more health"
            )
        match = self.match
        match.rounds.append(RoundResult(len(match.rounds) + 1, outcome, how, self.record.steps))
        self._report()
        decided = max(match.count("win"), match.count("loss")) >= self.settings.wins_needed
        over = decided or len(match.rounds) >= self.settings.rounds
        self._enter(Phase.MATCH_OVER if over else Phase.ROUND_OVER)

    def _cut_short(self) -> None:
        if self.phase is Phase.FIGHT and self.record.steps > 0:
            self.record.close(self.env)
            self._report()

    def _report(self) -> None:
        if self.on_round_end is not None:
            self.last_saved = self.on_round_end(self.record, self)


def run(
    game: Game,
    draw: Callable[[], None],
    events: Callable[[], Iterable[Any]] | None = None,
    clock: Clock | None = None,
    max_frames: float = math.inf,
) -> int:
    """Play frames until the person quits (or `max_frames`); returns the frames played.

    Each frame: wait for the clock (`game.fps`), hand the frame's events to the game, `draw()`.
    """
    events = events or pygame.event.get
    clock = clock or pygame.time.Clock()
    frames = 0
    while game.phase is not Phase.QUIT and frames < max_frames:
        elapsed = clock.tick(game.fps)
        game.frame(events(), elapsed)
        draw()
        frames += 1
    return frames
