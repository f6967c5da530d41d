"""Fight configuration: frozen dataclasses loaded from TOML files in `configs/`, validated on load.

`load_config("water", max_cycles=500)` takes a name from `configs/` (or a path to a .toml file)
plus keyword overrides (nested tables as dicts: `physics={"gravity": 0.003}`). An unknown or
missing key, a wrong type, a number out of range (|float| <= FLOAT_MAX, |int| <= INT_MAX, a `seed`
<= SEED_MAX, and each field's own range) or an impossible arena raises `ConfigError` naming the
source, the key and the value; numpy scalars stand for the plain numbers they hold. A config that
loads runs on every backend for any seed (`tests/env/test_random_configs.py` checks it).
"""

from __future__ import annotations

import dataclasses
import numbers
import sys
import typing
from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from vooga_env.game import formulas

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover - Python 3.10
    import tomli as tomllib

# An installed wheel carries configs/ inside the package; a source checkout has it beside it.
_PACKAGE = Path(__file__).resolve().parent.parent
CONFIG_DIR = next(
    (path for path in (_PACKAGE / "configs", _PACKAGE.parent / "configs") if path.is_dir()),
    _PACKAGE.parent / "configs",
)

REACTIONS = ("push", "momentum", "stop", "punch", "rebound", "force", "none")
# Bounds on every number: the batched engine keeps counts in int64 and sums frame counts, and a
# float this large already makes no fight (positions and speeds stay far from overflow).
INT_MAX = 2**31 - 1
FLOAT_MAX = 1e9
# A `seed` key (training, league, RLlib configs) is numpy's: its legacy seeding, which SB3 uses,
# takes 0 .. 2**32 - 1; each config checks its own lower bound and room for per-env offsets.
SEED_MAX = 2**32 - 1


class ConfigError(ValueError):
    """A configuration that cannot be used; the message names the source, the key and the value."""


@dataclass(frozen=True)
class Block:
    """One platform block of the stage: top-left corner and size (px)."""

    x: float
    y: float
    width: float
    height: float

    @property
    def right(self) -> float:
        return self.x + self.width


@dataclass(frozen=True)
class ArenaConfig:
    """The arena's bounds and the stage: left, right and top bounds rebound; the bottom is open.

    `spawns` holds each fighter's spawn x (the left edge, px); fighters spawn standing on the
    highest block under them, so never inside one. `spawn_jitter` (px) moves each spawn by a
    seeded random amount, so every x within `spawn_jitter` of a spawn must have a block under it.
    `random_sides` then tosses a seeded coin for which fighter takes which spawn: a swapped fight
    starts crossed over, as after a jump over (each turns to face the other on its first frame).
    """

    width: float = 800.0
    height: float = 480.0
    blocks: tuple[Block, ...] = (Block(120.0, 360.0, 560.0, 40.0),)
    spawns: tuple[float, ...] = (240.0, 520.0)
    spawn_jitter: float = 0.0
    random_sides: bool = False

    @property
    def stage_left(self) -> float:
        """The stage's left edge (px): the leftmost block's; the reward's edges and observations."""
        return min(block.x for block in self.blocks)

    @property
    def stage_right(self) -> float:
        """The stage's right edge (px): the rightmost block end."""
        return max(block.x + block.width for block in self.blocks)


@dataclass(frozen=True)
class PhysicsConfig:
    """The engine's factors (see FightPhysicsEngine) and the physics frame's length.

    `gravity` (px/ms^2) must be > 0: without it a jump never comes down.
    """

    gravity: float = 0.002
    background_factor: float = 1.0
    speed_factor: float = 0.5
    out_bound_distance: float = 1.0
    frame_time: float = 20.0
    ground_friction: float = 0.0015


@dataclass(frozen=True)
class AttackConfig:
    """One attack: frame counts, damage and knockback, and its hitbox relative to the attacker.

    The hitbox sticks out of the attacker's front edge, `offset_y` px below the top of a
    standing fighter (crouching or not, attacks are placed from the feet).
    Knockback (px/ms) = `knockback + knockback_growth * damage already taken`, launched `angle`
    degrees above the horizontal, in the attacker's facing direction.
    """

    startup: int = 2
    active: int = 2
    recovery: int = 4
    damage: float = 4.0
    knockback: float = 0.25
    knockback_growth: float = 0.006
    angle: float = 30.0
    hitstun: int = 8
    hitbox_width: float = 28.0
    hitbox_height: float = 12.0
    offset_y: float = 8.0


