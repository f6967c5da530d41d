"""The scripted fighters of `vooga_env.policies`, deciding for a whole batch of observations.

`scripted_actions(name, observations, draws)` makes, row by row, the choice the scalar policy
makes on that observation when its random draw (`rng.random()`) is `draws[row]`; a test holds
the two together. `VectorOpponent` draws from one seeded generator for the batch (not the
per-fighter streams of the scalar policies, so a game against it is not the same game).
"""

from __future__ import annotations

from typing import Any

import numpy as np

from vooga_env.game.actions import Action
from vooga_env.game.observations import OBSERVATION_NAMES
from vooga_env.policies.scripted import SCRIPTED

_I = {name: index for index, name in enumerate(OBSERVATION_NAMES)}


def _column(observations: np.ndarray, name: str) -> np.ndarray:
    return observations[:, _I[name]]


def _toward(gap: np.ndarray) -> np.ndarray:
    return np.where(gap > 0, Action.RIGHT, Action.LEFT)


def _recover(observations: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """policies._recover: (needed, action) per row."""
    left, right = _column(observations, "stage_left"), _column(observations, "stage_right")
    needed = ~((left >= 0) & (right >= 0))
    back_right = left < 0
    falling = (_column(observations, "self_vy") > 0) & ~(
        _column(observations, "self_on_ground") != 0
    )
    jump = falling & (_column(observations, "self_jumps_left") > 0)
    action = np.where(
        jump,
        np.where(back_right, Action.JUMP_RIGHT, Action.JUMP_LEFT),
        np.where(back_right, Action.RIGHT, Action.LEFT),
    )
    return needed, action


def _reach(observations: np.ndarray, move: str) -> np.ndarray:
    return _column(observations, f"self_{move}_reach") != 0


def _attacking(observations: np.ndarray) -> np.ndarray:
    return (_column(observations, "opponent_punching") != 0) | (
        _column(observations, "opponent_kicking") != 0
    )


def _rush(observations: np.ndarray, draws: np.ndarray) -> np.ndarray:
    gap = _column(observations, "opponent_x")
    kick = _reach(observations, "kick") & (draws < 0.5)
    return np.where(
        _reach(observations, "punch"), Action.PUNCH, np.where(kick, Action.KICK, _toward(gap))
    )


def _turtle(observations: np.ndarray, draws: np.ndarray) -> np.ndarray:
    gap = _column(observations, "opponent_x")
    attacking = _attacking(observations)
    strike = np.where(_reach(observations, "punch"), Action.PUNCH, Action.KICK)
    punish = attacking | (_column(observations, "opponent_hitstun") > 0) | (draws >= 0.7)
    guard = attacking & (_column(observations, "opponent_move_progress") < 0.6)
    close = np.where(guard, Action.BLOCK, np.where(punish, strike, Action.BLOCK))
    return np.where(_reach(observations, "kick"), close, _toward(gap))


def _zoner(observations: np.ndarray, draws: np.ndarray) -> np.ndarray:
    gap = _column(observations, "opponent_x")
    behind = np.where(
        gap > 0, _column(observations, "stage_left"), _column(observations, "stage_right")
    )
    away = np.where(gap > 0, Action.LEFT, Action.RIGHT)
    return np.where(
        _reach(observations, "punch") & (behind > 0.08),
        away,
        np.where(_reach(observations, "kick"), Action.KICK, _toward(gap)),
    )


def _edge_guard(observations: np.ndarray, draws: np.ndarray) -> np.ndarray:
    gap = _column(observations, "opponent_x")
    own = (_column(observations, "stage_left") - _column(observations, "stage_right")) / 2
    pressing = gap * (own + gap / 2) > 0
    strike = np.where(pressing | ~_reach(observations, "punch"), Action.KICK, Action.PUNCH)
    close = np.where(_attacking(observations) & ~pressing, Action.BLOCK, strike)
    far = np.where(
        pressing | (np.abs(own) < 0.05),
        _toward(gap),
        np.where(own > 0, Action.LEFT, Action.RIGHT),
    )
    return np.where(_reach(observations, "kick"), close, far)


def _away(gap: np.ndarray) -> np.ndarray:
    return np.where(gap > 0, Action.LEFT, Action.RIGHT)


def _jump_toward(gap: np.ndarray) -> np.ndarray:
    return np.where(gap > 0, Action.JUMP_RIGHT, Action.JUMP_LEFT)


def _behind(observations: np.ndarray, gap: np.ndarray) -> np.ndarray:
    left, right = _column(observations, "stage_left"), _column(observations, "stage_right")
    return np.where(gap > 0, left, right)


def _opponent_reach(observations: np.ndarray, move: str) -> np.ndarray:
    return _column(observations, f"opponent_{move}_reach") != 0


def _threatened(observations: np.ndarray) -> np.ndarray:
    """policies._threatened: could the opponent's punch or kick, started now, touch it?"""
    return _opponent_reach(observations, "punch") | _opponent_reach(observations, "kick")


def _aerial(observations: np.ndarray, draws: np.ndarray) -> np.ndarray:
    gap = _column(observations, "opponent_x")
    grounded = _column(observations, "self_on_ground") > 0
    room = _behind(observations, -gap) - np.abs(gap) / 2
    hop = grounded & (np.abs(gap) < 0.6) & (room > 0.15) & (draws < 0.5)
    far = np.where(hop, _jump_toward(gap), _toward(gap))
    return np.where(
        _reach(observations, "punch"),
        Action.PUNCH,
        np.where(_reach(observations, "kick"), Action.KICK, far),
    )


def _punisher(observations: np.ndarray, draws: np.ndarray) -> np.ndarray:
    gap = _column(observations, "opponent_x")
    attacking = _attacking(observations)
    late = _column(observations, "opponent_move_progress") >= 0.5
    punish = (_column(observations, "opponent_hitstun") > 0) | (attacking & late)
    kick_or_walk = np.where(_reach(observations, "kick"), Action.KICK, _toward(gap))
    strike = np.where(_reach(observations, "punch"), Action.PUNCH, kick_or_walk)
    poke = ~attacking & _reach(observations, "kick") & (draws < 0.3)
    threatened = _threatened(observations)
    evade = np.where(_behind(observations, gap) > 0.1, _away(gap), _jump_toward(gap))
    defend = np.where(attacking, Action.BLOCK, evade)
    bait = np.where(draws < 0.6, _toward(gap), Action.IDLE)
    return np.where(punish, strike, np.where(poke, Action.KICK, np.where(threatened, defend, bait)))


def _spacer(observations: np.ndarray, draws: np.ndarray) -> np.ndarray:
    gap = _column(observations, "opponent_x")
    duck = (_column(observations, "opponent_punching") > 0) & _opponent_reach(observations, "punch")
    back = _reach(observations, "punch") & (_behind(observations, gap) > 0.08)
    crouched = _column(observations, "self_crouching") > 0
    kick = np.where(crouched | (draws < 0.4), Action.KICK, Action.DOWN)
    rest = np.where(back, _away(gap), np.where(_reach(observations, "kick"), kick, _toward(gap)))
    return np.where(duck, Action.DOWN, rest)


def _edge_grappler(observations: np.ndarray, draws: np.ndarray) -> np.ndarray:
    gap = _column(observations, "opponent_x")
    ahead = np.where(
        gap > 0, _column(observations, "stage_right"), _column(observations, "stage_left")
    )
    cornered = ahead - np.abs(gap) / 2 < 0.15
    close = np.where(cornered, Action.KICK, Action.PUNCH)
    kick = _reach(observations, "kick") & (cornered | (draws < 0.2))
    block = _attacking(observations) & _opponent_reach(observations, "punch")
    escape = (_behind(observations, gap) < 0.1) & (draws < 0.5)
    far = np.where(block, Action.BLOCK, np.where(escape, _jump_toward(gap), _toward(gap)))
    return np.where(_reach(observations, "punch"), close, np.where(kick, Action.KICK, far))


def _shover(observations: np.ndarray, draws: np.ndarray) -> np.ndarray:
    block = _attacking(observations) & _threatened(observations)
    return np.where(block, Action.BLOCK, _toward(_column(observations, "opponent_x")))


def _standing(observations: np.ndarray) -> np.ndarray:
    """policies._standing: +1 where it would win on time (more stocks, then more health), -1 where
    it would lose, 0 where level."""
    stocks = np.sign(
        _column(observations, "self_stocks") - _column(observations, "opponent_stocks")
    )
    health = np.sign(
        _column(observations, "self_health") - _column(observations, "opponent_health")
    )
    return np.where(stocks != 0, stocks, health)


def _staller(observations: np.ndarray, draws: np.ndarray) -> np.ndarray:
    crouched = _column(observations, "self_crouching") != 0
    stall = np.where(crouched, Action.PUNCH, Action.DOWN)
    block = _attacking(observations) & _threatened(observations)
    kick_or_walk = np.where(
        _reach(observations, "kick"), Action.KICK, _toward(_column(observations, "opponent_x"))
    )
    fight = np.where(
        block, Action.BLOCK, np.where(_reach(observations, "punch"), Action.PUNCH, kick_or_walk)
    )
    standing = _standing(observations)
    stalling = (standing > 0) | ((standing == 0) & (_column(observations, "time_left") > 0.5))
    return np.where(stalling, stall, fight)


_MIXUP_STYLES = (_aerial, _punisher, _edge_grappler)


def _mixup(observations: np.ndarray, draws: np.ndarray) -> np.ndarray:
    """policies.MixUp: the style of the clock's twelfth, row by row."""
    time_left = _column(observations, "time_left").astype(np.float64)
    phase = (time_left * 12.0).astype(np.int64) % len(_MIXUP_STYLES)
    choices = np.stack([style(observations, draws) for style in _MIXUP_STYLES])
    return choices[phase, np.arange(len(observations))]


def _idle(observations: np.ndarray, draws: np.ndarray) -> np.ndarray:
    return np.full(len(observations), Action.IDLE)


_DECIDE = {
    "idle": _idle,
    "rush": _rush,
    "turtle": _turtle,
    "zoner": _zoner,
    "edge_guard": _edge_guard,
    "aerial": _aerial,
    "punisher": _punisher,
    "spacer": _spacer,
    "edge_grappler": _edge_grappler,
    "mixup": _mixup,
    "shover": _shover,
    "staller": _staller,
}
NAMES = (*_DECIDE, "random")
assert set(NAMES) == set(SCRIPTED), "a scripted fighter without a batched version"


def scripted_actions(name: str, observations: np.ndarray, draws: np.ndarray) -> np.ndarray:
    """The action of scripted fighter `name` for each row of `observations` (n, 41).

    `draws` (n,) in [0, 1) stand for each row's `rng.random()`; "random" maps them to
    `floor(draw * 10)`.
    """
    if name == "random":
        return np.minimum((draws * len(Action)).astype(np.int64), len(Action) - 1)
    if name not in _DECIDE:
        raise ValueError(f"unknown scripted fighter {name!r}; known: {', '.join(NAMES)}")
    chosen = _DECIDE[name](observations, draws)
    if name == "idle":  # stands still, even off the stage
        return chosen.astype(np.int64)
    needed, recover = _recover(observations)
    return np.where(needed, recover, chosen).astype(np.int64)


def _check_seed(seed: object) -> None:
    if seed is not None and (
        isinstance(seed, (bool, np.bool_)) or not isinstance(seed, (int, np.integer)) or seed < 0
    ):
        raise ValueError(f"opponent seed must be a non-negative int or None, got {seed!r}")


def batch_opponent(opponent: Any, seed: int | None = None) -> Any:
    """A scripted fighter's name as a `VectorOpponent`, or an object that already has
    `act(observations (n, 41)) -> actions (n,)`; anything else is refused, naming it."""
    if isinstance(opponent, str):
        return VectorOpponent(opponent, seed)
    if callable(getattr(opponent, "act", None)):
        return opponent
    raise TypeError(
        "opponent must be a scripted fighter's name "
        f"({', '.join(NAMES)}) or an object with act(observations) -> actions for a batch, "
        f"got {opponent!r}"
    )


class VectorOpponent:
    """A scripted fighter for a batch: `act(observations (n, 41)) -> actions (n,)`."""

    def __init__(self, name: str, seed: int | None = None) -> None:
        if name not in NAMES:
            raise ValueError(f"unknown scripted fighter {name!r}; known: {', '.join(NAMES)}")
        _check_seed(seed)
        self.name = name
        self.rng = np.random.default_rng(seed)

    def reset(self, seed: int | None = None) -> None:
        _check_seed(seed)
        if seed is not None:
            self.rng = np.random.default_rng(seed)

    def act(self, observations: np.ndarray) -> np.ndarray:
        return scripted_actions(self.name, observations, self.rng.random(len(observations)))

    def __repr__(self) -> str:
        return f"VectorOpponent({self.name!r})"
