"""`FightVecEnv`: the batched engine as a stable-baselines3 `VecEnv` (no SuperSuit in the path).

Two ways to fill the slots:

- `opponent=None` (self-play with parameter sharing): 2N slots, slot 2i is fight i's fighter_0
  and slot 2i + 1 its fighter_1; one policy plays both seats (the observations are mirrored).
- `opponent="rush"` (any scripted fighter's name, or an object with `act(observations) ->
  actions` for a batch): N slots, the learner in seat `seat` of every fight, the opponent in the
  other.

SB3's conventions: `reset()` returns the observations only; `seed(seed)` seeds fight i with
`seed + i` at the next `reset()`; a fight that ends is reset at once, and its slots' infos carry
`terminal_observation`, `TimeLimit.truncated` (True when the time ran out) and `winner`
("win", "loss" or "draw", from the slot's side). With `info_events=True` every step's infos
also carry the slot's `damage_dealt`, `damage_taken`, `hits_landed`, `hits_blocked`, `rung_out`
and `knocked_out` (off by default: a dict per slot and step costs more than the fights do).
"""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path
from typing import Any

import numpy as np
from gymnasium import spaces
from stable_baselines3.common.vec_env import VecEnv

from vooga_env.actions import Action
from vooga_env.config import FightConfig
from vooga_env.observations import HIGH, LOW, OBSERVATION_SIZE
from vooga_env.vector.engine import VectorFight
from vooga_env.vector.opponents import VectorOpponent

_EVENTS = ("damage_dealt", "damage_taken", "hits_landed", "hits_blocked", "rung_out", "knocked_out")


def _opponent_actions(opponent: Any, observations: np.ndarray) -> np.ndarray:
    """The opponent's actions for the batch, or an error that blames the opponent."""
    actions = np.asarray(opponent.act(observations))
    size = len(observations)
    if actions.shape != (size,) or not np.issubdtype(actions.dtype, np.integer):
        raise ValueError(
            f"opponent {opponent!r}: act(observations) must return {size} int actions "
            f"(shape ({size},)), got {actions.dtype} of shape {actions.shape}"
        )
    if size and (actions.min() < 0 or actions.max() >= len(Action)):
        raise ValueError(
            f"opponent {opponent!r}: actions must be in 0..{len(Action) - 1}, got {actions!r}"
        )
    return actions


