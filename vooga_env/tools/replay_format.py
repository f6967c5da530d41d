"""The replay file's fields and their types, checked on load: each error names the field, the
value and what is allowed (see `vooga_env.tools.replay` for what the fields mean)."""

from __future__ import annotations

import math
import string
from collections.abc import Callable
from typing import Any

from vooga_env.game.actions import Action
from vooga_env.game.config import FightConfig

REQUIRED = ("format", "version", "config", "seed", "names", "actions")
OPTIONAL = ("vooga_env", "config_name", "max_cycles", "policy_seeds", "result")
SEALED = ("header_digest", "digests")  # version 2 on
WINNERS = ("fighter_0", "fighter_1", "draw", None)


def _int(value: Any) -> bool:
    return isinstance(value, int) and not isinstance(value, bool)


def _count(value: Any) -> bool:
    return _int(value) and value >= 0


def _number(value: Any) -> bool:
    return (_int(value) or isinstance(value, float)) and math.isfinite(value)


def _pair(item: Callable[[Any], bool]) -> Callable[[Any], bool]:
    return lambda value: isinstance(value, list) and len(value) == 2 and all(map(item, value))


def _action(value: Any) -> bool:
    return _int(value) and 0 <= value < len(Action)


def _hex(size: int) -> Callable[[Any], bool]:
    digits = set(string.hexdigits.lower())
    return lambda value: isinstance(value, str) and len(value) == 2 * size and set(value) <= digits


RESULT = {
    "winner": (lambda value: value in WINNERS, "fighter_0, fighter_1, draw or null"),
    "steps": (_count, "an int >= 0, the number of actions"),
    "health": (_pair(_number), "two finite numbers"),
    "stocks": (_pair(_count), "two ints >= 0"),
    "positions": (_pair(_pair(_number)), "two [x, y] pairs of finite numbers"),
    "ring_outs": (_pair(_count), "two ints >= 0"),
    "knock_outs": (_pair(_count), "two ints >= 0"),
    "damage_dealt": (_pair(_number), "two finite numbers"),
}


def _refuse(key: str, value: Any, allowed: str) -> None:
    shown = repr(value)
    shown = shown if len(shown) <= 80 else shown[:77] + "..."
    raise ValueError(f"{key} = {shown} is not allowed: {allowed}")


def _expect(key: str, value: Any, ok: bool, allowed: str) -> None:
    if not ok:
        _refuse(key, value, allowed)


def check_keys(data: dict[str, Any]) -> None:
    """Raise ValueError for a field a replay of its version does not have, or one missing."""
    sealed = data["version"] >= 2
    allowed = (*REQUIRED, *OPTIONAL, *(SEALED if sealed else ()))
    for key in data:
        _expect(
            key,
            data[key],
            key in allowed,
            f"not a field of a version {data['version']} replay; the fields are "
            + ", ".join(allowed),
        )
    missing = [key for key in (*REQUIRED, *(SEALED if sealed else ())) if key not in data]
    if missing:
        raise ValueError(f"missing {', '.join(missing)}")


def check_fields(data: dict[str, Any], config: FightConfig, digest_bytes: int) -> None:
    """Raise ValueError for the first field of a replay's `data` (keys checked) that is wrong."""
    sealed = data["version"] >= 2
    _check_header(data, config)
    actions = data["actions"]
    _expect("actions", actions, isinstance(actions, list), "a list of [fighter_0, fighter_1]")
    for step, pair in enumerate(actions):
        _expect(f"actions[{step}]", pair, _pair(_action)(pair), f"two ints in 0..{len(Action) - 1}")
    _expect(
        "actions",
        f"{len(actions)} steps",
        len(actions) <= config.max_cycles,
        f"at most max_cycles = {config.max_cycles} steps",
    )
    _check_result(data.get("result", {}), len(actions))
    if sealed:
        _expect(
            "header_digest",
            data["header_digest"],
            _hex(digest_bytes)(data["header_digest"]),
            f"{2 * digest_bytes} hex digits",
        )
        digests = data["digests"]
        _expect(
            "digests",
            digests,
            isinstance(digests, list) and len(digests) == len(actions),
            f"a list of one digest per action ({len(actions)})",
        )
        for step, digest in enumerate(digests):
            _expect(
                f"digests[{step}]",
                digest,
                _hex(digest_bytes)(digest),
                f"{2 * digest_bytes} hex digits",
            )


def _check_header(data: dict[str, Any], config: FightConfig) -> None:
    seed, names = data["seed"], data["names"]
    _expect("seed", seed, _count(seed), "an int >= 0")
    _expect(
        "names",
        names,
        _pair(lambda name: isinstance(name, str) and name != "")(names),
        "two non-empty strings, fighter_0's policy and fighter_1's",
    )
    seeds = data.get("policy_seeds", [None, None])
    _expect(
        "policy_seeds",
        seeds,
        _pair(lambda s: s is None or _count(s))(seeds),
        "two ints >= 0 or nulls",
    )
    for key, expected in (
        ("vooga_env", None),
        ("config_name", config.name),
        ("max_cycles", config.max_cycles),
    ):
        if key not in data:
            continue
        value = data[key]
        if expected is None:
            _expect(key, value, isinstance(value, str), "a version string")
        else:
            _expect(
                key,
                value,
                value == expected and type(value) is type(expected),
                f"the config's own {key}, {expected!r}",
            )


def _check_result(result: Any, steps: int) -> None:
    _expect("result", result, isinstance(result, dict), "a table of the game's result")
    if not result:
        return  # a replay without a result to check
    for key in result:
        _expect(
            f"result.{key}",
            result[key],
            key in RESULT,
            f"not a field of a result; the fields are {', '.join(RESULT)}",
        )
    for key, (ok, allowed) in RESULT.items():
        _expect(
            f"result.{key}", result.get(key, "missing"), key in result and ok(result[key]), allowed
        )
    _expect(
        "result.steps", result["steps"], result["steps"] == steps, f"the number of actions, {steps}"
    )
