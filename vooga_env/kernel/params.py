"""`FightParams`: a FightConfig's numbers as the batched engine reads them, and what it can't run.

The batched engine runs the rules of `vooga_env.game.fight.Fight` over the physics engine for the
wiring every shipped config uses: enemy fighters push (`collisions.enemy = "push"`), fighters
rebound off blocks with the ground friction (`collisions.neutral = "rebound"`), and the default
reward. Any other choice raises `UnsupportedConfig` naming the option, rather than silently
differing.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from vooga_env.game.config import FightConfig
from vooga_env.game.rewards import HitAndRingOutReward
from vooga_env.kernel.layout import MOVES


class UnsupportedConfig(ValueError):
    """A config option the batched engine cannot run (yet); the message names it."""


def check_supported(config: FightConfig, reward_fn: object = None) -> None:
    """Raise `UnsupportedConfig` unless the batched engine runs `config` exactly as `Fight` does."""
    collisions = config.collisions
    if collisions.enemy != "push":
        raise UnsupportedConfig(
            f"collisions.enemy = {collisions.enemy!r}: the batched engine runs 'push' only"
        )
    if collisions.neutral != "rebound":
        raise UnsupportedConfig(
            f"collisions.neutral = {collisions.neutral!r}: the batched engine runs 'rebound' only"
        )
    # collisions.friends never fires: the two fighters are always on different teams
    if reward_fn is not None and not (
        type(reward_fn) is HitAndRingOutReward and reward_fn.config == config.rewards
    ):
        raise UnsupportedConfig(
            f"reward_fn = {reward_fn!r}: the batched engine computes HitAndRingOutReward of the "
            "config's [rewards] only"
        )


@dataclass(frozen=True)
class FightParams:
    """Static numbers of one config (px, ms, px/ms). Attack arrays are indexed by move code."""

    config: FightConfig
    width: float  # arena
    height: float
    block_x: np.ndarray  # (B,) the stage's blocks
    block_y: np.ndarray
    block_w: np.ndarray
    block_h: np.ndarray
    spawns: tuple[float, float]
    spawn_jitter: float
    stage_left: float
    stage_right: float
    gravity: float
    background_factor: float
    speed_factor: float
    out_bound_distance: float
    frame_time: float
    friction: float
    attack_startup: np.ndarray  # (3,) int64, [0] unused
    attack_active: np.ndarray
    attack_total: np.ndarray  # startup + active + recovery
    attack_damage: np.ndarray  # (3,) float64
    attack_knockback: np.ndarray
    attack_growth: np.ndarray
    attack_cos: np.ndarray  # cos and sin of the launch angle
    attack_sin: np.ndarray
    attack_hitstun: np.ndarray  # (3,) int64
    attack_blocked_hitstun: np.ndarray  # hitstun // 3
    hitbox_w: np.ndarray
    hitbox_h: np.ndarray
    hitbox_offset_y: np.ndarray

    @classmethod
    def from_config(cls, config: FightConfig) -> FightParams:
        arena, physics, fighter = config.arena, config.physics, config.fighter
        blocks = arena.blocks
        attacks = [None, *(getattr(fighter, move) for move in MOVES)]  # by move code

        def table(name: str, dtype: type = np.float64) -> np.ndarray:
            values = [0 if a is None else getattr(a, name) for a in attacks]
            return np.array(values, dtype=dtype)

        angles = [0.0 if a is None else math.radians(a.angle) for a in attacks]
        return cls(
            config=config,
            width=arena.width,
            height=arena.height,
            block_x=np.array([b.x for b in blocks]),
            block_y=np.array([b.y for b in blocks]),
            block_w=np.array([b.width for b in blocks]),
            block_h=np.array([b.height for b in blocks]),
            spawns=(arena.spawns[0], arena.spawns[1]),
            spawn_jitter=arena.spawn_jitter,
            stage_left=arena.stage_left,
            stage_right=arena.stage_right,
            gravity=physics.gravity,
            background_factor=physics.background_factor,
            speed_factor=physics.speed_factor,
            out_bound_distance=physics.out_bound_distance,
            frame_time=physics.frame_time,
            friction=physics.ground_friction,
            attack_startup=table("startup", np.int64),
            attack_active=table("active", np.int64),
            attack_total=np.array(
                [0] + [a.startup + a.active + a.recovery for a in attacks[1:]], dtype=np.int64
            ),
            attack_damage=table("damage"),
            attack_knockback=table("knockback"),
            attack_growth=table("knockback_growth"),
            attack_cos=np.array([math.cos(angle) for angle in angles]),
            attack_sin=np.array([math.sin(angle) for angle in angles]),
            attack_hitstun=table("hitstun", np.int64),
            attack_blocked_hitstun=table("hitstun", np.int64) // 3,
            hitbox_w=table("hitbox_width"),
            hitbox_h=table("hitbox_height"),
            hitbox_offset_y=table("offset_y"),
        )
