"""`Outcome`: how a fight stands after a step, one type for both backends, the envs and the tools;
`INFO_KEYS`: the per-fighter numbers every step's infos carry.

The int value is the code the compiled kernel writes into its `winner` array; `info` is the
string users see in `infos[agent]["winner"]` (and `EpisodeRecord.winner`, the replays).
"""

from __future__ import annotations

import enum

INFO_KEYS = (
    "health",
    "stocks",
    "hits_landed",  # hits not blocked, by attacker
    "hits_blocked",  # blocked hits, by defender
    "damage_dealt",
    "damage_taken",
    "rung_out",
    "knocked_out",
)


# An ended fight from one fighter's side: matches, Elo and the SB3 VecEnv's infos speak these.
SEAT_RESULTS = ("win", "loss", "draw")


class Outcome(enum.IntEnum):
    """The fight goes on, is a draw, or one fighter won (more stocks, then more health)."""

    GOING_ON = -2
    DRAW = -1
    FIGHTER_0 = 0
    FIGHTER_1 = 1

    @classmethod
    def of_leader(cls, leader: int | None) -> Outcome:
        """The ended fight's outcome from `Fight.winner()` (the leader's index, None: a draw)."""
        return cls.DRAW if leader is None else cls(leader)

    @classmethod
    def from_info(cls, winner: str | None) -> Outcome:
        """The outcome an `infos[agent]["winner"]` value (None: not there yet) stands for."""
        try:
            return _FROM_INFO[winner]
        except KeyError:
            allowed = ", ".join(repr(key) for key in _FROM_INFO)
            raise ValueError(f"winner = {winner!r} is not one of {allowed}") from None

    @property
    def info(self) -> str | None:
        """The `infos[agent]["winner"]` value: "fighter_0", "fighter_1", "draw"; None going on."""
        return _INFO[self]

    @property
    def over(self) -> bool:
        return self is not Outcome.GOING_ON

    def for_seat(self, seat: int) -> str:
        """The ended fight from the side of the fighter in `seat`: one of `SEAT_RESULTS`."""
        if not self.over:
            raise ValueError("the fight goes on; it has no result yet")
        if self is Outcome.DRAW:
            return "draw"
        return "win" if self == seat else "loss"


_INFO = {
    Outcome.GOING_ON: None,
    Outcome.DRAW: "draw",
    Outcome.FIGHTER_0: "fighter_0",
    Outcome.FIGHTER_1: "fighter_1",
}
_FROM_INFO = {info: outcome for outcome, info in _INFO.items()}
