"""The compiled kernel: `Fight.step` for one fight at a time, compiled, looped over the N fights.

The scalar code of `vooga_env.fight` and `vooga_env.physics` for the default wiring, transcribed
expression by expression (`kernel_step.py`, `kernel_parts.py`); `_fsum` is CPython's
`math.fsum`. Compiled on first use (some seconds) and cached on disk (`cache=True`), so later
processes start at once.
"""

from __future__ import annotations

import numba
import numpy as np

from vooga_env.vector.kernel_parts import _observe, _reset, jit
from vooga_env.vector.kernel_step import _step
from vooga_env.vector.params import FightParams
from vooga_env.vector.state import FightState, StepEvents


class Kernel:
    """Holds one config's parameters as arrays and steps a `FightState` with the compiled loop."""

    def __init__(self, params: FightParams) -> None:
        self.params = params
        c, f = params.config, params.config.fighter
        # the layout of kernel_parts' parameter indices
        self.fp = np.array(
            [params.width, params.height, params.gravity, params.background_factor,
             params.speed_factor, params.out_bound_distance, params.frame_time, params.friction,
             f.width, f.height, f.crouch_height, f.mass, f.speed, f.health, f.jump_speed,
             f.fast_fall_speed, f.head_slide, f.block_damage, f.block_knockback,
             c.rewards.damage, c.rewards.ring_out, c.rewards.ko, c.rewards.time_penalty,
             c.rewards.edge, params.stage_left, params.stage_right],
        )  # fmt: skip
        self.ip = np.array([c.frame_skip, f.air_jumps, c.max_cycles], dtype=np.int64)
        self.blocks = np.stack([params.block_x, params.block_y, params.block_w, params.block_h])
        self.attacks_f = np.stack(
            [params.attack_damage, params.attack_knockback, params.attack_growth,
             params.attack_cos, params.attack_sin, params.hitbox_w, params.hitbox_h,
             params.hitbox_offset_y]
        )  # fmt: skip
        self.attacks_i = np.stack(
            [params.attack_startup, params.attack_active, params.attack_total,
             params.attack_hitstun, params.attack_blocked_hitstun]
        )  # fmt: skip
        self.spawns = np.array(params.spawns)

    def observe(self, s: FightState, out: np.ndarray, index: np.ndarray) -> None:
        """Write the observations of the fights `index` into out[index] ((N, 2, 41) float32)."""
        p = self.params
        index = np.asarray(index, dtype=np.int64)
        _observe(self.fp, self.ip, self.attacks_f, self.attacks_i, index, out, s.floats, s.ints,
                 s.flags, s.counters, p.stage_left, p.stage_right, p.config.max_cycles,
                 p.config.stocks)  # fmt: skip

    def reset(self, s: FightState, index: np.ndarray) -> None:
        """`Fight.reset` of the fights `index` (spawn jitter from each fight's PCG64 stream)."""
        p, r = self.params, s.rng
        index = np.asarray(index, dtype=np.int64)
        _reset(index, self.fp, self.ip, self.blocks, self.spawns, p.spawn_jitter, p.config.stocks,
               r.state_hi, r.state_lo, r.inc_hi, r.inc_lo, s.floats, s.ints, s.flags,
               s.counters, s.values)  # fmt: skip

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
        _step(self.fp, self.ip, self.blocks, self.attacks_f, self.attacks_i, actions,
              s.floats, s.ints, s.flags, s.counters, s.values, events.damage, events.hits,
              events.outs, events.over, rewards, truncated, winner, 0, s.size)  # fmt: skip

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
        p = self.params
        arguments = (self.fp, self.ip, self.blocks, self.attacks_f, self.attacks_i, actions,
                     s.floats, s.ints, s.flags, s.counters, s.values, events.damage, events.hits,
                     events.outs, events.over, rewards, truncated, winner, out, p.stage_left,
                     p.stage_right, p.config.max_cycles, p.config.stocks)  # fmt: skip
        if bounds.shape[0] == 2:
            _step_observe(bounds[0], bounds[1], *arguments)
        else:
            _step_observe_chunks(bounds, *arguments)


@jit
def _step_observe(start, stop, fp, ip, blocks, af, ai, actions, fl, it, fg, ct, values, damage,
                  hits, outs, over, rewards, truncated, winner, out, stage_left, stage_right,
                  max_cycles, start_stocks):  # fmt: skip
    """Zero the events, step and observe the fights start..stop-1."""
    damage[:, :, start:stop] = 0.0
    hits[:, :, start:stop] = 0
    outs[:, :, start:stop] = False
    over[start:stop] = False
    _step(fp, ip, blocks, af, ai, actions, fl, it, fg, ct, values, damage, hits, outs, over,
          rewards, truncated, winner, start, stop)  # fmt: skip
    _observe(fp, ip, af, ai, np.arange(start, stop), out, fl, it, fg, ct, stage_left,
             stage_right, max_cycles, start_stocks)  # fmt: skip


@numba.njit(cache=True, nogil=True, parallel=True)
def _step_observe_chunks(bounds, fp, ip, blocks, af, ai, actions, fl, it, fg, ct, values, damage,
                         hits, outs, over, rewards, truncated, winner, out, stage_left,
                         stage_right, max_cycles, start_stocks):  # fmt: skip
    """`_step_observe` of each chunk bounds[c]..bounds[c + 1] - 1, the chunks on threads."""
    for c in numba.prange(bounds.shape[0] - 1):
        _step_observe(bounds[c], bounds[c + 1], fp, ip, blocks, af, ai, actions, fl, it, fg, ct,
                      values, damage, hits, outs, over, rewards, truncated, winner, out,
                      stage_left, stage_right, max_cycles, start_stocks)  # fmt: skip