@dataclass(frozen=True)
class FighterConfig:
    """A fighter's body and moves. Speeds in px/ms; frame counts in physics frames."""

    width: float = 40.0
    height: float = 60.0
    crouch_height: float = 38.0
    mass: float = 200.0
    speed: float = 0.5
    health: float = 100.0
    jump_speed: float = 0.75
    air_jumps: int = 1
    fast_fall_speed: float = 0.9
    head_slide: float = 2.0  # a fighter landing on the other slides off at this walking vector
    block_damage: float = 0.2
    block_knockback: float = 0.25
    punch: AttackConfig = AttackConfig()
    kick: AttackConfig = AttackConfig(
        startup=4,
        active=3,
        recovery=8,
        damage=7.0,
        knockback=0.4,
        knockback_growth=0.009,
        angle=40.0,
        hitstun=12,
        hitbox_width=40.0,
        hitbox_height=16.0,
        offset_y=36.0,
    )


@dataclass(frozen=True)
class RewardConfig:
    """Reward weights. Zero-sum unless `time_penalty` is set (it is charged to both fighters).

    Per step: `damage` * (damage dealt - damage taken) / health, `ring_out` for ringing the
    opponent out (minus for being rung out), `ko` likewise for a knock-out, minus `time_penalty`,
    plus `edge` times the change in stage room over the opponent's (see HitAndRingOutReward).
    When time runs out, `time_out` to the leader (the winner: more stocks, then more health) and
    minus `time_out` to the other; nothing on a draw.
    """

    damage: float = 5.0
    ring_out: float = 5.0
    ko: float = 5.0
    time_penalty: float = 0.0
    edge: float = 2.0
    time_out: float = 0.0


@dataclass(frozen=True)
class CollisionConfig:
    """Which reaction each collision kind runs: one of REACTIONS."""

    enemy: str = "push"
    neutral: str = "rebound"
    friends: str = "momentum"


@dataclass(frozen=True)
class StartConfig:
    """How far into a fight an episode starts, drawn at reset from the fight's seeded stream
    after the spawns: a fighter behind on health with the clock running down is otherwise a
    state a policy meets only where its opponents lead it.

    Each fighter starts having taken a uniform damage in [0, `damage`) (health lowered by it;
    full health again after a ring-out), the fight a uniform number of steps in [0, `steps`]
    into its `max_cycles`.
    """

    damage: float = 0.0
    steps: int = 0


@dataclass(frozen=True)
class FightConfig:
    """Everything a fight needs; `max_cycles` env steps, each `frame_skip` physics frames."""

    arena: ArenaConfig = ArenaConfig()
    physics: PhysicsConfig = PhysicsConfig()
    fighter: FighterConfig = FighterConfig()
    rewards: RewardConfig = RewardConfig()
    collisions: CollisionConfig = CollisionConfig()
    start: StartConfig = StartConfig()
    max_cycles: int = 900
    frame_skip: int = 2
    stocks: int = 1
    name: str = "default"

    def replace(self, **changes: Any) -> FightConfig:
        """A copy with top-level or nested (dict) changes, validated like a loaded file."""
        return build_config(FightConfig, _merge(_as_dict(self), changes), "overrides")


def load_config(config: str | Path | FightConfig = "default", **overrides: Any) -> FightConfig:
    """A FightConfig from a name in configs/, a .toml path or a FightConfig, plus overrides."""
    if isinstance(config, FightConfig):
        checked = config.replace(**overrides)  # one built by hand is checked here, as a file is
        return checked if overrides else config
    data, path = read_toml(config, CONFIG_DIR, "config")
    source = f"{path} with overrides {overrides}" if overrides else str(path)
    return build_config(FightConfig, _merge(data, overrides), source)


def read_toml(config: str | Path, folder: Path, what: str) -> tuple[dict[str, Any], Path]:
    """The table in `config` (a .toml path, or a name in `folder`) with its `name` filled in."""
    if not isinstance(config, (str, Path)):
        raise ConfigError(f"{what} must be a name or a path, got {config!r}")
    path = Path(config)
    if path.suffix != ".toml":
        path = folder / f"{config}.toml"
        if not path.is_file():
            known = sorted(p.stem for p in folder.glob("*.toml"))
            raise ConfigError(f"unknown {what} {str(config)!r}; known: {', '.join(known)}")
    try:
        with path.open("rb") as file:
            data = tomllib.load(file)
    except OSError as error:
        raise ConfigError(f"cannot read {what} file {path}: {error}") from None
    except tomllib.TOMLDecodeError as error:
        raise ConfigError(f"{path}: not valid TOML: {error}") from None
    data.setdefault("name", path.stem)
    return data, path


def _merge(base: Mapping[str, Any], changes: Mapping[str, Any]) -> dict[str, Any]:
    merged = dict(base)
    for key, value in changes.items():
        if isinstance(value, Mapping) and isinstance(merged.get(key), Mapping):
            merged[key] = _merge(merged[key], value)
        else:
            merged[key] = value
    return merged


