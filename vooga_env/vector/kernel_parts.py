"""The kernel's scalar parts: its records, the formulas compiled, `math.fsum`, PCG64 and scratch.

The stages (`stages.py`) take four records: `Params` (one config's numbers and attack tables, by
name), `State` (the `FightState` blocks), `Events` (the `StepEvents` blocks) and `Scratch` (one
frame's working arrays, on the stack); the reset takes `Streams` (the PCG64 states) too. The
float formulas are not written here: `F` holds `vooga_env.physics.formulas` and
`vooga_env.formulas` compiled, the very functions the engine calls, so the arithmetic is the same
by construction.
"""

from __future__ import annotations

import types as pytypes
from collections import namedtuple

import numba
import numpy as np
from numba import types
from numba.core import cgutils
from numba.extending import intrinsic

from vooga_env import formulas as fight_formulas
from vooga_env.physics import formulas as physics_formulas
from vooga_env.vector.layout import MAX_TERMS

jit = numba.njit(cache=True, nogil=True)
# the stages and scalar helpers of the hot loops, inlined into them: numba calls a compiled
# function through its address, which costs more than these helpers do (measured: half the time
# of the loops)
inline = numba.njit(cache=True, nogil=True, inline="always")

MUL_HI, MUL_LO = 0x2360ED051FC65DA4, 0x4385DF649FCCF645  # PCG64's 128-bit multiplier


def compiled(*modules: pytypes.ModuleType) -> pytypes.ModuleType:
    """A module of every function defined in `modules`, compiled to be inlined, calling each
    other compiled (numba reads a module's attributes, not a namespace object's).

    Each function is re-made with one shared namespace as its globals, in which the others are
    their compiled twins (numba cannot call a plain Python function), and `math` is `math`.
    """
    names = {module.__name__ for module in modules}
    namespace: dict = {}
    for module in modules:
        namespace.update(vars(module))
    functions = {}
    for name, value in list(namespace.items()):
        if isinstance(value, pytypes.FunctionType) and value.__module__ in names:
            twin = pytypes.FunctionType(value.__code__, namespace, name, value.__defaults__)
            namespace[name] = functions[name] = numba.njit(inline="always")(twin)
    module = pytypes.ModuleType("vooga_env.vector.kernel_parts.F")
    vars(module).update(functions)
    return module


F = compiled(physics_formulas, fight_formulas)

Params = namedtuple(
    "Params",
    [
        # arena and engine (px, ms, px/ms)
        "width", "height", "gravity", "factor", "speed_factor", "out_distance", "dt", "friction",
        "stage_left", "stage_right", "blocks", "spawns", "spawn_jitter",
        # the fighter
        "f_width", "f_height", "crouch", "mass", "speed", "health", "jump", "fast_fall",
        "head_slide", "block_damage", "block_knockback", "air_jumps",
        # the attacks, (MOVE_CODES,) arrays indexed by move code
        "damage", "knockback", "growth", "cos", "sin", "hitbox_w", "hitbox_h", "hitbox_offset_y",
        "startup", "active", "total", "hitstun", "blocked_hitstun",
        # the fight and its reward
        "frame_skip", "max_cycles", "stocks",
        "r_damage", "r_ring_out", "r_ko", "r_time", "edge",
    ],
)  # fmt: skip
State = namedtuple("State", ["fl", "it", "fg", "ct", "values"])  # FightState's blocks
Events = namedtuple("Events", ["damage", "hits", "outs", "over"])  # StepEvents' blocks
Streams = namedtuple("Streams", ["state_hi", "state_lo", "inc_hi", "inc_lo"])  # PCG64Streams'
# one frame's working arrays, indexed [fighter], [fighter, axis] or [fighter, kind, axis] (kind
# 0: position, 1: velocity); see `scratch`
Scratch = namedtuple(
    "Scratch",
    [
        "terms", "counts", "partials", "low", "high", "rubbing", "carry", "walk", "has_slide",
        "has_walk", "increments", "collided", "on_immovable", "grounded", "hit", "hit_toi",
        "hit_move", "hit_damage", "hit_blocked",
    ],
)  # fmt: skip


@intrinsic
def _stack(typingctx, size, dtype):
    """A pointer to `size` (a literal) values of `dtype` on the stack, for numba.carray: scratch
    that no other array aliases (np.empty's may alias the state), so the compiler need not
    reload it after each store to the state."""
    if not isinstance(size, types.IntegerLiteral):
        return None
    sig = types.CPointer(dtype.instance_type)(size, dtype)

    def codegen(context, builder, signature, args):
        item = context.get_data_type(dtype.instance_type)
        return cgutils.alloca_once(builder, item, size=size.literal_value)

    return sig, codegen


