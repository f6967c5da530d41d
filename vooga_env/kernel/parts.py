"""The kernel's scalar parts: its records, the formulas compiled, `math.fsum`, PCG64 and scratch.

The stages (`stages.py`) take four records: `Params` (one config's numbers and attack tables, by
name), `State` (the `FightState` blocks), `Events` (the `StepEvents` blocks) and `Scratch` (one
frame's working arrays, on the stack); the reset takes `Streams` (the PCG64 states) too. The
float formulas are not written here: `F` holds `vooga_env.physics.formulas` and
`vooga_env.game.formulas` compiled, the very functions the engine calls, so the arithmetic is the
same by construction.
"""

from __future__ import annotations

import types as pytypes
from collections import namedtuple

import numba
import numpy as np
from numba import types
from numba.core import cgutils
from numba.extending import intrinsic

from vooga_env.game import formulas as fight_formulas
from vooga_env.kernel.layout import MAX_TERMS
from vooga_env.physics import formulas as physics_formulas

# The hot loops must not call their parts (a call costs more than most parts do: half the loops'
# time, measured), yet inlining numba's IR copies a callee's whole scope once per block of it,
# which grows with the square of what it inlined itself: the step took minutes to compile.
# - `stage`: the stages (and the formulas: `compiled`), each compiled once, then inlined by LLVM
#   into the loop (`forceinline`: alwaysinline); no Python wrapper (a call from Python would
#   crash): only compiled code calls them.
# - `inline`: numba-IR inlining where the IR stays small: the few-line helpers (a compiled one
#   would be compiled once per literal argument it gets), the loops around the stages
#   (step.py), and what puts scratch on the caller's stack.
# - `jit`: an entry point, or a call kept a call (`forceinline` is inherited from the caller
#   unless set).
jit = numba.njit(cache=True, nogil=True, forceinline=False)
stage = numba.njit(
    cache=True, nogil=True, forceinline=True, no_cpython_wrapper=True, no_cfunc_wrapper=True
)
inline = numba.njit(cache=True, nogil=True, inline="always")

MUL_HI, MUL_LO = 0x2360ED051FC65DA4, 0x4385DF649FCCF645  # PCG64's 128-bit multiplier


