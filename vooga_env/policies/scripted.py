"""The scripted fighters, by name in `SCRIPTED`.

Scripted fighters read only their own (mirrored) observation and are deterministic given the seed
passed to `reset`; `batched.py` plays the same styles on arrays of observations.
"""

from __future__ import annotations

import numpy as np

from vooga_env.game.actions import Action
from vooga_env.game.observations import OBSERVATION_NAMES
from vooga_env.policies.base import Policy

_I = {name: index for index, name in enumerate(OBSERVATION_NAMES)}


class Scripted(Policy):
    """A scripted fighter with its own seeded random generator."""

    def __init__(self, seed: int | None = None) -> None:
        self.rng = np.random.default_rng(seed)

    def reset(self, seed: int | None = None) -> None:
        if seed is not None:
            self.rng = np.random.default_rng(seed)


class Idle(Scripted):
    """Stands still: the floor of the ladder."""

    name = "idle"

    def act(self, observation: np.ndarray) -> int:
        return int(Action.IDLE)


class RandomFighter(Scripted):
    """Uniformly random actions."""

    name = "random"

    def act(self, observation: np.ndarray) -> int:
        return int(self.rng.integers(len(Action)))


def _gap(observation: np.ndarray) -> float:
    """Signed x distance to the opponent in own frame (half-arena widths; > 0: it is in front)."""
    return float(observation[_I["opponent_x"]])


def _reach(observation: np.ndarray, who: str, move: str) -> bool:
    """Would `who`'s ('self' or 'opponent') `move`, started now, touch the other fighter?"""
    return bool(observation[_I[f"{who}_{move}_reach"]])


def _toward(gap: float) -> int:
    return Action.RIGHT if gap > 0 else Action.LEFT


def _away(gap: float) -> int:
    return Action.LEFT if gap > 0 else Action.RIGHT


def _recover(observation: np.ndarray) -> int | None:
    """Off the stage or falling beside it: head back towards the stage's centre."""
    left = observation[_I["stage_left"]]
    right = observation[_I["stage_right"]]
    if left >= 0 and right >= 0:
        return None
    back = Action.RIGHT if left < 0 else Action.LEFT
    falling = observation[_I["self_vy"]] > 0 and not observation[_I["self_on_ground"]]
    if falling and observation[_I["self_jumps_left"]] > 0:
        return Action.JUMP_RIGHT if back == Action.RIGHT else Action.JUMP_LEFT
    return back


class Rush(Scripted):
    """Closes in and attacks: punches up close, kicks from a little further."""

    name = "rush"

    def act(self, observation: np.ndarray) -> int:
        recover = _recover(observation)
        if recover is not None:
            return recover
        if _reach(observation, "self", "punch"):
            return Action.PUNCH
        if _reach(observation, "self", "kick") and self.rng.random() < 0.5:
            return Action.KICK
        return _toward(_gap(observation))


class Turtle(Scripted):
    """Stays at kick range and blocks; punishes an attack that missed or was blocked."""

    name = "turtle"

    def act(self, observation: np.ndarray) -> int:
        recover = _recover(observation)
        if recover is not None:
            return recover
        if not _reach(observation, "self", "kick"):
            return _toward(_gap(observation))
        punch = _reach(observation, "self", "punch")
        attacking = observation[_I["opponent_punching"]] or observation[_I["opponent_kicking"]]
        if attacking and observation[_I["opponent_move_progress"]] < 0.6:
            return Action.BLOCK
        if attacking or observation[_I["opponent_hitstun"]] > 0 or self.rng.random() >= 0.7:
            return Action.PUNCH if punch else Action.KICK
        return Action.BLOCK


class Zoner(Scripted):
    """Keeps the opponent at kick range: kicks when it steps in, backs off when it gets closer."""

    name = "zoner"

    def act(self, observation: np.ndarray) -> int:
        recover = _recover(observation)
        if recover is not None:
            return recover
        gap = _gap(observation)
        behind = observation[_I["stage_left"]] if gap > 0 else observation[_I["stage_right"]]
        if _reach(observation, "self", "punch") and behind > 0.08:
            return _away(gap)
        if _reach(observation, "self", "kick"):
            return Action.KICK
        return _toward(gap)


