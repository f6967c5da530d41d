"""`FightAECEnv`: PettingZoo's AEC view of the parallel env, with errors instead of asserts.

PettingZoo's `parallel_to_aec` guards its calls with `assert` (gone under `python -O`) and
hands a bad action on to the parallel env only when the last agent of the cycle steps, so the
error shows up one call late. This wrapper checks each call where it is made: an action when it
is given (the agent named), `None` for an agent that is done, and reset before anything else.
"""

from __future__ import annotations

import numbers
from typing import Any

from pettingzoo import ParallelEnv
from pettingzoo.utils.conversions import parallel_to_aec_wrapper
from pettingzoo.utils.env import AECIterator
from pettingzoo.utils.wrappers import OrderEnforcingWrapper
from pettingzoo.utils.wrappers.order_enforcing import (
    AECOrderEnforcingIterable,
    AECOrderEnforcingIterator,
)

from vooga_env.game.actions import action_index


class FightAECEnv(OrderEnforcingWrapper):
    """The AEC env of a FightParallelEnv (what `vooga_env.env()` returns)."""

    def __init__(self, parallel: ParallelEnv) -> None:
        super().__init__(parallel_to_aec_wrapper(parallel))

    def step(self, action: Any) -> None:
        self._need_reset("step")
        if self.agents:
            agent = self.agent_selection
            if self.terminations[agent] or self.truncations[agent]:
                if action is not None:
                    raise ValueError(
                        f"action for {agent} = {action!r}: the agent is done, "
                        "step(None) is the only action allowed (then reset())"
                    )
            else:
                action = action_index(f"action for {agent}", action)
        super().step(action)

    def observe(self, agent: str) -> Any:
        self._need_reset("observe")
        if agent not in self.possible_agents:
            raise KeyError(f"unknown agent {agent!r}; agents: {self.possible_agents}")
        return super().observe(agent)

    def state(self) -> Any:
        self._need_reset("state")
        return super().state()

    def render(self) -> Any:
        self._need_reset("render")
        return super().render()

    def agent_iter(self, max_iter: int = 2**63) -> AECOrderEnforcingIterable:
        self._need_reset("agent_iter")
        if isinstance(max_iter, bool) or not isinstance(max_iter, numbers.Integral) or max_iter < 0:
            raise ValueError(f"max_iter must be a non-negative int, got {max_iter!r}")
        return _Iterable(self, int(max_iter))

    def _need_reset(self, call: str) -> None:
        if not self._has_reset:
            raise RuntimeError(f"{call}() called before reset(); call reset() first")


class _Iterable(AECOrderEnforcingIterable):
    def __iter__(self) -> _Iterator:
        return _Iterator(self.env, self.max_iter)


class _Iterator(AECOrderEnforcingIterator):
    """`agent_iter`'s iterator: a loop that forgets to step gets a RuntimeError, not an assert."""

    def __next__(self) -> str:
        agent = AECIterator.__next__(self)
        if not self.env._has_updated:
            raise RuntimeError("agent_iter() loop without step(): call step() for each agent")
        self.env._has_updated = False
        return agent
