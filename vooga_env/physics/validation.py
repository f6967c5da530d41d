"""Argument checks shared by the engine: bad input fails where it is given, naming the argument."""

from __future__ import annotations

import math
import numbers
from collections.abc import Callable
from typing import Any


def finite(name: str, value: Any) -> float:
    """Return `value` as a float, or raise naming `name` if it is not a finite number.

    numpy's scalars are numbers.Real too, and come back as the float they hold.
    """
    if type(value) is float and value - value == 0.0:  # the engine's own writes: finite floats
        return value
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        raise TypeError(f"{name} must be a number, got {value!r} ({type(value).__name__})")
    value = float(value)
    if not math.isfinite(value):
        raise ValueError(f"{name} must be finite, got {value!r}")
    return value


def positive(name: str, value: Any) -> float:
    """A finite number > 0 (sizes, elapsed times)."""
    value = finite(name, value)
    if value <= 0.0:
        raise ValueError(f"{name} must be > 0, got {value!r}")
    return value


def non_negative(name: str, value: Any) -> float:
    """A finite number >= 0 (speeds, distances)."""
    value = finite(name, value)
    if value < 0.0:
        raise ValueError(f"{name} must be >= 0, got {value!r}")
    return value


def mass(name: str, value: Any) -> float:
    """A mass: a finite number > 0, or math.inf for a sprite no reaction can move."""
    if isinstance(value, numbers.Real) and not isinstance(value, bool) and value == math.inf:
        return math.inf
    return positive(name, value)


class Checked:
    """An attribute validated on every assignment, so a bad value fails where it is set.

    A data descriptor with `__set__` only: a write is checked and lands in the instance's
    `__dict__`, and a read finds it there at the speed of a plain attribute (reads far outnumber
    writes in the engine's hot path). On the class, the attribute is the descriptor itself.
    """

    def __init__(self, check: Callable[[str, Any], Any]) -> None:
        self.check = check

    def __set_name__(self, owner: type, name: str) -> None:
        self.name = name

    def __set__(self, obj: object, value: Any) -> None:
        obj.__dict__[self.name] = self.check(self.name, value)