class EdgeGuard(Scripted):
    """Holds the centre: presses an opponent who stands between it and that side's edge.

    Kicks (more knockback) when pressing, punches and blocks when it is the one near an edge.
    """

    name = "edge_guard"

    def act(self, observation: np.ndarray) -> int:
        recover = _recover(observation)
        if recover is not None:
            return recover
        gap = _gap(observation)
        own_offset = (observation[_I["stage_left"]] - observation[_I["stage_right"]]) / 2
        opponent_offset = own_offset + gap / 2  # both in arena widths, > 0: right of centre
        pressing = gap * opponent_offset > 0
        if _reach(observation, "self", "kick"):
            attacking = observation[_I["opponent_punching"]] or observation[_I["opponent_kicking"]]
            if attacking and not pressing:
                return Action.BLOCK
            punch = _reach(observation, "self", "punch")
            return Action.KICK if pressing or not punch else Action.PUNCH
        if pressing or abs(own_offset) < 0.05:
            return _toward(gap)
        return Action.LEFT if own_offset > 0 else Action.RIGHT


def _behind(observation: np.ndarray, gap: float) -> float:
    """Own distance to the stage edge behind (away from the opponent), in arena widths."""
    return float(observation[_I["stage_left"]] if gap > 0 else observation[_I["stage_right"]])


def _attacking(observation: np.ndarray) -> bool:
    return bool(observation[_I["opponent_punching"]] or observation[_I["opponent_kicking"]])


def _threatened(observation: np.ndarray) -> bool:
    """Could the opponent's punch or kick, started now, touch this fighter?"""
    return _reach(observation, "opponent", "punch") or _reach(observation, "opponent", "kick")


class Drawn(Scripted):
    """A scripted fighter that draws one number a step and decides with `choose(obs, draw)`
    (a pure function, so the batched version and the mixed-up player can reuse the choice)."""

    def act(self, observation: np.ndarray) -> int:
        recover = _recover(observation)
        draw = self.rng.random()
        return int(recover if recover is not None else self.choose(observation, draw))

    @staticmethod
    def choose(observation: np.ndarray, draw: float) -> int:
        raise NotImplementedError


class Aerial(Drawn):
    """Hops in from mid range (unless that would carry it off the stage beyond the opponent)
    and strikes from the air: punches close, kicks a little further."""

    name = "aerial"

    @staticmethod
    def choose(observation: np.ndarray, draw: float) -> int:
        gap = _gap(observation)
        if _reach(observation, "self", "punch"):
            return Action.PUNCH
        if _reach(observation, "self", "kick"):
            return Action.KICK
        grounded = observation[_I["self_on_ground"]] > 0
        room = _behind(observation, -gap) - abs(gap) / 2  # beyond the opponent, arena widths
        if grounded and abs(gap) < 0.6 and room > 0.15 and draw < 0.5:
            return Action.JUMP_RIGHT if gap > 0 else Action.JUMP_LEFT
        return _toward(gap)


class Punisher(Drawn):
    """Baits at the edge of the opponent's reach, blocks or backs off from an attack, and
    strikes while the opponent recovers from one; jumps over when cornered."""

    name = "punisher"

    @staticmethod
    def choose(observation: np.ndarray, draw: float) -> int:
        gap = _gap(observation)
        attacking = _attacking(observation)
        late = observation[_I["opponent_move_progress"]] >= 0.5
        if observation[_I["opponent_hitstun"]] > 0 or (attacking and late):
            if _reach(observation, "self", "punch"):
                return Action.PUNCH
            return Action.KICK if _reach(observation, "self", "kick") else _toward(gap)
        if not attacking and _reach(observation, "self", "kick") and draw < 0.3:
            return Action.KICK
        if _threatened(observation):
            if attacking:
                return Action.BLOCK
            if _behind(observation, gap) > 0.1:
                return _away(gap)
            return Action.JUMP_RIGHT if gap > 0 else Action.JUMP_LEFT
        return _toward(gap) if draw < 0.6 else Action.IDLE


