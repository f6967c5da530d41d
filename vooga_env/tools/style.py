"""How a fighter plays, counted from recorded games: how they ended, what it pressed, and its
punches and kicks attempted and landed.

`StyleStats.add(record, seat)` reads an `EpisodeRecord` played with `record_actions=True` and
`record_observations=True` (`run_match(..., record_actions=True, record_observations=True)`).
An attack is *attempted* when the fighter's own observation shows a punch (kick) starting: the
flag turns on, or its progress falls back to a fresh start. A hit (not blocked) is credited to
the attack the attacker is in after that step (or, if the move ended on it, the one before).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np

from vooga_env.game.actions import Action
from vooga_env.game.observations import OBSERVATION_NAMES

ENDINGS = ("ring_out", "ko", "time")
ATTACKS = ("punch", "kick")
_FLAG = {attack: OBSERVATION_NAMES.index(f"self_{attack}ing") for attack in ATTACKS}
_PROGRESS = OBSERVATION_NAMES.index("self_move_progress")


@dataclass
class StyleStats:
    """One fighter's style over games: endings, action counts, attacks attempted and landed."""

    games: int = 0
    steps: int = 0
    endings: dict[str, int] = field(default_factory=lambda: dict.fromkeys(ENDINGS, 0))
    actions: list[int] = field(default_factory=lambda: [0] * len(Action))
    attempted: dict[str, int] = field(default_factory=lambda: dict.fromkeys(ATTACKS, 0))
    landed: dict[str, int] = field(default_factory=lambda: dict.fromkeys(ATTACKS, 0))

    def add(self, record: Any, seat: int) -> None:
        """Count one finished game, in which this fighter sat in `seat`."""
        if record.actions is None or record.observations is None or record.step_hits is None:
            raise ValueError(
                "StyleStats needs games recorded with record_actions=True and "
                "record_observations=True"
            )
        self.games += 1
        self.steps += record.steps
        self.endings[record.ended_by] += 1
        for pair in record.actions:
            self.actions[pair[seat]] += 1
        seen = np.stack(record.observations)[:, seat]  # (steps + 1, 41): before each step
        for attack, column in _FLAG.items():
            on = seen[:, column] > 0
            fresh = on[1:] & (~on[:-1] | (seen[1:, _PROGRESS] < seen[:-1, _PROGRESS]))
            self.attempted[attack] += int(fresh.sum())
        for step, hits in enumerate(record.step_hits):
            if hits[seat]:
                self.landed[self._attack(seen, step)] += hits[seat]

    @staticmethod
    def _attack(seen: np.ndarray, step: int) -> str:
        """The attack that landed step `step`'s hit: the one shown after the step, or before."""
        for row in (seen[step + 1], seen[step]):
            for attack, column in _FLAG.items():
                if row[column] > 0:
                    return attack
        raise ValueError(f"a hit on step {step} with no attack under way in the observations")

    def to_dict(self) -> dict[str, Any]:
        total = max(sum(self.actions), 1)
        return {
            "games": self.games,
            "endings": dict(self.endings),
            "actions": {action.name.lower(): self.actions[action] / total for action in Action},
            "attacks": {
                attack: {
                    "attempted": self.attempted[attack],
                    "landed": self.landed[attack],
                    "per_game": self.attempted[attack] / max(self.games, 1),
                }
                for attack in ATTACKS
            },
        }
