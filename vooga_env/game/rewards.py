"""Rewards from hits and ring-outs; swap in your own by passing `reward_fn` to the env."""

from __future__ import annotations

from typing import Protocol

from vooga_env.game.config import RewardConfig
from vooga_env.game.fight import Fight, StepEvents
from vooga_env.game.formulas import edge_advantage, edge_room, time_out


class RewardFn(Protocol):
    """Maps one step's events to one reward per fighter index (an optional `reset(fight)` is
    called when an episode starts)."""

    def __call__(self, fight: Fight, events: StepEvents) -> tuple[float, float]: ...


class HitAndRingOutReward:
    """Damage dealt minus damage taken (over max health), +/- a bonus for ring-outs and KOs, and
    for a win on time (`time_out`: the evaluation counts a win on time as a win, so a learner that
    is not paid for it does not mind losing that way).

    `edge` adds potential-based shaping: each step, the change in (own room to the nearer stage
    edge - the opponent's room), over the stage width. It telescopes over an episode, so it leaves
    the best policy unchanged while saying early that being driven to the edge is bad.
    Zero-sum when `time_penalty` is 0: whatever one fighter gains, the other loses.
    """

    def __init__(self, config: RewardConfig) -> None:
        self.config = config
        self._potential = 0.0

    def reset(self, fight: Fight) -> None:
        self._potential = self._edge_advantage(fight)

    def __call__(self, fight: Fight, events: StepEvents) -> tuple[float, float]:
        config = self.config
        health = fight.config.fighter.health
        shaping = 0.0
        if config.edge:
            potential = self._edge_advantage(fight)
            shaping = config.edge * (potential - self._potential)
            self._potential = potential
        leader = None
        if config.time_out and time_out(events.over, fight.steps, fight.config.max_cycles):
            leader = fight.winner()
        rewards = []
        for me, other, sign in ((0, 1, 1.0), (1, 0, -1.0)):
            reward = config.damage * (events.damage_dealt[me] - events.damage_taken[me]) / health
            reward += config.ring_out * (events.rung_out[other] - events.rung_out[me])
            reward += config.ko * (events.knocked_out[other] - events.knocked_out[me])
            reward = reward + sign * shaping - config.time_penalty
            if leader is not None:
                reward += config.time_out if leader == me else -config.time_out
            rewards.append(reward)
        return rewards[0], rewards[1]

    @staticmethod
    def _edge_advantage(fight: Fight) -> float:
        """fighter_0's room to its nearer stage edge minus fighter_1's, over the stage width."""
        left, right = fight.stage_left, fight.stage_right
        rooms = [edge_room(f.x + f.width / 2.0, left, right) for f in fight.fighters]
        return edge_advantage(rooms[0], rooms[1], left, right)

    def __repr__(self) -> str:
        return f"HitAndRingOutReward({self.config!r})"
