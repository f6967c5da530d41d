"""The compiled kernel: `Fight.step` for one fight at a time, compiled, looped over the N fights.

The scalar code of `vooga_env.game.fight` and `vooga_env.physics` for the default wiring, as stages
named after their engine twins (`stages.py`, `observe.py`) that call the engine's own float
formulas compiled (`parts.F`), run in the engine's order (`step.py`). Compiled on
first use (some seconds) and cached on disk (`cache=True`), so later processes start at once.
"""

from __future__ import annotations

import numba
import numpy as np

from vooga_env.kernel.observe import _observe
from vooga_env.kernel.params import FightParams
from vooga_env.kernel.parts import (
    ATTACK_FLOATS,
    ATTACK_INTS,
    FLOAT_PARAMS,
    INT_PARAMS,
    Streams,
    events_record,
    jit,
    params_record,
    state_record,
)
from vooga_env.kernel.state import FightState, StepEvents
from vooga_env.kernel.step import _reset, _step


def kernel_arrays(params: FightParams) -> tuple[np.ndarray, ...]:
    """One config's numbers as the kernel's parameter arrays (see parts.params_record)."""
    c, f, r = params.config, params.config.fighter, params.config.rewards
    values = dict(
        width=params.width, height=params.height, gravity=params.gravity,
        factor=params.background_factor, speed_factor=params.speed_factor,
        out_distance=params.out_bound_distance, dt=params.frame_time, friction=params.friction,
        stage_left=params.stage_left, stage_right=params.stage_right,
        spawn_jitter=params.spawn_jitter,
        f_width=f.width, f_height=f.height, crouch=f.crouch_height, mass=f.mass, speed=f.speed,
        health=f.health, jump=f.jump_speed, fast_fall=f.fast_fall_speed,
        head_slide=f.head_slide, block_damage=f.block_damage,
        block_knockback=f.block_knockback,
        r_damage=r.damage, r_ring_out=r.ring_out, r_ko=r.ko, r_time=r.time_penalty, edge=r.edge,
        r_time_out=r.time_out,
        air_jumps=f.air_jumps, frame_skip=c.frame_skip, max_cycles=c.max_cycles,
        stocks=c.stocks, random_sides=int(c.arena.random_sides),
        start_damage=c.start.damage, start_steps=c.start.steps,
        damage=params.attack_damage, knockback=params.attack_knockback,
        growth=params.attack_growth, cos=params.attack_cos, sin=params.attack_sin,
        hitbox_w=params.hitbox_w, hitbox_h=params.hitbox_h,
        hitbox_offset_y=params.hitbox_offset_y, startup=params.attack_startup,
        active=params.attack_active, total=params.attack_total, hitstun=params.attack_hitstun,
        blocked_hitstun=params.attack_blocked_hitstun,
    )  # fmt: skip
    return (
        np.array([values[name] for name in FLOAT_PARAMS], dtype=np.float64),
        np.array([values[name] for name in INT_PARAMS], dtype=np.int64),
        np.stack([params.block_x, params.block_y, params.block_w, params.block_h]),
        np.array(params.spawns, dtype=np.float64),
        np.stack([values[name] for name in ATTACK_FLOATS]).astype(np.float64),
        np.stack([values[name] for name in ATTACK_INTS]).astype(np.int64),
    )


def state_blocks(s: FightState) -> tuple[np.ndarray, ...]:
    """A FightState's blocks in the order of parts.State."""
    return s.floats, s.ints, s.flags, s.counters, s.values


def event_blocks(events: StepEvents) -> tuple[np.ndarray, ...]:
    """A StepEvents' blocks in the order of parts.Events."""
    return events.damage, events.hits, events.outs, events.over