class FightVecEnv(VecEnv):
    """N batched fights as an SB3 VecEnv: 2N self-play slots, or N slots against an opponent."""

    def __init__(
        self,
        num_fights: int,
        config: str | Path | FightConfig = "default",
        opponent: Any = None,
        seat: int = 0,
        backend: str = "auto",
        opponent_seed: int | None = None,
        info_events: bool = False,
        **overrides: Any,
    ) -> None:
        if seat not in (0, 1):
            raise ValueError(f"seat must be 0 or 1, got {seat!r}")
        self.fights = VectorFight(num_fights, config, backend=backend, **overrides)
        self.render_mode = None
        if opponent is None:
            self.opponent = None
        elif isinstance(opponent, str):
            self.opponent = VectorOpponent(opponent, opponent_seed)
        elif hasattr(opponent, "act"):
            self.opponent = opponent
        else:
            raise TypeError(
                f"opponent must be None (self-play), a scripted fighter's name or an object with "
                f"act(observations) -> actions, got {opponent!r}"
            )
        self.seat = seat
        self.info_events = info_events
        self.self_play = self.opponent is None
        slots = 2 * num_fights if self.self_play else num_fights
        super().__init__(
            slots,
            spaces.Box(LOW, HIGH, (OBSERVATION_SIZE,), np.float32),
            spaces.Discrete(len(Action)),
        )
        self._fight_seeds: list[int] | None = None
        self._actions: np.ndarray | None = None
        self._observations: np.ndarray | None = None  # (N, 2, 41), the latest

    @property
    def config(self) -> FightConfig:
        return self.fights.config

    # --- VecEnv API
    def seed(self, seed: int | None = None) -> Sequence[int | None]:
        """Fight i gets `seed + i` at the next reset (both of its slots share the fight's seed)."""
        if seed is None:
            seed = int(np.random.randint(0, np.iinfo(np.uint32).max, dtype=np.uint32))
        self._fight_seeds = [seed + i for i in range(self.fights.num_fights)]
        per_slot = 2 if self.self_play else 1
        return [s for s in self._fight_seeds for _ in range(per_slot)]

    def reset(self) -> np.ndarray:
        observations = self.fights.reset(seed=self._fight_seeds)
        self._fight_seeds = None
        self._reset_seeds()
        self._reset_options()
        if self.opponent is not None and hasattr(self.opponent, "reset"):
            self.opponent.reset()
        self._observations = observations
        return self._slots(observations)

    def step_async(self, actions: np.ndarray) -> None:
        actions = np.asarray(actions)
        if actions.size != self.num_envs or actions.ndim > 2:
            raise ValueError(
                f"actions must hold one action per slot, {self.num_envs} "
                f"(shape ({self.num_envs},)), got shape {actions.shape}"
            )
        self._actions = actions

    def step_wait(self):
        if self._actions is None or self._observations is None:
            raise RuntimeError("step_wait() without reset() and step_async()")
        actions = self._actions.reshape(-1)
        if self.self_play:
            pairs = actions.reshape(-1, 2)
        else:
            pairs = np.empty((self.fights.num_fights, 2), dtype=np.int64)
            pairs[:, self.seat] = actions
            opponent_obs = self._observations[:, 1 - self.seat]
            pairs[:, 1 - self.seat] = _opponent_actions(self.opponent, opponent_obs)
        observations, rewards, terminated, truncated, info = self.fights.step(pairs)
        self._observations = observations
        self._actions = None
        done = terminated | truncated
        infos = self._infos(info, truncated)
        if self.self_play:
            return (
                observations.reshape(-1, OBSERVATION_SIZE),
                rewards.reshape(-1).astype(np.float32),
                np.repeat(done, 2),
                infos,
            )
        return (
            observations[:, self.seat],
            rewards[:, self.seat].astype(np.float32),
            done,
            infos,
        )

    def close(self) -> None:
        pass

    def get_attr(self, attr_name: str, indices: Any = None) -> list[Any]:
        return [getattr(self, attr_name) for _ in self._get_indices(indices)]

    def set_attr(self, attr_name: str, value: Any, indices: Any = None) -> None:
        setattr(self, attr_name, value)

    def env_method(self, method_name: str, *args: Any, indices: Any = None, **kwargs: Any):
        return [getattr(self, method_name)(*args, **kwargs) for _ in self._get_indices(indices)]

    def env_is_wrapped(self, wrapper_class: type, indices: Any = None) -> list[bool]:
        return [False for _ in self._get_indices(indices)]

    def get_images(self) -> Sequence[np.ndarray | None]:
        return [None for _ in range(self.num_envs)]

    # --- helpers
    def _slots(self, observations: np.ndarray) -> np.ndarray:
        if self.self_play:
            return observations.reshape(-1, OBSERVATION_SIZE)
        return observations[:, self.seat]

    def _infos(self, info: dict, truncated: np.ndarray) -> list[dict[str, Any]]:
        """One dict per slot: the step's events, and at a fight's end the SB3 keys and winner."""
        seats = (0, 1) if self.self_play else (self.seat,)
        if self.info_events:
            columns = {key: info[key].tolist() for key in _EVENTS}
            infos = [
                {key: columns[key][seat][fight] for key in _EVENTS}
                for fight in range(self.fights.num_fights)
                for seat in seats
            ]
        else:
            infos = [{} for _ in range(self.num_envs)]
        for row, fight in enumerate(info["done_index"].tolist()):
            winner = int(info["winner"][fight])
            for seat in seats:
                slot = fight * len(seats) + seats.index(seat)
                slot_info = infos[slot]
                slot_info["terminal_observation"] = info["final_observation"][row, seat]
                slot_info["TimeLimit.truncated"] = bool(truncated[fight])
                slot_info["winner"] = (
                    "draw" if winner < 0 else ("win" if winner == seat else "loss")
                )
        return infos

    def __repr__(self) -> str:
        against = "self-play" if self.self_play else f"vs {self.opponent!r} (seat {self.seat})"
        return f"FightVecEnv({self.fights!r}, {against})"
