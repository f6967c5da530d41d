"""Replays: one game as a JSON file (seed + config + actions) that plays back bit-identically.

The env is deterministic, so the seed, the whole resolved config and the actions of every step
are enough to play a game again exactly; the final result is stored too and `play_back` checks it
(winner, steps, health, stocks, positions, ring-outs, KOs, damage), raising `ReplayMismatch` on any
difference. The file (format `FORMAT`, version `VERSION`) holds:

    format, version, vooga_env (the package version that wrote it), config_name, max_cycles,
    config (every config key, as `load_config` would build it), seed, names (fighter_0's policy,
    fighter_1's), policy_seeds, actions ([[fighter_0's, fighter_1's], ...] per step), result.

Floats are written with Python's shortest round-tripping repr, so they load back bit for bit.
"""

from __future__ import annotations

import dataclasses
import json
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from vooga_env.actions import Action
from vooga_env.config import ConfigError, FightConfig, load_config
from vooga_env.files import atomic_write_text
from vooga_env.match import EpisodeRecord, capture_frame

FORMAT = "vooga_env.replay"
VERSION = 1


class ReplayError(ValueError):
    """A replay file that cannot be read; the message names the file and the problem."""


class ReplayMismatch(RuntimeError):
    """Playing a replay back did not give the recorded result."""


@dataclass
class Replay:
    """One game: the fight's config and seed, both fighters' actions per step, and the result."""

    config: FightConfig
    seed: int
    actions: list[tuple[int, int]]
    names: tuple[str, str] = ("fighter_0", "fighter_1")
    policy_seeds: tuple[int | None, int | None] = (None, None)
    result: dict[str, Any] = field(default_factory=dict)

    @classmethod
    def from_episode(cls, record: EpisodeRecord, config: FightConfig) -> Replay:
        """The replay of a game played with `record_actions=True` on an env with `config`."""
        if record.actions is None:
            raise ValueError("the episode was played without record_actions=True")
        return cls(
            config=config,
            seed=record.seed,
            actions=[(int(a), int(b)) for a, b in record.actions],
            names=record.names,
            policy_seeds=record.policy_seeds,
            result=_result(record),
        )

    def to_dict(self) -> dict[str, Any]:
        from vooga_env import __version__

        return {
            "format": FORMAT,
            "version": VERSION,
            "vooga_env": __version__,
            "config_name": self.config.name,
            "max_cycles": self.config.max_cycles,
            "config": dataclasses.asdict(self.config),
            "seed": self.seed,
            "names": list(self.names),
            "policy_seeds": list(self.policy_seeds),
            "actions": [list(pair) for pair in self.actions],
            "result": self.result,
        }

    @classmethod
    def from_dict(cls, data: Any, source: str = "replay") -> Replay:
        if not isinstance(data, dict) or data.get("format") != FORMAT:
            raise ReplayError(f'{source}: not a vooga_env replay (no "format": "{FORMAT}")')
        if data.get("version") != VERSION:
            raise ReplayError(
                f"{source}: replay version {data.get('version')!r}; this vooga_env reads {VERSION}"
            )
        missing = [key for key in ("config", "seed", "actions", "names") if key not in data]
        if missing:
            raise ReplayError(f"{source}: missing {', '.join(missing)}")
        try:
            config = load_config(FightConfig(), **data["config"])
        except (ConfigError, TypeError) as error:
            raise ReplayError(f"{source}: bad config: {error}") from None
        seed = data["seed"]
        if isinstance(seed, bool) or not isinstance(seed, int) or seed < 0:
            raise ReplayError(f"{source}: seed must be a non-negative int, got {seed!r}")
        return cls(
            config=config,
            seed=seed,
            actions=_actions(data["actions"], source),
            names=tuple(data["names"]),
            policy_seeds=tuple(data.get("policy_seeds", (None, None))),
            result=dict(data.get("result", {})),
        )

    def save(self, path: str | Path) -> Path:
        """Write the replay as JSON (folders made as needed); returns the path."""
        return atomic_write_text(
            Path(path), json.dumps(self.to_dict(), separators=(",", ":")) + "\n"
        )

    @classmethod
    def load(cls, path: str | Path) -> Replay:
        path = Path(path)
        try:
            data = json.loads(path.read_text())
        except OSError as error:
            raise ReplayError(f"cannot read replay {path}: {error.strerror}") from None
        except json.JSONDecodeError as error:
            raise ReplayError(f"{path}: not JSON: {error}") from None
        return cls.from_dict(data, str(path))


def play_back(
    replay: Replay,
    render_mode: str | None = None,
    record_observations: bool = False,
    record_frames: bool = False,
    check: bool = True,
    step_hook: Callable[[EpisodeRecord], None] | None = None,
) -> EpisodeRecord:
    """Play the replay's actions on a fresh env; with `check`, raise ReplayMismatch on a difference.

    Returns the played game's record (with its actions, and its observations / frames if asked).
    """
    import vooga_env

    env = vooga_env.parallel_env(config=replay.config, render_mode=render_mode)
    agents = env.possible_agents
    record = EpisodeRecord(replay.seed, replay.names, replay.policy_seeds, actions=[])
    record.observations = [] if record_observations else None
    record.frames = [] if record_frames else None
    try:
        observations, _ = env.reset(seed=replay.seed)
        for step, actions in enumerate([*replay.actions, None]):
            if record.observations is not None:
                record.observations.append(np.stack([observations[agent] for agent in agents]))
            if record.frames is not None:
                record.frames.append(capture_frame(env))
            if actions is None:
                break
            if not env.agents:
                raise ReplayMismatch(
                    f"the fight ended after {step} steps, the replay has {len(replay.actions)}"
                )
            observations, _, _, _, infos = env.step(dict(zip(agents, actions, strict=True)))
            record.add_step(actions, infos)
            if step_hook is not None:
                step_hook(record)
        record.close(env)
    finally:
        env.close()
    if check and replay.result:
        differences = [
            f"{key}: recorded {replay.result[key]!r}, played back {value!r}"
            for key, value in _result(record).items()
            if key in replay.result and replay.result[key] != value
        ]
        if differences:
            raise ReplayMismatch("playback differs from the recording: " + "; ".join(differences))
    return record


def _result(record: EpisodeRecord) -> dict[str, Any]:
    return {
        "winner": record.winner,
        "steps": record.steps,
        "health": list(record.health),
        "stocks": list(record.stocks),
        "positions": [list(position) for position in record.positions],
        "ring_outs": list(record.ring_outs),
        "knock_outs": list(record.knock_outs),
        "damage_dealt": list(record.damage_dealt),
    }


def _actions(actions: Any, source: str) -> list[tuple[int, int]]:
    if not isinstance(actions, list):
        raise ReplayError(f"{source}: actions must be a list of [fighter_0, fighter_1] pairs")
    pairs = []
    for step, pair in enumerate(actions):
        if (
            not isinstance(pair, list)
            or len(pair) != 2
            or not all(
                isinstance(a, int) and not isinstance(a, bool) and 0 <= a < len(Action)
                for a in pair
            )
        ):
            raise ReplayError(
                f"{source}: actions[{step}] = {pair!r}; "
                f"each must be two ints in 0..{len(Action) - 1}"
            )
        pairs.append((pair[0], pair[1]))
    return pairs
