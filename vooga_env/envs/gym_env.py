"""`FightEnv`: the fight as a single-agent Gymnasium env, one fighter against a given opponent."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import gymnasium
import numpy as np

from vooga_env.envs.parallel import AGENTS, FightParallelEnv
from vooga_env.game.actions import action_index, check_seat
from vooga_env.game.config import FightConfig
from vooga_env.policies import Policy, make_policy


class FightEnv(gymnasium.Env):
    """One fighter (the learner) against an opponent policy; see FightParallelEnv for the fight.

    ## Arguments
    `opponent`: a scripted fighter's name (`idle`, `random`, `rush`, `turtle`, `zoner`,
    `edge_guard`), a saved model path (.zip), an exported fighter (.npz), any callable
    `obs -> action`, or an object with SB3's `predict`. `seat`: 0 or 1 for the learner's side, or
    "random" to draw it each episode (the observations and actions are mirrored, so a policy plays
    either side). Everything else goes to `FightParallelEnv`: `config`, `render_mode`, `reward_fn`,
    `backend`, and config overrides.

    Observations, actions, rewards and infos are the learner's, as in the parallel env;
    `info["seat"]`, `info["opponent"]` (its name) and `info["opponent_action"]` are added.
    """

    metadata = FightParallelEnv.metadata

    def __init__(
        self,
        config: str | Path | FightConfig = "default",
        opponent: Any = "random",
        seat: int | str = 0,
        render_mode: str | None = None,
        **kwargs: Any,
    ) -> None:
        if seat != "random":
            seat = check_seat(seat, "0, 1 or 'random'")
        self.fight_env = FightParallelEnv(config, render_mode=render_mode, **kwargs)
        self.metadata = self.fight_env.metadata
        self.render_mode = render_mode
        self.opponent: Policy = make_policy(opponent)
        self.seat_choice = seat
        self.seat = 0 if seat == "random" else seat
        self.observation_space = self.fight_env.observation_space(AGENTS[0])
        self.action_space = self.fight_env.action_space(AGENTS[0])
        self._opponent_observation: np.ndarray | None = None

    def set_opponent(self, opponent: Any, seed: int | None = None) -> None:
        """Fight a different opponent from the next step on (curricula and self-play swap here)."""
        self.opponent = make_policy(opponent, seed)

    @property
    def config(self) -> FightConfig:
        return self.fight_env.config

    def reset(
        self, *, seed: int | None = None, options: dict[str, Any] | None = None
    ) -> tuple[np.ndarray, dict[str, Any]]:
        if seed is not None and (
            isinstance(seed, (bool, np.bool_))
            or not isinstance(seed, (int, np.integer))
            or seed < 0
        ):
            raise ValueError(f"seed must be a non-negative int or None, got {seed!r}")
        super().reset(seed=None if seed is None else int(seed))
        fight_seed = int(self.np_random.integers(2**31))
        if self.seat_choice == "random":
            self.seat = int(self.np_random.integers(2))
        self.opponent.reset(int(self.np_random.integers(2**31)))
        observations, infos = self.fight_env.reset(seed=fight_seed, options=options)
        me, them = AGENTS[self.seat], AGENTS[1 - self.seat]
        self._opponent_observation = observations[them]
        return observations[me], {**infos[me], "seat": self.seat}

    def step(self, action: Any) -> tuple[np.ndarray, float, bool, bool, dict[str, Any]]:
        if self._opponent_observation is None:
            raise RuntimeError("step() called before reset()")
        me, them = AGENTS[self.seat], AGENTS[1 - self.seat]
        opponent_action = self._opponent_action(them)
        observations, rewards, terminations, truncations, infos = self.fight_env.step(
            {me: action, them: opponent_action}
        )
        self._opponent_observation = observations[them]
        info = {
            **infos[me],
            "seat": self.seat,
            "opponent": self.opponent.name,
            "opponent_action": opponent_action,
        }
        return observations[me], rewards[me], terminations[me], truncations[me], info

    def _opponent_action(self, seat: str) -> int:
        """The opponent's action; a bad one is blamed on the opponent, not on its seat."""
        who = f"opponent {self.opponent.name!r} (playing {seat})"
        try:
            action = self.opponent.act(self._opponent_observation)
        except TypeError as error:
            raise TypeError(f"{who}: {error}") from error
        except ValueError as error:
            raise ValueError(f"{who}: {error}") from error
        return action_index(f"the action of {who}", action)

    def render(self) -> np.ndarray | None:
        return self.fight_env.render()

    def close(self) -> None:
        self.fight_env.close()
