"""Rewards from hits and ring-outs; swap in your own by passing `reward_fn` to the env."""

from __future__ import annotations

from typing import Protocol

from vooga_env.config import RewardConfig
from vooga_env.fight import Fight, StepEvents


class RewardFn(Protocol):
    """Maps one step's events to one reward per fighter index."""

    def __call__(self, fight: Fight, events: StepEvents) -> tuple[float, float]: ...


class HitAndRingOutReward:
    """Damage dealt minus damage taken (over max health), +/- a bonus for ring-outs and KOs.

    Zero-sum when `time_penalty` is 0: whatever one fighter gains, the other loses.
    """

    def __init__(self, config: RewardConfig) -> None:
        self.config = config

    def __call__(self, fight: Fight, events: StepEvents) -> tuple[float, float]:
        config = self.config
        health = fight.config.fighter.health
        rewards = []
        for me, other in ((0, 1), (1, 0)):
            reward = config.damage * (events.damage_dealt[me] - events.damage_taken[me]) / health
            reward += config.ring_out * (events.rung_out[other] - events.rung_out[me])
            reward += config.ko * (events.knocked_out[other] - events.knocked_out[me])
            rewards.append(reward - config.time_penalty)
        return rewards[0], rewards[1]

    def __repr__(self) -> str:
        return f"HitAndRingOutReward({self.config!r})"
