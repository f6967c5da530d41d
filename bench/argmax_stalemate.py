"""Where a model's argmax stands still, and whether one move would get it out against everyone.

    python -m bench.argmax_stalemate MODEL --against shover runs/league/snapshots/snapshot_N.zip

A late league model's argmax can walk into shover for a whole game: both fighters push, neither
moves, and nothing in the observation changes but the clock (docs/league.md, "A stalemate only
the argmax keeps"). This plays the model's argmax against each `--against` (a scripted fighter's
name, or a saved model sampling its actions, as the league's snapshots play) over `--games`
batched games, half in each seat, and counts the steps that stand still: both fighters on the
ground, neither moving nor attacking, a punch in reach, and the argmax walking in. Then it plays
the same games with a punch, a kick or a jump in place of that walk: a move that wins against one
opponent and loses against another is a choice one observation cannot make.
"""

from __future__ import annotations

import argparse
from pathlib import Path
from typing import Any

import numpy as np

from agents.common import _positive
from vooga_env.game.actions import Action
from vooga_env.game.observations import OBSERVATION_NAMES
from vooga_env.policies import SCRIPTED
from vooga_env.policies.models import FrozenPolicy, MLPPolicy, frozen_batch, load_model
from vooga_env.tools.batch_match import batch_match

_I = {name: index for index, name in enumerate(OBSERVATION_NAMES)}
MOVES = {"walk": None, "punch": Action.PUNCH, "kick": Action.KICK, "jump": Action.JUMP}
"""What replaces the argmax's walk at a standing-still step ("walk": nothing, the model as is)."""


def standing_still(observations: np.ndarray, actions: np.ndarray) -> np.ndarray:
    """Rows (n,) where both fighters are on the ground, neither moves or attacks, a punch would
    reach, and `actions` walk toward the opponent: a push that changes nothing but the clock."""
    o = observations

    def both(name: str) -> np.ndarray:
        return np.stack([o[:, _I[f"self_{name}"]], o[:, _I[f"opponent_{name}"]]], axis=1)

    still = (both("on_ground") > 0).all(1) & (np.abs(both("vx")) < 0.01).all(1)
    still &= (both("punching") == 0).all(1) & (both("kicking") == 0).all(1)
    toward = np.where(o[:, _I["opponent_x"]] > 0, Action.RIGHT, Action.LEFT)
    return still & (o[:, _I["self_punch_reach"]] > 0) & (actions == toward)


class Replaced:
    """An MLP fighter (`MLPPolicy`) as a batch player whose action at a standing-still step is
    `move` instead (None: kept); it counts those steps and sums its action probabilities there."""

    def __init__(self, policy: MLPPolicy, move: Action | None) -> None:
        self.policy = policy
        self.move = move
        self.still_steps = 0
        self.steps = 0
        self.probabilities = np.zeros(len(Action))

    def reset(self, seed: int | None = None) -> None:
        self.policy.reset(seed)

    def act(self, observations: np.ndarray) -> np.ndarray:
        actions = self.policy.act_batch(observations)
        still = standing_still(observations, actions)
        self.still_steps += int(still.sum())
        self.steps += len(observations)
        if still.any():
            logits = self.policy.logits(observations[still])
            odds = np.exp(logits - logits.max(axis=1, keepdims=True))
            self.probabilities += (odds / odds.sum(axis=1, keepdims=True)).sum(axis=0)
        return actions if self.move is None else np.where(still, self.move, actions)


def stalemates(model: Any, against: list[str], games: int, seed: int) -> list[dict[str, Any]]:
    """Per opponent: the standing-still share of the argmax's steps, its mean probabilities
    there, and the model's wins/draws/losses with each move of MOVES in place of the walk."""
    rows = []
    for spec in against:
        row: dict[str, Any] = {"opponent": spec, "results": {}}
        saved = None if spec in SCRIPTED else load_model(spec)  # it samples, as snapshots do
        for move_name, move in MOVES.items():
            player = Replaced(FrozenPolicy(model, "model", True), move)
            other = spec if saved is None else frozen_batch(saved, Path(spec).stem, False, seed + 2)
            result = batch_match(player, other, games, seed)
            row["results"][move_name] = [result[key] for key in ("wins", "draws", "losses")]
            if move is None:
                row["still_share"] = player.still_steps / player.steps
                mean = (player.probabilities / max(player.still_steps, 1)).tolist()
                row["probabilities"] = dict(zip((a.name.lower() for a in Action), mean))
        rows.append(row)
    return rows


def format_rows(rows: list[dict[str, Any]]) -> str:
    head = ["opponent", "still", "walk p", *(f"{name} w/d/l" for name in MOVES)]
    lines = ["  ".join(head)]
    for row in rows:
        cells = [Path(row["opponent"]).stem, f"{row['still_share']:.0%}"]
        cells.append(f"{row['probabilities']['right'] + row['probabilities']['left']:.2f}")
        cells += ["/".join(map(str, row["results"][name])) for name in MOVES]
        lines.append("  ".join(cells))
    return "\n".join(lines)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("model", type=Path, help="a saved PPO model (.zip)")
    parser.add_argument(
        "--against", nargs="+", default=["shover"],
        help="scripted fighters' names or saved models (these sample their actions)",
    )  # fmt: skip
    parser.add_argument("--games", type=_positive, default=40)
    parser.add_argument("--seed", type=int, default=5)
    args = parser.parse_args(argv)
    if not args.model.is_file():
        parser.error(f"model {str(args.model)!r}: no such file (a saved PPO model, .zip)")
    for spec in args.against:
        if spec not in SCRIPTED and not Path(spec).is_file():
            parser.error(
                f"--against {spec!r}: neither a scripted fighter ({', '.join(SCRIPTED)}) "
                "nor a saved model's file"
            )
    print(format_rows(stalemates(load_model(args.model), args.against, args.games, args.seed)))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