def _as_dict(config: Any) -> Any:
    if dataclasses.is_dataclass(config):
        return {f.name: _as_dict(getattr(config, f.name)) for f in dataclasses.fields(config)}
    if isinstance(config, tuple):
        return [_as_dict(item) for item in config]
    return config


def overridden_source(path: Path, overrides: Mapping[str, Any]) -> str:
    """The source an error names: the file, and the overrides given on top of it (a bad `--seed`
    is the flag's fault, not the file's)."""
    if not overrides:
        return str(path)
    return f"{path} with {', '.join(f'{key} = {value!r}' for key, value in overrides.items())}"


def build_config(cls: type, data: Any, source: str, prefix: str = "") -> Any:
    """Build dataclass `cls` from `data`, checking every key and type; then check the whole.

    A dataclass may refuse values in `__post_init__` by raising ConfigError("key = value ...");
    the source and the key's prefix are added here.
    """
    if dataclasses.is_dataclass(data) and isinstance(data, cls):
        data = _as_dict(data)
    if not isinstance(data, Mapping):
        raise ConfigError(f"{source}: {prefix or 'config'} must be a table, got {data!r}")
    hints = typing.get_type_hints(cls)
    names = [f.name for f in dataclasses.fields(cls)]
    for key in data:
        if key not in names:
            raise ConfigError(
                f"{source}: unknown key {prefix + str(key)!r}; allowed: {', '.join(names)}"
            )
    for field in dataclasses.fields(cls):
        required = field.default is dataclasses.MISSING
        if required and field.default_factory is dataclasses.MISSING and field.name not in data:
            raise ConfigError(
                f"{source}: missing key {prefix + field.name!r}; {prefix or 'a config'} needs "
                f"{', '.join(names)}"
            )
    values = {}
    for name in names:
        if name in data:
            values[name] = _convert(hints[name], data[name], source, prefix + name)
    try:
        built = cls(**values)
    except ConfigError as error:
        raise ConfigError(f"{source}: {prefix}{error}") from None
    _check(built, source, prefix)
    return built


def _convert(hint: Any, value: Any, source: str, key: str) -> Any:
    origin = typing.get_origin(hint)
    if dataclasses.is_dataclass(hint):
        return build_config(hint, value, source, key + ".")
    if origin is tuple:
        if not isinstance(value, (list, tuple)):
            raise ConfigError(f"{source}: {key} must be a list, got {value!r}")
        item_hint = typing.get_args(hint)[0]
        return tuple(
            _convert(item_hint, item, source, f"{key}[{index}]") for index, item in enumerate(value)
        )
    if hint is bool:
        if not isinstance(value, bool):
            raise ConfigError(f"{source}: {key} must be true or false, got {value!r}")
        return value
    if hint is float:
        # numbers.Real holds numpy's floats and ints too (a numpy scalar is the number it holds)
        if isinstance(value, bool) or not isinstance(value, numbers.Real):
            raise ConfigError(f"{source}: {key} must be a finite number, got {value!r}")
        value = float(value)
        if not abs(value) <= FLOAT_MAX:  # NaN fails too
            raise ConfigError(
                f"{source}: {key} must be a finite number of magnitude <= {FLOAT_MAX:g}, "
                f"got {value!r}"
            )
        return value
    if hint is int:
        if isinstance(value, bool) or not isinstance(value, numbers.Integral):
            raise ConfigError(f"{source}: {key} must be an integer, got {value!r}")
        value, limit = int(value), SEED_MAX if key.rpartition(".")[2] == "seed" else INT_MAX
        if abs(value) > limit:
            raise ConfigError(f"{source}: {key} must be an integer in +-{limit}, got {value!r}")
        return value
    if hint is str:
        if not isinstance(value, str):
            raise ConfigError(f"{source}: {key} must be a string, got {value!r}")
        return value
    raise TypeError(f"unsupported config type {hint}")  # pragma: no cover


def _fail(source: str, key: str, value: Any, allowed: str) -> None:
    raise ConfigError(f"{source}: {key} = {value!r} is not allowed: {allowed}")


_POSITIVE = {
    ArenaConfig: ("width", "height"),
    Block: ("width", "height"),
    PhysicsConfig: ("gravity", "background_factor", "frame_time"),
    AttackConfig: ("hitbox_width", "hitbox_height"),
    FighterConfig: ("width", "height", "crouch_height", "mass", "health"),
    FightConfig: ("max_cycles", "frame_skip", "stocks"),
}
_NON_NEGATIVE = {
    ArenaConfig: ("spawn_jitter",),
    PhysicsConfig: ("speed_factor", "out_bound_distance", "ground_friction"),
    AttackConfig: ("startup", "recovery", "damage", "knockback", "knockback_growth", "hitstun"),
    FighterConfig: (
        "speed",
        "jump_speed",
        "air_jumps",
        "fast_fall_speed",
        "head_slide",
        "block_damage",
        "block_knockback",
    ),
    RewardConfig: ("damage", "ring_out", "ko", "time_penalty", "edge", "time_out"),
    StartConfig: ("damage", "steps"),
}


