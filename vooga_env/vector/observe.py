"""Observations, rewards and winners of N fights: `observations.observe` and the default reward.

Same float expressions in the same order as the single env, so every float32 observation and every
reward is bit for bit the single env's.
"""

from __future__ import annotations

import numpy as np

from vooga_env.fight import SIDES
from vooga_env.observations import HIGH, HITSTUN_SCALE, LOW, OBSERVATION_SIZE, VELOCITY_SCALE
from vooga_env.vector.contacts import py_min
from vooga_env.vector.params import FightParams
from vooga_env.vector.state import FightState, StepEvents

FEATURES = (OBSERVATION_SIZE - 3) // 2  # per fighter


def reach(
    p: FightParams, s: FightState, f: int, index=slice(None)
) -> tuple[np.ndarray, np.ndarray]:
    """`Fight.reach`: would fighter f's punch, and its kick, started now touch the other?"""
    c = p.config.fighter
    o = 1 - f
    x, other_x = s.x[f, index], s.x[o, index]
    toward = (other_x + c.width / 2) - (x + c.width / 2)
    facing = np.where(toward == 0.0, s.facing[f, index], np.where(toward > 0.0, 1.0, -1.0))
    left, top = other_x, s.y[o, index]
    right, bottom = left + c.width, top + s.height[o, index]
    feet = s.y[f, index] + s.height[f, index] - c.height
    result = []
    for move in (1, 2):
        width = p.hitbox_w[move]
        hx = np.where(facing > 0, x + c.width, x - width)
        hy = feet + p.hitbox_offset_y[move]
        result.append(
            (hx < right) & (left < hx + width) & (hy < bottom) & (top < hy + p.hitbox_h[move])
        )
    return result[0], result[1]


def observe(p: FightParams, s: FightState, index=slice(None)) -> np.ndarray:
    """Both fighters' observations of the fights `index`: (n, 2, OBSERVATION_SIZE) float32."""
    c = p.config
    arena, fighter = c.arena, c.fighter
    half_width, half_height = arena.width / 2.0, arena.height / 2.0
    reaches = (reach(p, s, 0, index), reach(p, s, 1, index))
    n = s.frame[index].shape[0]
    out = np.empty((n, 2, OBSERVATION_SIZE))
    for i in (0, 1):
        side = SIDES[i]
        for slot, f in ((0, i), (1, 1 - i)):
            move, frame = s.move[f, index], s.move_frame[f, index]
            columns = [
                side * (s.x[f, index] + fighter.width / 2.0 - half_width) / half_width,
                (s.y[f, index] + s.height[f, index] / 2.0 - half_height) / half_height,
                side * s.vx[f, index] / VELOCITY_SCALE,
                s.vy[f, index] / VELOCITY_SCALE,
                side * s.facing[f, index],
                s.health[f, index] / fighter.health,
                (fighter.health - s.health[f, index]) / fighter.health,
                s.on_ground[f, index],
                s.jumps_left[f, index] / fighter.air_jumps if fighter.air_jumps else 1.0,
                move == 1,
                move == 2,
                s.blocking[f, index],
                s.crouching[f, index],
                np.where(move != 0, frame / np.maximum(p.attack_total[move], 1), 0.0),
                s.hit_active[f, index],
                s.hitstun[f, index] / HITSTUN_SCALE,
                s.stocks[f, index] / c.stocks,
                reaches[f][0],
                reaches[f][1],
            ]
            start = slot * FEATURES
            for k, column in enumerate(columns):
                out[:, i, start + k] = column
        out[:, i, FEATURES] -= out[:, i, 0]
        out[:, i, FEATURES + 1] -= out[:, i, 1]
        centre = s.x[i, index] + fighter.width / 2.0
        edges = (centre - p.stage_left, p.stage_right - centre)
        if side < 0:
            edges = edges[::-1]
        out[:, i, 2 * FEATURES] = edges[0] / arena.width
        out[:, i, 2 * FEATURES + 1] = edges[1] / arena.width
        out[:, i, 2 * FEATURES + 2] = 1.0 - s.steps[index] / c.max_cycles
    observations = out.astype(np.float32)
    return np.clip(observations, LOW, HIGH, out=observations)


def edge_advantage(p: FightParams, s: FightState, index=slice(None)) -> np.ndarray:
    """`HitAndRingOutReward._edge_advantage`: fighter_0's room to its nearer stage edge minus
    fighter_1's, over the stage width."""
    rooms = []
    for f in (0, 1):
        centre = s.x[f, index] + p.config.fighter.width / 2.0
        rooms.append(py_min(centre - p.stage_left, p.stage_right - centre))
    return (rooms[0] - rooms[1]) / (p.stage_right - p.stage_left)


def rewards(p: FightParams, s: FightState, events: StepEvents) -> np.ndarray:
    """`HitAndRingOutReward` for both fighters: (N, 2) float64; moves the edge potential on."""
    r = p.config.rewards
    health = p.config.fighter.health
    shaping = 0.0
    if r.edge:
        potential = edge_advantage(p, s)
        shaping = r.edge * (potential - s.potential)
        s.potential[:] = potential
    out = np.empty((events.over.shape[0], 2))
    rung_out = events.rung_out.astype(np.int64)
    knocked_out = events.knocked_out.astype(np.int64)
    for me, sign in ((0, 1.0), (1, -1.0)):
        other = 1 - me
        reward = r.damage * (events.damage_dealt[me] - events.damage_taken[me]) / health
        reward = reward + r.ring_out * (rung_out[other] - rung_out[me])
        reward = reward + r.ko * (knocked_out[other] - knocked_out[me])
        out[:, me] = reward + sign * shaping - r.time_penalty
    return out


def winners(s: FightState) -> np.ndarray:
    """`Fight.winner` of each fight: 0, 1, or -1 for a draw (more stocks, then more health)."""
    stocks, health = s.stocks, s.health
    first = (stocks[0] > stocks[1]) | ((stocks[0] == stocks[1]) & (health[0] > health[1]))
    second = (stocks[1] > stocks[0]) | ((stocks[0] == stocks[1]) & (health[1] > health[0]))
    return np.where(first, 0, np.where(second, 1, -1))
