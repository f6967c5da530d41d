"""`FightVecEnv`: the batched engine as a stable-baselines3 `VecEnv` (no SuperSuit in the path).

Two ways to fill the slots:

- `opponent=None` (self-play with parameter sharing): 2N slots, slot 2i is fight i's fighter_0
  and slot 2i + 1 its fighter_1; one policy plays both seats (the observations are mirrored).
- `opponent="rush"` (any scripted fighter's name, or an object with `act(observations) ->
  actions` for a batch): N slots, the learner in seat `seat` of every fight, the opponent in the
  other; `seat="alternate"` puts fight i's learner in seat i % 2, so that it trains in both
  (the observations are mirrored, so that matters only where a stage or the engine's order of
  the two fighters is not symmetric).

`obs_type` ("vector", "pixels" or "both", with `pixel_size` and `pixel_rgb`) as the single env's:
images (H, W, 1) uint8 per slot (grayscale with a channel axis, or (H, W, 3)), the shape
`CnnPolicy` and `VecFrameStack` take, or a dict for `MultiInputPolicy`; opponents act on the
vectors, so against one only the learner's images are drawn (`VectorFight`'s `pixel_seats`).

SB3's conventions: `reset()` returns the observations only; `seed(seed)` seeds fight i with
`seed + i` at the next `reset()` (and a scripted opponent named without `opponent_seed` draws from
`seed`, so the same seed and actions replay the same fights); a fight that ends is reset at once,
and its slots' infos carry `terminal_observation`, `TimeLimit.truncated` (True when the time ran
out), `winner` ("win", "loss" or "draw", from the slot's side) and `episode` (`r` return, `l`
length, `t` seconds since the env was made), as SB3's `Monitor` writes it, so PPO logs `ep_rew_mean`
with no wrapper. With `info_events=True` every step's infos also carry the slot's `damage_dealt`,
`damage_taken`, `hits_landed`, `hits_blocked`, `rung_out` and `knocked_out` (off by default: a dict
per slot and step costs more than the fights do).

`render_mode="rgb_array"`: `render()` draws fight 0 (a `Spectator` replays it on the physics
engine), so `VecVideoRecorder` works. `env_method("set_opponent", name)` swaps the opponent; the
slots share one batch, so `env_method`, `get_attr` and `set_attr` act on the batch once and
answer for every slot asked.
"""

from __future__ import annotations

import time
from collections.abc import Sequence
from pathlib import Path
from typing import Any

import numpy as np
from gymnasium import spaces
from stable_baselines3.common.vec_env import VecEnv

from vooga_env.envs.obs_space import observation_space
from vooga_env.envs.spectator import Spectator
from vooga_env.game.actions import Action, batch_actions, check_seat
from vooga_env.game.config import FightConfig
from vooga_env.game.outcome import Outcome
from vooga_env.game.pixels import pixel_spec
from vooga_env.kernel.vector_fight import VectorFight
from vooga_env.policies.batched import batch_opponent

_EVENTS = ("damage_dealt", "damage_taken", "hits_landed", "hits_blocked", "rung_out", "knocked_out")


