"""Replays: one game as a JSON file (seed + config + actions) that plays back bit-identically,
checked step by step.

The env is deterministic, so the seed, the whole resolved config and the actions of every step
are enough to play a game again exactly. A replay carries a digest of every step (BLAKE2b, 8
bytes, of the step's actions, both observations, the fighters' positions, health and stocks and
the rewards after it) and one of its header (the config's name, the seed, the names, the policy
seeds). `play_back` checks the header, then each step as it plays, and raises `ReplayMismatch`
naming the first step that differs; any edited action is caught at its own step, whether or not
it changes the game. The config's values are checked through what they do to the steps, so a
later vooga_env that adds a config key (with its default) still reads old replays. The final
result is checked too. The digests guard against edits and corruption, not against someone who
recomputes them.

The file (format `FORMAT`, version `VERSION`; version 1, without digests, still loads and is
checked on its result only) holds:

    format, version, vooga_env (the package version that wrote it), config_name, max_cycles,
    config (every config key, as `load_config` would build it), seed, names (fighter_0's policy,
    fighter_1's), policy_seeds, actions ([[fighter_0's, fighter_1's], ...] per step), result,
    header_digest, digests (one per step).

Every field is type-checked on load (`ReplayError` names the field, the value and what is
allowed). Floats are written with Python's shortest round-tripping repr: they load back bit for
bit.
"""

from __future__ import annotations

import dataclasses
import hashlib
import json
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from vooga_env.envs.parallel import parallel_env
from vooga_env.game.config import ConfigError, FightConfig, load_config
from vooga_env.tools.files import atomic_write_text
from vooga_env.tools.match import EpisodeRecord, capture_frame
from vooga_env.tools.replay_format import check_fields, check_keys

FORMAT = "vooga_env.tools.replay"
VERSION = 2
DIGEST_BYTES = 8


class ReplayError(ValueError):
    """A replay file that cannot be read; the message names the file and the problem."""


class ReplayMismatch(RuntimeError):
    """Playing a replay back did not give the recording; `step` is the first step that differs
    (None: the header, or only the result)."""

    def __init__(self, message: str, step: int | None = None) -> None:
        super().__init__(message)
        self.step = step


@dataclass
class Replay:
    """One game: the fight's config and seed, both fighters' actions per step, and the result."""

    config: FightConfig
    seed: int
    actions: list[tuple[int, int]]
    names: tuple[str, str] = ("fighter_0", "fighter_1")
    policy_seeds: tuple[int | None, int | None] = (None, None)
    result: dict[str, Any] = field(default_factory=dict)
    header_digest: str = ""  # "" (with no digests): an unsealed replay, checked on its result
    digests: list[str] = field(default_factory=list)

    @classmethod
    def from_episode(cls, record: EpisodeRecord, config: FightConfig) -> Replay:
        """The replay of a game played with `record_actions=True` on an env with `config`, sealed
        with its digests (it is played once more to take them, and must give the same result)."""
        if record.actions is None:
            raise ValueError("the episode was played without record_actions=True")
        replay = cls(
            config=config,
            seed=record.seed,
            actions=[(int(a), int(b)) for a, b in record.actions],
            names=tuple(record.names),
            policy_seeds=tuple(record.policy_seeds),
            result=_result(record),
        )
        return replay.sealed()

    def sealed(self) -> Replay:
        """This replay with its header and step digests, taken by playing it (result checked)."""
        digests: list[str] = []
        record = _play(dataclasses.replace(self, header_digest="", digests=[]), digests=digests)
        differences = _differences(self.result, record)
        if differences:
            raise ReplayMismatch("the game does not play back as it was played: " + differences)
        return dataclasses.replace(self, header_digest=self.header(), digests=digests)

    def header(self) -> str:
        """The digest of who played, from which seed, under which config's name (the config's
        values show in the step digests)."""
        text = json.dumps(
            [self.config.name, self.seed, list(self.names), list(self.policy_seeds)],
            separators=(",", ":"),
        )
        return hashlib.blake2b(text.encode(), digest_size=DIGEST_BYTES).hexdigest()

    def to_dict(self) -> dict[str, Any]:
        from vooga_env import __version__

        sealed = {"header_digest": self.header_digest, "digests": self.digests}
        return {
            "format": FORMAT,
            "version": VERSION if self.digests else 1,  # unsealed: the old format says it all
            "vooga_env": __version__,
            "config_name": self.config.name,
            "max_cycles": self.config.max_cycles,
            "config": dataclasses.asdict(self.config),
            "seed": self.seed,
            "names": list(self.names),
            "policy_seeds": list(self.policy_seeds),
            "actions": [list(pair) for pair in self.actions],
            "result": self.result,
            **(sealed if self.digests else {}),
        }

    @classmethod
    def from_dict(cls, data: Any, source: str = "replay") -> Replay:
        if not isinstance(data, dict) or data.get("format") != FORMAT:
            raise ReplayError(f'{source}: not a vooga_env replay (no "format": "{FORMAT}")')
        if type(data.get("version")) is not int or data["version"] not in (1, VERSION):
            raise ReplayError(
                f"{source}: replay version {data.get('version')!r}; this vooga_env reads "
                f"versions 1 and {VERSION}"
            )
        try:
            check_keys(data)
        except ValueError as error:
            raise ReplayError(f"{source}: {error}") from None
        try:
            config = load_config(FightConfig(), **data["config"])
        except (ConfigError, TypeError) as error:
            raise ReplayError(f"{source}: bad config: {error}") from None
        try:
            check_fields(data, config, DIGEST_BYTES)
        except ValueError as error:
            raise ReplayError(f"{source}: {error}") from None
        return cls(
            config=config,
            seed=data["seed"],
            actions=[(a, b) for a, b in data["actions"]],
            names=tuple(data["names"]),
            policy_seeds=tuple(data.get("policy_seeds", (None, None))),
            result=dict(data.get("result", {})),
            header_digest=data.get("header_digest", ""),
            digests=list(data.get("digests", [])),
        )

    def save(self, path: str | Path) -> Path:
        """Write the replay as JSON, atomically (folders made as needed); returns the path."""
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
    """Play the replay's actions on a fresh env; with `check`, raise ReplayMismatch at the first
    step (or the header, or the result) that differs from the recording.

    Returns the played game's record (with its actions, and its observations / frames if asked).
    """
    if check and replay.digests and replay.header() != replay.header_digest:
        raise ReplayMismatch(
            "the header differs from the recording: its config name, seed, names or policy "
            "seeds were changed"
        )
    record = _play(
        replay, render_mode, record_observations, record_frames, check, step_hook, digests=None
    )
    differences = _differences(replay.result, record) if check else ""
    if differences:
        raise ReplayMismatch("playback differs from the recording: " + differences)
    return record