@inline
def scratch():
    """A frame's working arrays, on the stack (see _stack); each frame clears what it needs."""
    hit_toi = numba.carray(_stack(2, np.float64), 2)
    hit_toi[0] = hit_toi[1] = 0.0
    return Scratch(
        np.zeros((2, 2, 2, MAX_TERMS)),  # fighter, kind, axis, term
        numba.carray(_stack(8, np.int64), (2, 2, 2)),
        np.empty(MAX_TERMS + 1),
        numba.carray(_stack(8, np.float64), (2, 2, 2)),
        numba.carray(_stack(8, np.float64), (2, 2, 2)),
        numba.carray(_stack(4, np.bool_), (2, 2)),  # fighter, axis: slowed by friction
        numba.carray(_stack(4, np.float64), (2, 2)),
        numba.carray(_stack(4, np.float64), (2, 2)),  # fighter, (slide, walk) increments
        numba.carray(_stack(2, np.bool_), 2),
        numba.carray(_stack(2, np.bool_), 2),
        numba.carray(_stack(4, np.float64), (2, 2)),
        numba.carray(_stack(2, np.bool_), 2),
        numba.carray(_stack(2, np.bool_), 2),
        numba.carray(_stack(2, np.bool_), 2),
        numba.carray(_stack(2, np.bool_), 2),
        hit_toi,
        numba.carray(_stack(2, np.int64), 2),
        numba.carray(_stack(2, np.float64), 2),
        numba.carray(_stack(2, np.bool_), 2),
    )


@inline
def add_term(x, f, kind, axis, value):
    """Append a non-zero term (kind 0: position shift, 1: velocity change), as PendingResponse."""
    if value != 0.0:
        x.terms[f, kind, axis, x.counts[f, kind, axis]] = value
        x.counts[f, kind, axis] += 1


@jit
def _fsum(terms, f, kind, axis, count, partials):
    """CPython's math.fsum of terms[f, kind, axis, :count] (finite values); `partials`: scratch.

    Indexes the 4-d array rather than taking a slice: a view costs more than the sum.
    """
    if count <= 2:  # one correctly rounded addition; fsum never returns -0.0
        total = 0.0
        for t in range(count):
            total += terms[f, kind, axis, t]
        return total + 0.0
    n = 0
    for t in range(count):
        x = terms[f, kind, axis, t]
        i = 0
        for j in range(n):
            y = partials[j]
            if abs(x) < abs(y):
                x, y = y, x
            hi = x + y
            lo = y - (hi - x)
            if lo != 0.0:
                partials[i] = lo
                i += 1
            x = hi
        n = i
        if x != 0.0:
            partials[n] = x
            n += 1
    hi = 0.0
    if n > 0:
        n -= 1
        hi = partials[n]
        lo = 0.0
        while n > 0:
            x = hi
            n -= 1
            y = partials[n]
            hi = x + y
            yr = hi - x
            lo = y - yr
            if lo != 0.0:
                break
        if n > 0 and ((lo < 0.0 and partials[n - 1] < 0.0) or (lo > 0.0 and partials[n - 1] > 0.0)):
            y = lo * 2.0
            x = hi + y
            yr = x - hi
            if y == yr:
                hi = x
    return hi + 0.0


@inline
def _mulhi(a, b):
    """High 64 bits of the 128-bit product of two uint64."""
    mask = np.uint64(0xFFFFFFFF)
    a0, a1 = a & mask, a >> np.uint64(32)
    b0, b1 = b & mask, b >> np.uint64(32)
    p00, p01, p10, p11 = a0 * b0, a0 * b1, a1 * b0, a1 * b1
    middle = (p00 >> np.uint64(32)) + (p01 & mask) + (p10 & mask)
    return p11 + (p01 >> np.uint64(32)) + (p10 >> np.uint64(32)) + (middle >> np.uint64(32))


@inline
def _next_double(state_hi, state_lo, inc_hi, inc_lo, i):
    """PCG64's next double for stream i: `Generator.random()`, the top 53 bits of the XSL-RR
    output of the stepped LCG state (see rng.py)."""
    hi, lo = state_hi[i], state_lo[i]
    mul_hi, mul_lo = np.uint64(MUL_HI), np.uint64(MUL_LO)
    new_lo = lo * mul_lo
    new_hi = _mulhi(lo, mul_lo) + lo * mul_hi + hi * mul_lo
    added = new_lo + inc_lo[i]
    carry = np.uint64(1) if added < new_lo else np.uint64(0)
    new_hi = new_hi + inc_hi[i] + carry
    state_hi[i], state_lo[i] = new_hi, added
    mixed = new_hi ^ added
    rotate = new_hi >> np.uint64(58)
    output = (mixed >> rotate) | (mixed << ((np.uint64(64) - rotate) & np.uint64(63)))
    return np.float64(output >> np.uint64(11)) * (1.0 / 9007199254740992.0)