class Kernel:
    """Holds one config's parameter arrays and steps a `FightState` with the compiled loops.

    The compiled entry points take arrays (numba unboxes arrays fast, a record slowly) and build
    the records the stages take: `Params`, `State`, `Events` (parts).
    """

    def __init__(self, params: FightParams) -> None:
        self.params = params
        self.arrays = kernel_arrays(params)

    def observe(self, s: FightState, out: np.ndarray, index: np.ndarray) -> None:
        """Write the observations of the fights `index` into out[index] ((N, 2, 41) float32)."""
        index = np.asarray(index, dtype=np.int64)
        _observe_arrays(*self.arrays, *state_blocks(s), index, out)

    def reset(self, s: FightState, index: np.ndarray) -> None:
        """`Fight.reset` of the fights `index` (spawn jitter from each fight's PCG64 stream)."""
        r = s.rng
        index = np.asarray(index, dtype=np.int64)
        _reset_arrays(*self.arrays, *state_blocks(s), r.state_hi, r.state_lo, r.inc_hi,
                      r.inc_lo, index)  # fmt: skip

    def step(
        self,
        s: FightState,
        actions: np.ndarray,
        events: StepEvents,
        rewards: np.ndarray,
        truncated: np.ndarray,
        winner: np.ndarray,
    ) -> None:
        """One env step of every fight (frames until `frame_skip` or the fight's end), in place.

        Fills `events`, `rewards` (N, 2), `truncated` (N,) and `winner` (N,): 0, 1, -1 for a
        draw, -2 while the fight goes on; `events.over` is `terminated`.
        """
        actions = np.ascontiguousarray(actions, dtype=np.int64)
        _step_arrays(*self.arrays, *state_blocks(s), *event_blocks(events), actions, rewards,
                     truncated, winner, 0, s.size)  # fmt: skip

    def step_observe(
        self,
        s: FightState,
        actions: np.ndarray,
        events: StepEvents,
        rewards: np.ndarray,
        truncated: np.ndarray,
        winner: np.ndarray,
        out: np.ndarray,
        bounds: np.ndarray,
    ) -> None:
        """`step` with `events` zeroed first, then `observe` into `out`: one compiled call.

        `bounds` (int64, ascending, from 0 to N) cuts the fights into chunks, stepped on numba's
        threads at once when there are two or more (each fight is independent, so the results do
        not depend on the cut).
        """
        arguments = (*self.arrays, *state_blocks(s), *event_blocks(events), actions, rewards,
                     truncated, winner, out)  # fmt: skip
        if bounds.shape[0] == 2:
            _step_observe(bounds[0], bounds[1], *arguments)
        else:
            _step_observe_chunks(bounds, *arguments)


# The entry points: parameter arrays (fp, ip, blocks, spawns, af, ai: params_record), state
# blocks (fl, it, fg, ct, values: State), event blocks (damage, hits, outs, over: Events). Each
# builds the records and inlines the loop that takes them, so that the compiler sees their
# arrays unmanaged (a record handed to another compiled function would cost a reference count
# call for each array taken out of it).


@jit
def _observe_arrays(fp, ip, blocks, spawns, af, ai, fl, it, fg, ct, values, index, out):
    p = params_record(fp, ip, blocks, spawns, af, ai)
    _observe(p, state_record(fl, it, fg, ct, values), index, out)


@jit
def _reset_arrays(fp, ip, blocks, spawns, af, ai, fl, it, fg, ct, values, state_hi, state_lo,
                  inc_hi, inc_lo, index):  # fmt: skip
    p = params_record(fp, ip, blocks, spawns, af, ai)
    rng = Streams(state_hi, state_lo, inc_hi, inc_lo)
    _reset(p, state_record(fl, it, fg, ct, values), rng, index)


@jit
def _step_arrays(fp, ip, blocks, spawns, af, ai, fl, it, fg, ct, values, damage, hits, outs,
                 over, actions, rewards, truncated, winner, start, stop):  # fmt: skip
    p = params_record(fp, ip, blocks, spawns, af, ai)
    s, e = state_record(fl, it, fg, ct, values), events_record(damage, hits, outs, over)
    _step(p, s, e, actions, rewards, truncated, winner, start, stop)


@jit
def _step_observe(start, stop, fp, ip, blocks, spawns, af, ai, fl, it, fg, ct, values, damage,
                  hits, outs, over, actions, rewards, truncated, winner, out):  # fmt: skip
    """Zero the events, step and observe the fights start..stop-1."""
    damage[:, :, start:stop] = 0.0
    hits[:, :, start:stop] = 0
    outs[:, :, start:stop] = False
    over[start:stop] = False
    _step_arrays(fp, ip, blocks, spawns, af, ai, fl, it, fg, ct, values, damage, hits, outs,
                 over, actions, rewards, truncated, winner, start, stop)  # fmt: skip
    _observe_arrays(fp, ip, blocks, spawns, af, ai, fl, it, fg, ct, values,
                    np.arange(start, stop), out)  # fmt: skip


@numba.njit(cache=True, nogil=True, parallel=True)
def _step_observe_chunks(bounds, fp, ip, blocks, spawns, af, ai, fl, it, fg, ct, values, damage,
                         hits, outs, over, actions, rewards, truncated, winner, out):  # fmt: skip
    """`_step_observe` of each chunk bounds[c]..bounds[c + 1] - 1, the chunks on threads."""
    for c in numba.prange(bounds.shape[0] - 1):
        _step_observe(bounds[c], bounds[c + 1], fp, ip, blocks, spawns, af, ai, fl, it, fg, ct,
                      values, damage, hits, outs, over, actions, rewards, truncated, winner,
                      out)  # fmt: skip