def compiled(*modules: pytypes.ModuleType) -> pytypes.ModuleType:
    """A module of every function defined in `modules`, compiled to be inlined by LLVM (see
    `stage`; with a Python wrapper, so that the tests call them), calling each other compiled
    (numba reads a module's attributes, not a namespace object's).

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
            namespace[name] = functions[name] = numba.njit(forceinline=True)(twin)
    module = pytypes.ModuleType("vooga_env.kernel.parts.F")
    vars(module).update(functions)
    return module


F = compiled(physics_formulas, fight_formulas)

# The Params record's fields: the floats, the ints, the stage, then the attack tables (one value
# per move code each). The compiled entry points take them as six arrays in this order (numba
# unboxes arrays fast, a namedtuple slowly) and build the record (`params_record`).
FLOAT_PARAMS = (
    # arena and engine (px, ms, px/ms)
    "width", "height", "gravity", "factor", "speed_factor", "out_distance", "dt", "friction",
    "stage_left", "stage_right", "spawn_jitter",
    # the fighter
    "f_width", "f_height", "crouch", "mass", "speed", "health", "jump", "fast_fall",
    "head_slide", "block_damage", "block_knockback",
    # the reward
    "r_damage", "r_ring_out", "r_ko", "r_time", "edge", "r_time_out",
    # the start
    "start_damage",
)  # fmt: skip
INT_PARAMS = ("air_jumps", "frame_skip", "max_cycles", "stocks", "random_sides", "start_steps")
STAGE_PARAMS = ("blocks", "spawns")  # (4, B): x, y, width, height; (2,) spawn x
ATTACK_FLOATS = (
    "damage", "knockback", "growth", "cos", "sin", "hitbox_w", "hitbox_h", "hitbox_offset_y",
)  # fmt: skip
ATTACK_INTS = ("startup", "active", "total", "hitstun", "blocked_hitstun")
Params = namedtuple(
    "Params", FLOAT_PARAMS + INT_PARAMS + STAGE_PARAMS + ATTACK_FLOATS + ATTACK_INTS
)
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


@intrinsic
def _unmanaged(typingctx, array):
    """The same array view without its reference count (meminfo NULL), for the records: numba
    counts a reference, atomically, each time an array is taken out of a tuple, and the stages
    take theirs in the hot loop. Valid while the array it views is alive (the call's arguments)."""
    if not isinstance(array, types.Array):
        return None

    def codegen(context, builder, signature, args):
        view = cgutils.create_struct_proxy(array)(context, builder, value=args[0])
        view.meminfo = cgutils.get_null_value(view.meminfo.type)
        view.parent = cgutils.get_null_value(view.parent.type)
        return view._getvalue()

    return array(array), codegen


@inline
def params_record(fp, ip, blocks, spawns, af, ai):
    """The Params record of the arrays (FLOAT_PARAMS, INT_PARAMS, blocks, spawns, ATTACK_FLOATS
    rows, ATTACK_INTS rows), its arrays unmanaged (see _unmanaged)."""
    u = _unmanaged
    return Params(
        fp[0], fp[1], fp[2], fp[3], fp[4], fp[5], fp[6], fp[7], fp[8], fp[9], fp[10],
        fp[11], fp[12], fp[13], fp[14], fp[15], fp[16], fp[17], fp[18], fp[19], fp[20], fp[21],
        fp[22], fp[23], fp[24], fp[25], fp[26], fp[27], fp[28],
        ip[0], ip[1], ip[2], ip[3], ip[4], ip[5],
        u(blocks), u(spawns),
        u(af[0]), u(af[1]), u(af[2]), u(af[3]), u(af[4]), u(af[5]), u(af[6]), u(af[7]),
        u(ai[0]), u(ai[1]), u(ai[2]), u(ai[3]), u(ai[4]),
    )  # fmt: skip


# params_record reads each field by position: a field added to the lists must be added there
assert [len(FLOAT_PARAMS), len(INT_PARAMS), len(ATTACK_FLOATS), len(ATTACK_INTS)] == [29, 6, 8, 5]


@inline
def state_record(fl, it, fg, ct, values):
    """A State of the FightState blocks, unmanaged (see _unmanaged)."""
    u = _unmanaged
    return State(u(fl), u(it), u(fg), u(ct), u(values))


@inline
def events_record(damage, hits, outs, over):
    """An Events of the StepEvents blocks, unmanaged (see _unmanaged)."""
    u = _unmanaged
    return Events(u(damage), u(hits), u(outs), u(over))


TERMS_SIZE = 2 * 2 * 2 * MAX_TERMS  # fighter, kind, axis, term
PARTIALS_SIZE = MAX_TERMS + 1


@inline
def scratch():
    """A frame's working arrays, on the stack (see _stack); each frame clears what it needs."""
    hit_toi = numba.carray(_stack(2, np.float64), 2)
    hit_toi[0] = hit_toi[1] = 0.0
    terms = numba.carray(_stack(TERMS_SIZE, np.float64), (2, 2, 2, MAX_TERMS))
    terms[:] = 0.0
    return Scratch(
        terms,
        numba.carray(_stack(8, np.int64), (2, 2, 2)),
        numba.carray(_stack(PARTIALS_SIZE, np.float64), PARTIALS_SIZE),
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
def _next_double(rng, i):
    """PCG64's next double for stream i of `rng` (Streams): `Generator.random()`, the top 53 bits
    of the XSL-RR output of the stepped LCG state (see rng.py)."""
    state_hi, state_lo, inc_hi, inc_lo = rng.state_hi, rng.state_lo, rng.inc_hi, rng.inc_lo
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