class Spacer(Drawn):
    """Keeps its distance low: ducks punches, kicks from a crouch (low), steps back when close."""

    name = "spacer"

    @staticmethod
    def choose(observation: np.ndarray, draw: float) -> int:
        gap = _gap(observation)
        punch_coming = observation[_I["opponent_punching"]] > 0
        if punch_coming and _reach(observation, "opponent", "punch"):
            return Action.DOWN
        if _reach(observation, "self", "punch") and _behind(observation, gap) > 0.08:
            return _away(gap)
        if _reach(observation, "self", "kick"):
            crouched = observation[_I["self_crouching"]] > 0
            return Action.KICK if crouched or draw < 0.4 else Action.DOWN
        return _toward(gap)


class EdgeGrappler(Drawn):
    """Pushes the opponent towards the edge behind it with punches, and kicks it off from there;
    blocks a punch, and jumps over when it is the one cornered."""

    name = "edge_grappler"

    @staticmethod
    def choose(observation: np.ndarray, draw: float) -> int:
        gap = _gap(observation)
        ahead = observation[_I["stage_right"]] if gap > 0 else observation[_I["stage_left"]]
        cornered = ahead - abs(gap) / 2 < 0.15  # the opponent's room behind it, arena widths
        if _reach(observation, "self", "punch"):
            return Action.KICK if cornered else Action.PUNCH
        if _reach(observation, "self", "kick") and (cornered or draw < 0.2):
            return Action.KICK
        if _attacking(observation) and _reach(observation, "opponent", "punch"):
            return Action.BLOCK
        if _behind(observation, gap) < 0.1 and draw < 0.5:
            return Action.JUMP_RIGHT if gap > 0 else Action.JUMP_LEFT
        return _toward(gap)


class Shover(Drawn):
    """Walks into the opponent and shoves it off the stage with its body; never attacks, and
    blocks an attack that could reach it. A fighter that crouches when pressed is walked off."""

    name = "shover"

    @staticmethod
    def choose(observation: np.ndarray, draw: float) -> int:
        if _attacking(observation) and _threatened(observation):
            return Action.BLOCK
        return _toward(_gap(observation))


def _standing(observation: np.ndarray) -> int:
    """+1 if it would win were time to run out now (more stocks, then more health), -1 if it
    would lose, 0 on a draw."""
    own = (observation[_I["self_stocks"]], observation[_I["self_health"]])
    other = (observation[_I["opponent_stocks"]], observation[_I["opponent_health"]])
    return int(own > other) - int(own < other)


class Staller(Drawn):
    """Plays for time: crouches where it stands and punches from the crouch without end (a low
    jab that meets a fighter walking in) while it leads, or while it is level in the first half
    of the clock; otherwise closes in and attacks, blocking what could reach it, until it leads
    again. A fighter that waits is hit in the second half and loses on time: what a fresh
    exploiter did to the league's model after one punch (docs/league.md, "Playing for time")."""

    name = "staller"

    @staticmethod
    def choose(observation: np.ndarray, draw: float) -> int:
        standing = _standing(observation)
        if standing > 0 or (standing == 0 and observation[_I["time_left"]] > 0.5):
            return Action.PUNCH if observation[_I["self_crouching"]] else Action.DOWN
        if _attacking(observation) and _threatened(observation):
            return Action.BLOCK
        if _reach(observation, "self", "punch"):
            return Action.PUNCH
        return Action.KICK if _reach(observation, "self", "kick") else _toward(_gap(observation))


class MixUp(Drawn):
    """Changes style every twelfth of the clock: aerial, punisher, edge grappler in turn."""

    name = "mixup"
    STYLES = (Aerial, Punisher, EdgeGrappler)

    @staticmethod
    def choose(observation: np.ndarray, draw: float) -> int:
        phase = int(float(observation[_I["time_left"]]) * 12.0) % len(MixUp.STYLES)
        return MixUp.STYLES[phase].choose(observation, draw)


SCRIPTED: dict[str, type[Scripted]] = {
    cls.name: cls
    for cls in (
        Idle,
        RandomFighter,
        Rush,
        Turtle,
        Zoner,
        EdgeGuard,
        Aerial,
        Punisher,
        Spacer,
        EdgeGrappler,
        MixUp,
        Shover,
        Staller,
    )
}
