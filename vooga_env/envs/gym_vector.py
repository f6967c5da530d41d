"""`FightVectorEnv`: the batched engine as a Gymnasium `VectorEnv`, one learner a fight.

    envs = gymnasium.make_vec("vooga_env/Fight-v0", num_envs=1024,
                              vectorization_mode="vector_entry_point", opponent="rush")

The vector form of `FightEnv`: fight i plays as `parallel_env(config).reset(seed=seed + i)`,
the learner in seat `seat`, all fights stepped by the compiled kernel in one call. A fight that
ends is reset in the same step (`AutoresetMode.SAME_STEP`): its last observation and info are in
`infos["final_obs"]` / `infos["final_info"]`, masked by `infos["_final_obs"]`, as Gymnasium's own
vector envs write them.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import gymnasium
import numpy as np
from gymnasium import spaces
from gymnasium.vector import AutoresetMode
from gymnasium.vector.utils import batch_space

from vooga_env.envs.obs_space import observation_space
from vooga_env.envs.render import frames_per_second
from vooga_env.envs.spectator import Spectator
from vooga_env.game.actions import Action, batch_actions, check_seat
from vooga_env.game.config import FightConfig
from vooga_env.game.outcome import Outcome
from vooga_env.game.pixels import pixel_spec
from vooga_env.kernel.vector_fight import VectorFight
from vooga_env.policies.batched import batch_opponent

# the per-fighter (2, N) arrays of VectorFight's info that a learner's info carries
_PER_FIGHTER = (
    "health",
    "stocks",
    "damage_dealt",
    "damage_taken",
    "hits_landed",
    "hits_blocked",
    "rung_out",
    "knocked_out",
)


class FightVectorEnv(gymnasium.vector.VectorEnv):
    """`num_envs` fights of one learner against `opponent` (a scripted fighter's name, or an
    object with `act(observations (n, 41)) -> actions (n,)`, which acts on the vectors).
    `obs_type` ("vector", "pixels", "both"; `pixel_size`, `pixel_rgb`) as FightParallelEnv's, for
    the learner. `render_mode="rgb_array"` draws fight 0; `threads` as `VectorFight`'s; other
    keywords are config overrides."""

    def __init__(
        self,
        num_envs: int,
        config: str | Path | FightConfig = "default",
        opponent: Any = "random",
        seat: int = 0,
        render_mode: str | None = None,
        threads: int = 1,
        obs_type: str = "vector",
        **overrides: Any,
    ) -> None:
        self._spectator: Spectator | None = None  # first: gymnasium's __del__ closes it
        seat = check_seat(seat)
        if render_mode not in (None, "rgb_array"):
            raise ValueError(f"render_mode must be None or 'rgb_array', got {render_mode!r}")
        pixel_spec(obs_type)  # an unknown obs_type is refused by its own name, not as "both"
        self.obs_type = obs_type
        inner = obs_type if obs_type == "vector" else "both"  # the opponent acts on the vectors
        seats = None if obs_type == "vector" else seat  # only the learner's images are drawn
        self.fights = VectorFight(
            num_envs, config, threads=threads, obs_type=inner, pixel_seats=seats, **overrides
        )
        self.num_envs = self.fights.num_fights
        self.opponent = batch_opponent(opponent)
        self.seat = seat
        self.render_mode = render_mode
        self.metadata = {
            "autoreset_mode": AutoresetMode.SAME_STEP,
            "render_modes": ["rgb_array"],
            "render_fps": frames_per_second(self.fights.config),
        }
        self._spectator = Spectator(self.fights.config) if render_mode else None
        self.single_observation_space = observation_space(obs_type, self.fights.pixels)
        self.single_action_space = spaces.Discrete(len(Action))
        self.observation_space = batch_space(self.single_observation_space, self.num_envs)
        self.action_space = batch_space(self.single_action_space, self.num_envs)
        self._observations: np.ndarray | None = None

    def reset(
        self, *, seed: int | list[int | None] | None = None, options: dict[str, Any] | None = None
    ) -> tuple[np.ndarray, dict[str, Any]]:
        """Reset every fight; `seed`: fight i gets `seed + i` (or `seed[i]`)."""
        if seed is not None or self._observations is None:
            self.fights.seed(seed)
        if self._spectator is not None:
            self._spectator.reset(self.fights.state.rng.get_state(0))
        observations = self.fights.reset()
        self._observations = self._vectors(observations)
        reset_opponent = getattr(self.opponent, "reset", None)
        if reset_opponent is not None:  # an int seed reseeds the opponent too; a list does not
            reset_opponent(int(seed) if isinstance(seed, (int, np.integer)) else None)
        return self._learner(observations), {}

    def step(self, actions: Any) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, dict]:
        if self._observations is None:
            raise RuntimeError("step() called before reset()")
        pairs = np.empty((self.num_envs, 2), dtype=np.int64)
        pairs[:, self.seat] = batch_actions("actions", actions, self.num_envs)
        pairs[:, 1 - self.seat] = batch_actions(
            f"opponent {self.opponent!r}: act(observations)",
            self.opponent.act(self._observations[:, 1 - self.seat]),
            self.num_envs,
        )
        observations, rewards, terminated, truncated, info = self.fights.step(pairs)
        if self._spectator is not None:
            self._spectator.step(int(pairs[0, 0]), int(pairs[0, 1]))
        self._observations = self._vectors(observations)
        return (
            self._learner(observations),
            rewards[:, self.seat],
            terminated,
            truncated,
            self._infos(info),
        )

    def render(self) -> np.ndarray | None:
        """Fight 0's frame, (H, W, 3) uint8, when made with `render_mode="rgb_array"`."""
        return None if self._spectator is None else self._spectator.render()

    def close_extras(self, **kwargs: Any) -> None:
        if self._spectator is not None:
            self._spectator.close()

    def _learner(self, observations: Any) -> Any:
        """The learner's seat of the batch's observations, as `obs_type` asks."""
        if self.obs_type == "vector":
            return observations[:, self.seat]
        if self.obs_type == "pixels":
            return observations["pixels"]
        return {"vector": observations["vector"][:, self.seat], "pixels": observations["pixels"]}

    def _vectors(self, observations: Any) -> np.ndarray:
        return observations if self.obs_type == "vector" else observations["vector"]

    def _infos(self, info: dict[str, Any]) -> dict[str, Any]:
        """The learner's events for every fight, and `final_obs`/`final_info` where one ended."""
        infos = {key: info[key][self.seat] for key in _PER_FIGHTER}
        done = np.zeros(self.num_envs, dtype=bool)
        done[info["done_index"]] = True
        if done.any():
            final_obs = np.full(self.num_envs, None, dtype=object)
            finals = self._learner(info["final_observation"])
            for row, fight in enumerate(info["done_index"].tolist()):
                final_obs[fight] = _row(finals, row)
            winner = np.full(self.num_envs, None, dtype=object)
            for fight in info["done_index"].tolist():
                winner[fight] = Outcome(int(info["winner"][fight])).info
            final_info = {**infos, "winner": winner}
            final_info.update({f"_{key}": done for key in list(final_info)})
            infos.update(final_obs=final_obs, _final_obs=done, final_info=final_info)
            infos["_final_info"] = done
        return infos


def _row(observations: Any, row: int) -> Any:
    """Row `row` of a batch of observations (an array, or a dict of arrays)."""
    if isinstance(observations, dict):
        return {key: value[row] for key, value in observations.items()}
    return observations[row]
