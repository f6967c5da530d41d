"""The compiled kernel: `Fight.step` for one fight at a time, compiled, looped over the N fights.

The scalar code of `vooga_env.fight` and `vooga_env.physics` for the default wiring, as stages
named after their engine twins (`stages.py`, `kernel_observe.py`) that call the engine's own float
formulas compiled (`kernel_parts.F`), run in the engine's order (`kernel_step.py`). Compiled on
first use (some seconds) and cached on disk (`cache=True`), so later processes start at once.
"""

from __future__ import annotations

import numba
import numpy as np

from vooga_env.vector.kernel_observe import _observe, observe
from vooga_env.vector.kernel_parts import Events, Params, State, Streams, _stack, jit
from vooga_env.vector.kernel_step import _reset, _step
from vooga_env.vector.params import FightParams
from vooga_env.vector.state import FightState, StepEvents


def kernel_params(params: FightParams) -> Params:
    """One config's numbers as the kernel's `Params` record."""
    c, f, r = params.config, params.config.fighter, params.config.rewards
    return Params(
        width=params.width, height=params.height, gravity=params.gravity,
        factor=params.background_factor, speed_factor=params.speed_factor,
        out_distance=params.out_bound_distance, dt=params.frame_time, friction=params.friction,
        stage_left=params.stage_left, stage_right=params.stage_right,
        blocks=np.stack([params.block_x, params.block_y, params.block_w, params.block_h]),
        spawns=np.array(params.spawns), spawn_jitter=params.spawn_jitter,
        f_width=f.width, f_height=f.height, crouch=f.crouch_height, mass=f.mass, speed=f.speed,
        health=f.health, jump=f.jump_speed, fast_fall=f.fast_fall_speed,
        head_slide=f.head_slide, block_damage=f.block_damage,
        block_knockback=f.block_knockback, air_jumps=f.air_jumps,
        damage=params.attack_damage, knockback=params.attack_knockback,
        growth=params.attack_growth, cos=params.attack_cos, sin=params.attack_sin,
        hitbox_w=params.hitbox_w, hitbox_h=params.hitbox_h,
        hitbox_offset_y=params.hitbox_offset_y, startup=params.attack_startup,
        active=params.attack_active, total=params.attack_total, hitstun=params.attack_hitstun,
        blocked_hitstun=params.attack_blocked_hitstun,
        frame_skip=c.frame_skip, max_cycles=c.max_cycles, stocks=c.stocks,
        r_damage=r.damage, r_ring_out=r.ring_out, r_ko=r.ko, r_time=r.time_penalty, edge=r.edge,
    )  # fmt: skip


def state_record(s: FightState) -> State:
    return State(s.floats, s.ints, s.flags, s.counters, s.values)


def events_record(events: StepEvents) -> Events:
    return Events(events.damage, events.hits, events.outs, events.over)


class Kernel:
    """Holds one config's `Params` record and steps a `FightState` with the compiled loop."""

    def __init__(self, params: FightParams) -> None:
        self.params = params
        self.record = kernel_params(params)

    def observe(self, s: FightState, out: np.ndarray, index: np.ndarray) -> None:
        """Write the observations of the fights `index` into out[index] ((N, 2, 41) float32)."""
        _observe(self.record, state_record(s), np.asarray(index, dtype=np.int64), out)

    def reset(self, s: FightState, index: np.ndarray) -> None:
        """`Fight.reset` of the fights `index` (spawn jitter from each fight's PCG64 stream)."""
        r = s.rng
        streams = Streams(r.state_hi, r.state_lo, r.inc_hi, r.inc_lo)
        _reset(self.record, state_record(s), streams, np.asarray(index, dtype=np.int64))

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
        _step(self.record, state_record(s), events_record(events), actions, rewards, truncated,
              winner, 0, s.size)  # fmt: skip

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
        arguments = (self.record, state_record(s), events_record(events), actions, rewards,
                     truncated, winner, out)  # fmt: skip
        if bounds.shape[0] == 2:
            _step_observe(bounds[0], bounds[1], *arguments)
        else:
            _step_observe_chunks(bounds, *arguments)


@jit
def _step_observe(start, stop, p, s, e, actions, rewards, truncated, winner, out):
    """Zero the events, step and observe the fights start..stop-1."""
    e.damage[:, :, start:stop] = 0.0
    e.hits[:, :, start:stop] = 0
    e.outs[:, :, start:stop] = False
    e.over[start:stop] = False
    _step(p, s, e, actions, rewards, truncated, winner, start, stop)
    position = numba.carray(_stack(4, np.float64), (2, 2))
    for i in range(start, stop):
        observe(p, s, out, i, position)


@numba.njit(cache=True, nogil=True, parallel=True)
def _step_observe_chunks(bounds, p, s, e, actions, rewards, truncated, winner, out):
    """`_step_observe` of each chunk bounds[c]..bounds[c + 1] - 1, the chunks on threads."""
    for c in numba.prange(bounds.shape[0] - 1):
        _step_observe(bounds[c], bounds[c + 1], p, s, e, actions, rewards, truncated, winner, out)
