"""A batch opponent that plays a random style, drawn again on request: the league's way to show
its learner play that no scripted fighter and no past snapshot shows (`[league] styles`;
docs/league.md, "Random styles, and two other levers").

Fresh exploiters beat the league's models with plain styles the pool never held: walking in and
shoving, crouching under punches and kicking, jumping over and jabbing. A style here is, for each
sixth of the clock, how the fighter moves (shares of forward, back, jump forward, jump back, jump,
crouch, block and idle, drawn from a Dirichlet, so that most styles lean hard on one or two moves)
and how often it attacks when an attack would reach (and with which). Like the scripted fighters it
steps back onto the stage when it is off it. The style is keyed to the clock, not to the fight, so
the opponent keeps no state per fight and a batch of fights at different times plays several
styles at once.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from vooga_env.game.actions import Action
from vooga_env.policies.batched import _away, _column, _jump_toward, _reach, _recover, _toward

PHASES = 6  # styles a game: one for each sixth of the clock
MOVES = 8  # forward, back, jump forward, jump back, jump, crouch, block, idle
CONCENTRATION = 0.4  # the Dirichlet's: below 1, most styles lean on a few moves


class RandomStyles:
    """`act(observations (n, 41)) -> actions (n,)` in the current style; `redraw()` draws a
    new one. Seeded: the same seed and calls give the same actions."""

    def __init__(self, seed: int | None = None) -> None:
        self.rng = np.random.default_rng(seed)
        self.redraw()

    def redraw(self) -> None:
        """A new style for each phase of the clock."""
        self.moves = self.rng.dirichlet(np.full(MOVES, CONCENTRATION), size=PHASES)
        self.attack = self.rng.random(PHASES)  # the chance to attack when in reach
        self.punch = self.rng.random(PHASES)  # the chance that attack is a punch, if both reach

    def act(self, observations: np.ndarray) -> np.ndarray:
        count = len(observations)
        time_left = _column(observations, "time_left").astype(np.float64)
        phase = np.clip((time_left * PHASES).astype(np.int64), 0, PHASES - 1)
        move_draw, attack_draw, punch_draw = self.rng.random((3, count))
        move = (move_draw[:, None] > self.moves[phase].cumsum(axis=1)).sum(axis=1)
        chosen = _moves(observations)[np.minimum(move, MOVES - 1), np.arange(count)]
        punch, kick = _reach(observations, "punch"), _reach(observations, "kick")
        strike = np.where(
            punch & ((punch_draw < self.punch[phase]) | ~kick), Action.PUNCH, Action.KICK
        )
        chosen = np.where((attack_draw < self.attack[phase]) & (punch | kick), strike, chosen)
        needed, recover = _recover(observations)
        return np.where(needed, recover, chosen).astype(np.int64)

    def state(self) -> dict[str, Any]:
        """The style and the generator, as JSON (a league's checkpoint keeps them)."""
        return {
            "rng": self.rng.bit_generator.state,
            "moves": self.moves.tolist(),
            "attack": self.attack.tolist(),
            "punch": self.punch.tolist(),
        }

    def load_state(self, state: dict[str, Any]) -> None:
        self.rng.bit_generator.state = state["rng"]
        self.moves = np.array(state["moves"])
        self.attack = np.array(state["attack"])
        self.punch = np.array(state["punch"])

    def __repr__(self) -> str:
        return "RandomStyles()"


def _moves(observations: np.ndarray) -> np.ndarray:
    """(MOVES, n): each move's action for each row, forward being toward the opponent."""
    count = len(observations)
    gap = _column(observations, "opponent_x")
    return np.stack(
        [
            _toward(gap),
            _away(gap),
            _jump_toward(gap),
            np.where(gap > 0, Action.JUMP_LEFT, Action.JUMP_RIGHT),
            np.full(count, Action.JUMP),
            np.full(count, Action.DOWN),
            np.full(count, Action.BLOCK),
            np.full(count, Action.IDLE),
        ]
    )
