"""`VectorFight`: N fights stepped together, the single env's rules and results, auto-reset.

    fights = VectorFight(1024, config="default")
    observations = fights.reset(seed=0)             # (N, 2, 41) float32; fight i seeded 0 + i
    observations, rewards, terminated, truncated, info = fights.step(actions)  # actions (N, 2)

Fight i behaves exactly as `parallel_env(config).reset(seed=seed + i)` followed by the same actions,
`reset()` (no seed) whenever it ends: same positions, velocities, observations, rewards, dones. A
fight that ends is reset in the same `step`; its last observation is `info["final_observation"]`.
The fights are stepped by the numba kernel (`compiled.py`; numba is a core dependency), in
`threads` chunks at once (default one; more is a choice for an otherwise idle machine); the
results do not depend on it. The engine backend of the single env (`parallel_env(backend=
"engine")`) is the readable reference the kernel is tested against.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np

from vooga_env.game.config import FightConfig, load_config
from vooga_env.game.observations import OBSERVATION_SIZE
from vooga_env.game.outcome import Outcome
from vooga_env.game.pixels import compose, pixel_spec
from vooga_env.kernel.params import FightParams, check_supported
from vooga_env.kernel.state import FightState, StepEvents

BACKENDS = ("auto", "numba")  # one backend; "auto" kept for the callers that name it
INSTALL_NUMBA = "VectorFight needs numba (a core dependency of vooga-env): pip install numba"


def numba_available() -> bool:
    try:
        import numba  # noqa: F401
    except ImportError:
        return False
    return True


class VectorFight:
    """N independent fights in arrays (`state`: a `FightState`), stepped with one call."""

    def __init__(
        self,
        num_fights: int,
        config: str | Path | FightConfig = "default",
        backend: str = "auto",
        reward_fn: Any = None,
        threads: int = 1,
        obs_type: str = "vector",
        pixel_size: tuple[int, int] = (84, 84),
        pixel_rgb: bool = False,
        pixel_seats: Any = None,
        **overrides: Any,
    ) -> None:
        self.obs_type = obs_type
        self.pixels = pixel_spec(obs_type, pixel_size, pixel_rgb)
        if isinstance(num_fights, bool) or not isinstance(num_fights, (int, np.integer)):
            raise TypeError(f"num_fights must be an int, got {num_fights!r}")
        if num_fights < 1:
            raise ValueError(f"num_fights must be >= 1, got {num_fights}")
        if backend not in BACKENDS:
            raise ValueError(
                f"backend must be one of {', '.join(BACKENDS)}, got {backend!r} (the numpy "
                "backend is gone: the numba kernel runs every batch)"
            )
        self.config = load_config(config, **overrides)
        check_supported(self.config, reward_fn)
        if not numba_available():
            raise ImportError(INSTALL_NUMBA)
        from vooga_env.kernel.cache import load_kernel

        self.backend = "numba"
        self.num_fights = int(num_fights)
        self.params = FightParams.from_config(self.config)
        self._kernel = load_kernel().Kernel(self.params)
        self.state = FightState(self.num_fights)
        self._all = np.arange(self.num_fights)
        self.threads = self._thread_count(threads)
        self._bounds = np.linspace(0, self.num_fights, self.threads + 1).round().astype(np.int64)
        self._needs_reset = True
        self._seeded = False
        self._raster = None
        if self.pixels is not None:
            from vooga_env.kernel.cache import load_raster

            self._raster = load_raster().Rasteriser(self.params, self.pixels)
        self.pixel_seats = self._check_pixel_seats(pixel_seats)

    def _check_pixel_seats(self, seats: Any) -> np.ndarray | None:
        """The seat whose image each fight draws: 0 or 1 for all, "alternate" (i % 2), or one
        per fight; None: both seats' images, (N, 2, H, W[, 3])."""
        if seats is None:
            return None
        if self.pixels is None:
            raise ValueError(
                f"pixel_seats is for pixel observations, not obs_type={self.obs_type!r}"
            )
        if isinstance(seats, str) and seats == "alternate":
            return self._all % 2
        array = np.asarray(seats)
        if array.ndim == 0:
            array = np.full(self.num_fights, array)
        integers = np.issubdtype(array.dtype, np.integer)
        if not integers or array.shape != (self.num_fights,) or not np.isin(array, (0, 1)).all():
            raise ValueError(
                f"pixel_seats = {seats!r} is not allowed: 0, 1, 'alternate' or one seat (0 or 1) "
                f"per fight, {self.num_fights} of them"
            )
        return array.astype(np.int64)

    def _thread_count(self, threads: int) -> int:
        """Threads for the step, one unless asked: a second thread gains 1.5-2x on an idle
        machine but waits on its descheduled worker when another process (a trainer) holds the
        other core, down to 0.04x of one thread."""
        if isinstance(threads, bool) or not isinstance(threads, (int, np.integer)):
            raise TypeError(f"threads must be an int >= 1, got {threads!r}")
        if threads < 1:
            raise ValueError(f"threads must be >= 1, got {threads}")
        return int(min(threads, self.num_fights))

    @property
    def observation_shape(self) -> tuple[int, int, int]:
        return (self.num_fights, 2, OBSERVATION_SIZE)

    def seed(self, seed: int | list[int | None] | None = None) -> None:
        """Seed every fight's spawn RNG: fight i gets `seed + i` (or `seed[i]`; None: entropy)."""
        if isinstance(seed, (list, tuple, np.ndarray)):
            if len(seed) != self.num_fights:
                raise ValueError(
                    f"seed: need {self.num_fights} seeds, one per fight, got {len(seed)}"
                )
            for index, value in enumerate(seed):
                if value is not None and (
                    isinstance(value, (bool, np.bool_))
                    or not isinstance(value, (int, np.integer))
                    or value < 0
                ):
                    raise ValueError(
                        f"seed[{index}] = {value!r}: each seed must be a non-negative int or None"
                    )
            seeds = [None if s is None else int(s) for s in seed]
        elif seed is None:
            seeds = [None] * self.num_fights
        else:
            if isinstance(seed, bool) or not isinstance(seed, (int, np.integer)) or seed < 0:
                raise ValueError(f"seed must be a non-negative int, a list or None, got {seed!r}")
            seeds = [int(seed) + i for i in range(self.num_fights)]
        self.state.rng.seed(self._all, seeds)
        self._seeded = True

    def reset(self, seed: int | list[int | None] | None = None) -> np.ndarray:
        """Reset every fight (seeding first if `seed` is given); the (N, 2, 41) observations.

        Without a seed, the first reset seeds from entropy and later ones continue each fight's
        stream, as the single env's `reset()` does.
        """
        if seed is not None or not self._seeded:
            self.seed(seed)
        self._reset_fights(self._all)
        self._needs_reset = False
        return self.observe()

    def step(self, actions: np.ndarray):
        """One env step of every fight; ended fights are reset in the same call.

        `actions`: (N, 2) ints in 0..9, fighter_0's then fighter_1's. Returns observations
        (N, 2, 41) float32 (of the new episode where one ended), rewards (N, 2) float64,
        terminated (N,), truncated (N,), and `info`: `StepEvents` fields (each (2, N)),
        `health` and `stocks` (2, N) before any reset, `winner` (N,) (`Outcome` codes: 0, 1,
        DRAW -1, GOING_ON -2 while the fight goes on), `done_index` (the ended fights' indices,
        ascending) and `final_observation` (len(done_index), 2, 41): their last observations.
        With `obs_type="pixels"` the observations (and the final ones) are the images
        (N, 2, H, W[, 3]) uint8 instead, with "both" a dict of the two ("vector", "pixels");
        with `pixel_seats` only fighter pixel_seats[i]'s image of fight i, (N, H, W[, 3]): a
        learner against a scripted opponent needs its own view only, at half the cost.
        """
        events, rewards, terminated, truncated, winner, observations = self._compiled_step(actions)
        s = self.state
        info = {
            "damage_dealt": events.damage_dealt,
            "damage_taken": events.damage_taken,
            "hits_landed": events.hits_landed,
            "hits_blocked": events.hits_blocked,
            "rung_out": events.rung_out,
            "knocked_out": events.knocked_out,
            "health": s.health.copy(),
            "stocks": s.stocks.copy(),
            "winner": winner,
        }
        index = np.flatnonzero(winner != Outcome.GOING_ON)
        info["done_index"] = index
        images = self._images(self._all)
        info["final_observation"] = self._compose(
            observations[index], None if images is None else images[index]
        )
        if index.size:
            self._reset_fights(index)
            self._observe_into(observations, index)
            if images is not None:
                self._raster.render(self.state, index, images, self.pixel_seats)
        return self._compose(observations, images), rewards, terminated, truncated, info

    def advance(self, actions: np.ndarray):
        """One env step without the auto-reset: (events, rewards, terminated, truncated, winner)."""
        actions = self._check_actions(actions)
        size = self.num_fights
        events = StepEvents(size)
        reward = np.empty((size, 2))
        truncated = np.empty(size, dtype=bool)
        winner = np.empty(size, dtype=np.int64)
        self._kernel.step(self.state, actions, events, reward, truncated, winner)
        return events, reward, events.over.copy(), truncated, winner

    def _compiled_step(self, actions: np.ndarray):
        """`advance` and `observe` in one compiled call, the fights in chunks on threads."""
        actions = self._check_actions(actions)
        size = self.num_fights
        events = StepEvents(size)
        rewards = np.empty((size, 2))
        truncated = np.empty(size, dtype=bool)
        winner = np.empty(size, dtype=np.int64)
        observations = np.empty(self.observation_shape, dtype=np.float32)
        self._kernel.step_observe(
            self.state, actions, events, rewards, truncated, winner, observations, self._bounds
        )
        return events, rewards, events.over.copy(), truncated, winner, observations

    def reset_done(self, done: np.ndarray) -> np.ndarray:
        """Reset the fights where `done` holds; all fights' observations afterwards."""
        index = np.flatnonzero(done)
        if index.size:
            self._reset_fights(index)
        return self.observe()

    def observe(self) -> Any:
        """Every fight's observations now, as `obs_type` asks: (N, 2, 41) float32, images
        (N, 2, H, W[, 3]) uint8, or a dict of both ("vector", "pixels")."""
        out = np.empty(self.observation_shape, dtype=np.float32)
        self._kernel.observe(self.state, out, self._all)
        return self._compose(out, self._images(self._all))

    def _images(self, index: np.ndarray) -> np.ndarray | None:
        """The images of the fights `index`, (N, 2, H, W, C) or with `pixel_seats` (N, H, W, C);
        None without pixels."""
        if self._raster is None:
            return None
        spec = self.pixels
        seat_axis = () if self.pixel_seats is not None else (2,)
        shape = (self.num_fights, *seat_axis, spec.height, spec.width, spec.channels)
        out = np.empty(shape, np.uint8)
        self._raster.render(self.state, index, out, self.pixel_seats)
        return out

    def _compose(self, vectors: np.ndarray, images: np.ndarray | None) -> Any:
        return compose(self.obs_type, vectors, images, self.pixels)

    def _observe_into(self, out: np.ndarray, index: np.ndarray) -> None:
        self._kernel.observe(self.state, out, index)

    def _reset_fights(self, index: np.ndarray) -> None:
        """`Fight.reset` for the fights `index`: jittered spawns, full stocks, both respawned."""
        self._kernel.reset(self.state, index)

    def _check_actions(self, actions: Any) -> np.ndarray:
        """The actions as an (N, 2) int64 array, once the batch has been reset."""
        if self._needs_reset:
            raise RuntimeError("step() before reset(): call reset() first")
        actions = np.asarray(actions)
        if actions.shape != (self.num_fights, 2):
            raise ValueError(f"actions must have shape ({self.num_fights}, 2), got {actions.shape}")
        if not np.issubdtype(actions.dtype, np.integer):
            if np.issubdtype(actions.dtype, np.floating) and np.all(actions == np.round(actions)):
                actions = actions.astype(np.int64)
            else:
                raise TypeError(f"actions must be integers in 0..9, got dtype {actions.dtype}")
        if actions.min() < 0 or actions.max() > 9:
            fight, seat = np.argwhere((actions < 0) | (actions > 9))[0].tolist()
            raise ValueError(
                f"actions[{fight}, {seat}] = {int(actions[fight, seat])}: actions must be in 0..9"
            )
        return actions.astype(np.int64, copy=False)

    def __repr__(self) -> str:
        return (
            f"VectorFight(num_fights={self.num_fights}, config={self.config.name!r}, "
            f"backend={self.backend!r})"
        )