def _differences(result: dict[str, Any], record: EpisodeRecord) -> str:
    """What of the recorded `result` the played `record` does not match ("" if all does)."""
    return "; ".join(
        f"{key}: recorded {result[key]!r}, played back {value!r}"
        for key, value in _result(record).items()
        if key in result and result[key] != value
    )


def _play(
    replay: Replay,
    render_mode: str | None = None,
    record_observations: bool = False,
    record_frames: bool = False,
    check: bool = True,
    step_hook: Callable[[EpisodeRecord], None] | None = None,
    digests: list[str] | None = None,
) -> EpisodeRecord:
    """Play the actions, checking each step's digest (with `check`) or appending it to `digests`."""
    env = parallel_env(config=replay.config, render_mode=render_mode)
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
                    f"the fight ended after {step} steps, the replay has {len(replay.actions)}",
                    step,
                )
            observations, rewards, _, _, infos = env.step(dict(zip(agents, actions, strict=True)))
            record.add_step(actions, infos)
            digest = step_digest(env, actions, [rewards[agent] for agent in agents])
            if digests is not None:
                digests.append(digest)
            elif check and replay.digests and step >= len(replay.digests):
                raise ReplayMismatch(
                    f"step {step} was not recorded: the recording has {len(replay.digests)}", step
                )
            elif check and replay.digests and digest != replay.digests[step]:
                raise ReplayMismatch(
                    f"step {step} differs from the recording (its actions {list(actions)} or "
                    f"the state after them): digest {digest}, recorded {replay.digests[step]}",
                    step,
                )
            if step_hook is not None:
                step_hook(record)
        record.close(env)
    finally:
        env.close()
    return record


def step_digest(env: Any, actions: tuple[int, int], rewards: list[float]) -> str:
    """The digest of one step: its actions and the state after it (both observations, positions,
    health, stocks, rewards), the same on every backend since they step bit-identically."""
    status = [[s["x"], s["y"], s["health"], s["stocks"]] for s in env.fighter_status()]
    digest = hashlib.blake2b(digest_size=DIGEST_BYTES)
    digest.update(np.asarray(actions, dtype=np.int64).tobytes())
    digest.update(np.ascontiguousarray(env.state(), dtype=np.float32).tobytes())
    digest.update(np.asarray(status, dtype=np.float64).tobytes())
    digest.update(np.asarray(rewards, dtype=np.float64).tobytes())
    return digest.hexdigest()


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