def _check(config: Any, source: str, prefix: str) -> None:
    """Range checks per field, then what only the whole can tell (an impossible arena)."""
    for name in _POSITIVE.get(type(config), ()):
        if getattr(config, name) <= 0:
            _fail(source, prefix + name, getattr(config, name), "must be > 0")
    for name in _NON_NEGATIVE.get(type(config), ()):
        if getattr(config, name) < 0:
            _fail(source, prefix + name, getattr(config, name), "must be >= 0")
    if isinstance(config, AttackConfig) and config.active < 1:
        _fail(source, prefix + "active", config.active, "an attack needs at least 1 active frame")
    if isinstance(config, FighterConfig) and config.crouch_height > config.height:
        _fail(
            source,
            prefix + "crouch_height",
            config.crouch_height,
            f"must be <= height ({config.height})",
        )
    if isinstance(config, CollisionConfig):
        for name in ("enemy", "neutral", "friends"):
            if getattr(config, name) not in REACTIONS:
                _fail(
                    source, prefix + name, getattr(config, name), f"one of {', '.join(REACTIONS)}"
                )
    if isinstance(config, FightConfig):
        _check_arena(config, source)
        _check_start(config, source)


def _check_arena(config: FightConfig, source: str) -> None:
    arena = config.arena
    if not arena.blocks:
        _fail(source, "arena.blocks", [], "the stage needs at least one block")
    for index, block in enumerate(arena.blocks):
        if (
            block.x < 0
            or block.x + block.width > arena.width
            or block.y < 0
            or (block.y + block.height > arena.height)
        ):
            _fail(
                source,
                f"arena.blocks[{index}]",
                block,
                f"must lie inside the {arena.width:g}x{arena.height:g} arena",
            )
    if arena.stage_left <= 0 and arena.stage_right >= arena.width:
        _fail(
            source,
            "arena.blocks",
            arena.blocks,
            "the stage must be narrower than the arena, or nobody can be rung out",
        )
    if len(arena.spawns) != 2:
        _fail(source, "arena.spawns", arena.spawns, "exactly two spawn x positions")
    for index, x in enumerate(arena.spawns):
        _check_spawn(config, source, f"arena.spawns[{index}]", x)


def _check_start(config: FightConfig, source: str) -> None:
    """A fight must start with both fighters standing and some of its clock left."""
    start = config.start
    if start.damage >= config.fighter.health:
        _fail(
            source,
            "start.damage",
            start.damage,
            f"must be < fighter.health ({config.fighter.health:g})",
        )
    if start.steps >= config.max_cycles:
        _fail(source, "start.steps", start.steps, f"must be < max_cycles ({config.max_cycles})")


def _check_spawn(config: FightConfig, source: str, key: str, x: float) -> None:
    """Every spawn the jitter can draw, [x - jitter, x + jitter], must stand on the stage."""
    arena, fighter = config.arena, config.fighter
    low, high = x - arena.spawn_jitter, x + arena.spawn_jitter
    margin = config.physics.out_bound_distance
    jitter = f" (spawn_jitter {arena.spawn_jitter:g}: {low:g}..{high:g})" if low < high else ""
    if low < margin or high + fighter.width > arena.width - margin:
        _fail(source, key, x, f"the fighter{jitter} must spawn inside the arena's bounds")
    # a block is under a left edge at s when block.x < s + width and s < block.x + block.width,
    # written as formulas.under writes it (block.x - width < s can round the other way)
    under = sorted(
        (block for block in arena.blocks if block.x < high + fighter.width and low < block.right),
        key=lambda block: block.x,
    )
    point = low  # the first left edge not yet known to be covered
    for block in under:
        if block.x >= point + fighter.width:
            break
        point = max(point, block.right)
    if point <= high:
        _fail(source, key, x, f"the fighter{jitter} must spawn above a block of the stage")
    if min(block.y for block in under) < fighter.height:
        _fail(source, key, x, f"the fighter{jitter} is too tall to stand on the block under it")


def spawn_block(arena: ArenaConfig, x: float, width: float) -> Block | None:
    """The highest block under a fighter whose left edge is at `x`, or None."""
    under = [block for block in arena.blocks if formulas.under(block.x, block.width, x, width)]
    return min(under, key=lambda block: block.y, default=None)
