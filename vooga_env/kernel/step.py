"""The kernel's step and reset: `Fight.step` and `Fight.reset` of every fight, one after the other.

`_step` is `Fight.step` over `World.step` for the default wiring (push between the fighters,
rebound with friction on blocks, the attack hitboxes), the stages (`stages.py`) in the engine's
order; what each stage computes is documented there.
"""

from __future__ import annotations

import numpy as np

from vooga_env.kernel import stages
from vooga_env.kernel.layout import (
    S_FRAME,
    S_HEALTH,
    S_POTENTIAL,
    S_SPAWN_TOP,
    S_SPAWN_X,
    S_STEPS,
    S_STOCKS,
)
from vooga_env.kernel.parts import _next_double, inline, scratch, stage
from vooga_env.kernel.stages import F


@inline
def _step(p, s, e, actions, rewards, truncated, winner, start, stop):
    """One env step of the fights start..stop-1 (frames until `frame_skip` or the fight's end),
    in place; fills `e`, rewards (N, 2), truncated (N,) and winner (N,: stages.outcome)."""
    x = scratch()
    for i in range(start, stop):
        for _frame in range(p.frame_skip):
            if _frame_of(p, s, e, x, actions, i):
                e.over[i] = True
                break
        s.ct[S_STEPS, i] += 1
        stages.reward(p, s, e, i, rewards)
        truncated[i], winner[i] = stages.outcome(p, s, e, i)
        if truncated[i]:
            stages.time_out_reward(p, winner[i], i, rewards)


@inline
def _frame_of(p, s, e, x, actions, i):
    """One physics frame of fight i (Fight._frame); True when the fight is over."""
    for f in range(2):
        stages.control(p, s, x, i, f, actions[i, f])
    stages.place_hitboxes(p, s, i)
    stages.integrate(p, s, x, i)
    pair_found, pair_axis, pair_normal, pair_toi, pair_depth = stages.find_contacts(p, s, x, i)
    for a in range(2):
        if x.hit[a]:
            stages.reaction_hit(p, s, x, i, a)
    if pair_found:
        stages.reaction_push(p, s, x, i, pair_axis, pair_normal, pair_toi, pair_depth)
    for f in range(2):
        stages.resolve(p, s, x, i, f)
        stages.keep_in_bounds(p, s, i, f)
    return stages.after_frame(p, s, e, x, i, pair_found, pair_axis, pair_normal)


@inline
def _reset(p, s, rng, index):
    """`Fight.reset` of the fights `index`: jittered spawns (each fight's PCG64 stream), swapped
    on a coin toss with `random_sides`, the block under each, full stocks, both respawned, the
    [start] damage and clock, the reward's edge potential."""
    jitter = p.spawn_jitter
    for i in index:
        for f in range(2):
            if jitter > 0:
                draw = _next_double(rng, i)
                s.fl[S_SPAWN_X, f, i] = p.spawns[f] + (-jitter + (jitter - -jitter) * draw)
            else:
                s.fl[S_SPAWN_X, f, i] = p.spawns[f] + 0.0
        if p.random_sides:
            toss = _next_double(rng, i)
            if toss < 0.5:
                left, right = s.fl[S_SPAWN_X, 0, i], s.fl[S_SPAWN_X, 1, i]
                s.fl[S_SPAWN_X, 0, i], s.fl[S_SPAWN_X, 1, i] = right, left
        for f in range(2):
            s.fl[S_SPAWN_TOP, f, i] = _spawn_top(p, s.fl[S_SPAWN_X, f, i])
        for f in range(2):
            s.it[S_STOCKS, f, i] = p.stocks
            stages.respawn(p, s, f, i)
        s.ct[S_FRAME, i] = 0
        s.ct[S_STEPS, i] = 0
        if p.start_damage > 0:
            for f in range(2):
                draw = _next_double(rng, i)
                s.fl[S_HEALTH, f, i] -= p.start_damage * draw
        if p.start_steps > 0:
            draw = _next_double(rng, i)
            s.ct[S_STEPS, i] = int(draw * (p.start_steps + 1))
        s.values[S_POTENTIAL, i] = stages.edge_advantage(p, s, i)  # HitAndRingOutReward.reset


@stage
def _spawn_top(p, x):
    """config.spawn_block's top: the highest block under a fighter at x, the first on a tie."""
    top = np.inf
    for b in range(p.blocks.shape[1]):
        if F.under(p.blocks[0, b], p.blocks[2, b], x, p.f_width) and p.blocks[1, b] < top:
            top = p.blocks[1, b]
    return top