class FightVecEnv(VecEnv):
    """N batched fights as an SB3 VecEnv: 2N self-play slots, or N slots against an opponent."""

    def __init__(
        self,
        num_fights: int,
        config: str | Path | FightConfig = "default",
        opponent: Any = None,
        seat: int | str = 0,
        backend: str = "auto",
        opponent_seed: int | None = None,
        info_events: bool = False,
        render_mode: str | None = None,
        threads: int = 1,
        obs_type: str = "vector",
        **overrides: Any,
    ) -> None:
        alternate = seat == "alternate"
        if not alternate:
            seat = check_seat(seat, "0, 1 or 'alternate'")
        if render_mode not in (None, "rgb_array"):
            raise ValueError(f"render_mode must be None or 'rgb_array', got {render_mode!r}")
        pixel_spec(obs_type)  # an unknown obs_type is refused by its own name, not as "both"
        self.obs_type = obs_type
        self.self_play = opponent is None
        self.fights = VectorFight(
            num_fights,
            config,
            backend=backend,
            threads=threads,
            obs_type=obs_type if obs_type == "vector" else "both",  # opponents act on vectors
            # against an opponent only the learner's images are drawn
            pixel_seats=None if self.self_play or obs_type == "vector" else seat,
            **overrides,
        )
        self.render_mode = render_mode
        self._spectator = Spectator(self.fights.config) if render_mode else None
        self.opponent = None if opponent is None else batch_opponent(opponent, opponent_seed)
        self._opponent_follows_seed = isinstance(opponent, str) and opponent_seed is None
        self.seat = seat
        fights = np.arange(num_fights)
        self._rows = fights
        self._seats = fights % 2 if alternate else np.full(num_fights, seat)
        self.info_events = info_events
        slots = 2 * num_fights if self.self_play else num_fights
        super().__init__(
            slots,
            observation_space(obs_type, self.fights.pixels, channel_axis=True),
            spaces.Discrete(len(Action)),
        )
        self._fight_seeds: list[int] | None = None
        self._actions: np.ndarray | None = None
        self._observations: np.ndarray | None = None  # (N, 2, 41), the latest
        self._returns = np.zeros(slots)
        self._lengths = np.zeros(slots, dtype=np.int64)
        self._start = time.time()

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

    def set_opponent(self, opponent: Any, seed: int | None = None) -> None:
        """Fight `opponent` (a scripted name or a batch `act`) from the next step on."""
        if self.self_play:
            raise ValueError("set_opponent: this FightVecEnv is self-play (opponent=None)")
        self.opponent = batch_opponent(opponent, seed)
        self._opponent_follows_seed = isinstance(opponent, str) and seed is None

    def reset(self) -> np.ndarray:
        seeded = self._fight_seeds is not None
        if seeded or self._observations is None:
            self.fights.seed(self._fight_seeds)  # None, the first time: from entropy
        if seeded and self._opponent_follows_seed:
            self.opponent.reset(self._fight_seeds[0])
        if self._spectator is not None:
            self._spectator.reset(self.fights.state.rng.get_state(0))
        everything = self.fights.reset()
        observations = self._vectors(everything)
        self._fight_seeds = None
        self._returns[:] = 0.0
        self._lengths[:] = 0
        self._reset_seeds()
        self._reset_options()
        if self.opponent is not None and hasattr(self.opponent, "reset"):
            self.opponent.reset()
        self._observations = observations
        return self._slots(everything)

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
            rows, seats = self._rows, self._seats
            pairs[rows, seats] = batch_actions("actions", actions, self.num_envs)
            opponent_obs = self._observations[rows, 1 - seats]
            pairs[rows, 1 - seats] = batch_actions(
                f"opponent {self.opponent!r}: act(observations)",
                self.opponent.act(opponent_obs),
                self.num_envs,
            )
        everything, rewards, terminated, truncated, info = self.fights.step(pairs)
        if self._spectator is not None:
            self._spectator.step(int(pairs[0, 0]), int(pairs[0, 1]))
        self._observations = self._vectors(everything)
        self._actions = None
        if self.self_play:
            slot_rewards, done = rewards.reshape(-1), np.repeat(terminated | truncated, 2)
        else:
            slot_rewards, done = rewards[self._rows, self._seats], terminated | truncated
        self._returns += slot_rewards
        self._lengths += 1
        infos = self._infos(info, truncated)
        return self._slots(everything), slot_rewards.astype(np.float32), done, infos

    def render(self, mode: str | None = None) -> np.ndarray | None:
        """Fight 0's frame, (H, W, 3) uint8, when made with `render_mode="rgb_array"`."""
        if self._spectator is None:
            return None
        if mode not in (None, "rgb_array"):
            raise ValueError(f"render mode must be 'rgb_array', got {mode!r}")
        return self._spectator.render()

    def close(self) -> None:
        if self._spectator is not None:
            self._spectator.close()

    def get_attr(self, attr_name: str, indices: Any = None) -> list[Any]:
        value = getattr(self, attr_name)
        return [value for _ in self._get_indices(indices)]

    def set_attr(self, attr_name: str, value: Any, indices: Any = None) -> None:
        setattr(self, attr_name, value)

    def env_method(self, method_name: str, *args: Any, indices: Any = None, **kwargs: Any):
        result = getattr(self, method_name)(*args, **kwargs)
        return [result for _ in self._get_indices(indices)]

    def env_is_wrapped(self, wrapper_class: type, indices: Any = None) -> list[bool]:
        return [False for _ in self._get_indices(indices)]

    def get_images(self) -> Sequence[np.ndarray | None]:
        return [self.render()] + [None] * (self.num_envs - 1)

    # --- helpers
    def _slots(self, observations: Any) -> Any:
        """The batch's observations as the slots', as `obs_type` asks: the vectors (N, 2, 41)
        and, in self-play, the images (N, 2, H, W[, C]) by slot; against an opponent the images
        are the learner's already (N, H, W[, C])."""
        if isinstance(observations, dict):
            pixels = self._channels(observations["pixels"])
            if self.self_play:
                pixels = pixels.reshape(-1, *pixels.shape[2:])
            if self.obs_type == "pixels":
                return pixels
            return {"vector": self._slots(observations["vector"]), "pixels": pixels}
        if self.self_play:
            return observations.reshape(-1, *observations.shape[2:])
        return observations[self._rows, self._seats]

    def _slot_seats(self, fight: int) -> list[tuple[int, int]]:
        """(slot, seat) for each learner slot of `fight`."""
        if self.self_play:
            return [(2 * fight, 0), (2 * fight + 1, 1)]
        return [(fight, int(self._seats[fight]))]

    def _vectors(self, observations: Any) -> np.ndarray:
        return observations if self.obs_type == "vector" else observations["vector"]

    def _infos(self, info: dict, truncated: np.ndarray) -> list[dict[str, Any]]:
        """One dict per slot: the step's events, and at a fight's end the SB3 keys and winner."""
        if self.info_events:
            columns = {key: info[key].tolist() for key in _EVENTS}
            infos = [
                {key: columns[key][seat][fight] for key in _EVENTS}
                for fight in range(self.fights.num_fights)
                for _, seat in self._slot_seats(fight)
            ]
        else:
            infos = [{} for _ in range(self.num_envs)]
        elapsed = round(time.time() - self._start, 6)
        finals = info["final_observation"]
        for row, fight in enumerate(info["done_index"].tolist()):
            winner = int(info["winner"][fight])
            for slot, seat in self._slot_seats(fight):
                slot_info = infos[slot]
                slot_info["terminal_observation"] = self._final(finals, row, seat)
                slot_info["TimeLimit.truncated"] = bool(truncated[fight])
                slot_info["winner"] = Outcome(winner).for_seat(seat)
                slot_info["episode"] = {
                    "r": float(self._returns[slot]),
                    "l": int(self._lengths[slot]),
                    "t": elapsed,
                }
                self._returns[slot] = 0.0
                self._lengths[slot] = 0
        return infos

    def _final(self, finals: Any, row: int, seat: int) -> Any:
        """One slot's last observation of an ended fight, as `obs_type` asks."""
        if not isinstance(finals, dict):
            return finals[row, seat]
        images = finals["pixels"][row, seat] if self.self_play else finals["pixels"][row]
        images = self._channels(images)
        if self.obs_type == "pixels":
            return images
        return {"vector": finals["vector"][row, seat], "pixels": images}

    def _channels(self, images: np.ndarray) -> np.ndarray:
        """Grayscale images with a channel axis, (..., H, W, 1), as SB3 takes images."""
        return images if self.fights.pixels.rgb else images[..., None]

    def __repr__(self) -> str:
        against = "self-play" if self.self_play else f"vs {self.opponent!r} (seat {self.seat})"
        return f"FightVecEnv({self.fights!r}, {against})"
