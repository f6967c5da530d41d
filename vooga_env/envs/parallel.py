"""The two-fighter PettingZoo ParallelEnv, and the module-level `env`/`parallel_env` factories."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np
from gymnasium import spaces
from gymnasium.utils import seeding
from pettingzoo import ParallelEnv
from pettingzoo.utils.env import AECEnv

from vooga_env.envs.obs_space import observation_space
from vooga_env.envs.render import LazyViewer, frames_per_second
from vooga_env.game.actions import Action, action_index
from vooga_env.game.config import FightConfig, load_config
from vooga_env.game.fight import Fight
from vooga_env.game.observations import HIGH, LOW, OBSERVATION_SIZE
from vooga_env.game.outcome import INFO_KEYS, Outcome
from vooga_env.game.pixels import compose, pixel_spec
from vooga_env.game.rewards import RewardFn
from vooga_env.kernel.backends import make_simulation

AGENTS = ("fighter_0", "fighter_1")
_ACTIONS = len(Action)


class FightParallelEnv(ParallelEnv):
    """Two fighters on a stage; knock the other off it, or out.

    ## Action Space
    `Discrete(10)` per fighter, the same for both (`vooga_env.game.actions.Action`): 0 idle, 1 left,
    2 right, 3 jump, 4 jump left, 5 jump right, 6 down (crouch / fast-fall), 7 punch, 8 kick,
    9 block. Left and right are in the fighter's own mirrored frame (swapped for `fighter_1`). Each
    action is repeated for `frame_skip` physics frames of `frame_time` ms.

    ## Observation Space
    `Box(-2, 2, (41,), float32)`, ego-centric and mirrored (`vooga_env.game.observations`): 19
    features of the fighter itself (x, y, vx, vy, facing, health, damage_taken, on_ground,
    jumps_left, punching, kicking, blocking, crouching, move_progress, hitbox_active, hitstun,
    stocks, punch_reach, kick_reach), the same 19 of the opponent (its x and y relative to the
    fighter's), then the distances to the stage's left and right edges and the fraction of time
    left. `OBSERVATION_NAMES` names every index.

    ## Rewards
    Per step (`configs/*.toml` [rewards]): `damage` (5) * (damage dealt - damage taken) / max
    health, `+ring_out` (5) for ringing the opponent out and `-ring_out` for being rung out, `ko`
    (5) likewise for knock-outs, plus `edge` (2) times the change in the fighter's room to its
    nearer stage edge minus the opponent's, over the stage width (potential-based shaping: it
    telescopes, so the best policy is unchanged), minus `time_penalty` (0); when time runs out,
    `time_out` (0) to the leader and minus `time_out` to the other. Zero-sum by default.
    `infos` carry the step's events (hits landed, damage dealt and taken, ring-out, KO) and, at
    the end, the `winner`.

    ## Episode End
    Both fighters terminate in the same step when one loses its last stock (a ring-out: falling
    wholly below the arena; or a KO: health 0). Both truncate after `max_cycles` steps.

    ## Arguments
    `config` (a name from `configs/`, a .toml path or a FightConfig), `render_mode` ("human" or
    "rgb_array"), `reward_fn` (called with the fight and the step's events), `backend` ("auto",
    "engine" or "compiled": what steps the fight, see `vooga_env.kernel.backends`; every backend
    gives the same results bit for bit), and any config key as a keyword override: `max_cycles`,
    `frame_skip`, `stocks`, or a table such as `physics={"gravity": 0.003}`. `obs_type`:
    "vector" (the default, above), "pixels" (`Box(0, 255, (H, W), uint8)`, or (H, W, 3) with
    `pixel_rgb=True`; `pixel_size=(H, W)`, default (84, 84); see `vooga_env.game.pixels` for
    what is drawn) or "both" (a `Dict` of "vector" and "pixels"). Images are ego-centric like
    the vectors: fighter_1's is flipped left-right.

    ## Version History
    v0: first release.
    """

    metadata = {
        "name": "vooga_fight_v0",
        "render_modes": ["human", "rgb_array"],
        "render_fps": 25,
        "is_parallelizable": True,
    }

    def __init__(
        self,
        config: str | Path | FightConfig = "default",
        render_mode: str | None = None,
        reward_fn: RewardFn | None = None,
        backend: str = "auto",
        obs_type: str = "vector",
        pixel_size: tuple[int, int] = (84, 84),
        pixel_rgb: bool = False,
        **overrides: Any,
    ) -> None:
        self.obs_type = obs_type
        self.pixels = pixel_spec(obs_type, pixel_size, pixel_rgb)
        if render_mode is not None and render_mode not in self.metadata["render_modes"]:
            raise ValueError(
                f"render_mode must be one of {self.metadata['render_modes']} or None, "
                f"got {render_mode!r}"
            )
        self.config = load_config(config, **overrides)
        self.render_mode = render_mode
        self.simulation = make_simulation(self.config, backend, reward_fn, render_mode)
        self.possible_agents = list(AGENTS)
        self.agents: list[str] = []
        self.metadata = {**self.metadata, "render_fps": frames_per_second(self.config)}
        self._np_random, _ = seeding.np_random(None)
        self._observation_space = observation_space(obs_type, self.pixels)
        self._renderer = None
        if self.pixels is not None:
            self._renderer = self.simulation.pixel_renderer(self.pixels)
        self._action_space = spaces.Discrete(len(Action))
        self.state_space = spaces.Box(LOW, HIGH, (2 * OBSERVATION_SIZE,), np.float32)
        self._viewer = None
        if render_mode is not None:  # the simulation is then the engine's, see make_simulation
            self._viewer = LazyViewer(self.simulation, render_mode, frames_per_second(self.config))

    def observation_space(self, agent: str) -> spaces.Space:
        """The same object on every call (PettingZoo asks for that), held by this env alone."""
        self._check_agent(agent)
        return self._observation_space

    def action_space(self, agent: str) -> spaces.Discrete:
        self._check_agent(agent)
        return self._action_space

    def reset(
        self, seed: int | None = None, options: dict[str, Any] | None = None
    ) -> tuple[dict[str, np.ndarray], dict[str, dict[str, Any]]]:
        if seed is not None:
            if isinstance(seed, bool) or not isinstance(seed, (int, np.integer)) or seed < 0:
                raise ValueError(f"seed must be a non-negative int or None, got {seed!r}")
            self._np_random, _ = seeding.np_random(int(seed))
        both = self._observations(self.simulation.reset(self._np_random))
        self.agents = list(self.possible_agents)
        first, second = self.possible_agents
        observations = {first: both[0], second: both[1]}
        infos = {
            agent: {"health": status["health"], "stocks": status["stocks"]}
            for agent, status in zip(self.possible_agents, self.simulation.fighter_status())
        }
        if self.render_mode == "human":
            self.render()
        return observations, infos

    def step(self, actions: dict[str, Any]) -> tuple[dict, dict, dict, dict, dict]:
        if not self.agents:
            raise RuntimeError("step() called on a finished episode; call reset() first")
        both, rewards, terminated, truncated, winner, columns = self.simulation.step(
            *self._read_actions(actions)
        )
        both = self._observations(both)
        first, second = self.possible_agents
        values_0, values_1 = zip(*columns)
        infos = {first: dict(zip(INFO_KEYS, values_0)), second: dict(zip(INFO_KEYS, values_1))}
        if winner != Outcome.GOING_ON:
            infos[first]["winner"] = infos[second]["winner"] = Outcome(winner).info
            self.agents = []
        result = (
            {first: both[0], second: both[1]},
            {first: rewards[0], second: rewards[1]},
            {first: terminated, second: terminated},
            {first: truncated, second: truncated},
            infos,
        )
        if self.render_mode == "human":
            self.render()
        return result

    @property
    def backend(self) -> str:
        """What steps the fight: "engine" or "compiled" (see `vooga_env.game.simulation`)."""
        return self.simulation.backend

    @property
    def fight(self) -> Fight:
        """The engine's `Fight` (the "engine" backend only: the compiled one keeps arrays)."""
        fight = getattr(self.simulation, "fight", None)
        if fight is None:
            raise AttributeError(
                f"the {self.backend!r} backend has no Fight object; "
                "pass backend='engine' to reach the engine's sprites"
            )
        return fight

    def fighter_status(self) -> list[dict[str, Any]]:
        """Each fighter's top-left `x`, `y` (px), `health` and `stocks` now, fighter_0's first."""
        return self.simulation.fighter_status()

    def state(self) -> np.ndarray:
        """Both fighters' observations, fighter_0's first."""
        return self.simulation.observe().reshape(-1)

    def render(self, *_: Any) -> np.ndarray | None:
        """The frame (rgb_array) or a window update (human); extra arguments are ignored, as
        RLlib's `ParallelPettingZooEnv.render()` passes one."""
        if self.render_mode is None:
            return None
        return self._viewer.draw()

    def close(self) -> None:
        if self._viewer is not None:
            self._viewer.close()

    def _observations(self, vectors: np.ndarray) -> Any:
        """Both fighters' observations as `obs_type` asks, indexable by seat (0, 1)."""
        if self._renderer is None:
            return vectors
        images = compose(self.obs_type, vectors, self._renderer.render(), self.pixels)
        if self.obs_type == "pixels":
            return images
        return [{key: value[seat] for key, value in images.items()} for seat in (0, 1)]

    def _read_actions(self, actions: dict[str, Any]) -> tuple[int, int]:
        if type(actions) is dict and len(actions) == 2:  # the usual case, checked quickly
            first = actions.get(AGENTS[0])
            second = actions.get(AGENTS[1])
            if (
                type(first) is int  # not bool, not a numpy integer: those take the long way
                and type(second) is int
                and 0 <= first < _ACTIONS
                and 0 <= second < _ACTIONS
            ):
                return first, second
        if not isinstance(actions, dict):
            raise TypeError(f"actions must be a dict keyed by agent, got {actions!r}")
        unknown = set(actions) - set(self.possible_agents)
        if unknown:
            raise KeyError(f"actions for unknown agents {sorted(unknown)}; agents: {self.agents}")
        chosen = []
        for agent in self.possible_agents:
            if agent not in actions:
                raise KeyError(f"no action for {agent!r}; every live agent needs one")
            chosen.append(action_index(f"action for {agent}", actions[agent]))
        return chosen[0], chosen[1]

    def _check_agent(self, agent: str) -> None:
        if agent not in self.possible_agents:
            raise KeyError(f"unknown agent {agent!r}; agents: {self.possible_agents}")


def parallel_env(**kwargs: Any) -> FightParallelEnv:
    """The ParallelEnv (see FightParallelEnv for the arguments)."""
    return FightParallelEnv(**kwargs)


def env(**kwargs: Any) -> AECEnv:
    """The same fight as an AEC env (PettingZoo's `parallel_to_aec`, checking its input first)."""
    from vooga_env.envs.aec import FightAECEnv

    return FightAECEnv(parallel_env(**kwargs))


raw_env = parallel_env
