"""The numba backend's scalar parts: layout of the parameter arrays, the engine's small formulas,
`math.fsum`, PCG64, the reset and the observations (see kernel.py).

Each function transcribes its original in `vooga_env.fight`, `vooga_env.physics` or
`vooga_env.observations` expression by expression, so that results are bit for bit the same.
"""

from __future__ import annotations

import numba
import numpy as np
from numba import types
from numba.core import cgutils
from numba.extending import intrinsic

from vooga_env.observations import HITSTUN_SCALE, VELOCITY_SCALE
from vooga_env.physics.contact import OVERLAP_EPSILON
from vooga_env.vector.state import (
    FIGHT_COUNTERS,
    FIGHT_FLOATS,
    FIGHTER_FLAGS,
    FIGHTER_FLOATS,
    FIGHTER_INTS,
)

jit = numba.njit(cache=True, nogil=True)
# scalar helpers of the hot loops, inlined into them: numba calls a compiled function through
# its address, which costs more than these helpers do (measured: half the time of the loops)
inline = numba.njit(cache=True, nogil=True, inline="always")

# float parameters, by index in the `fp` array (kernel.Kernel fills it in this order)
W, H, GRAVITY, FACTOR, SPEED_FACTOR, OUT_DISTANCE, DT, FRICTION = range(8)
F_WIDTH, F_HEIGHT, CROUCH, MASS, SPEED, HEALTH, JUMP, FAST_FALL = range(8, 16)
HEAD_SLIDE, BLOCK_DAMAGE, BLOCK_KNOCKBACK = range(16, 19)
R_DAMAGE, R_RING_OUT, R_KO, R_TIME, EDGE, STAGE_LEFT, STAGE_RIGHT = range(19, 26)
# int parameters, by index in the `ip` array
FRAME_SKIP, AIR_JUMPS, MAX_CYCLES = range(3)
EPSILON = OVERLAP_EPSILON
# rows of the state's blocks (state.py): fl = floats, it = ints, fg = flags, ct = counters,
# values = the fight's floats
S_X, S_Y, S_VX, S_VY, S_HEIGHT, S_HEALTH, S_FACING = range(7)
S_HIT_X, S_HIT_Y, S_HIT_W, S_HIT_H, S_SPAWN_X, S_SPAWN_TOP = range(7, 13)
S_STOCKS, S_JUMPS_LEFT, S_MOVE, S_MOVE_FRAME, S_HITSTUN = range(5)
S_ON_GROUND, S_ON_HEAD, S_JUMP_HELD, S_BLOCKING, S_CROUCHING, S_HIT_ACTIVE, S_STRUCK = range(7)
S_FRAME, S_STEPS = range(2)
S_POTENTIAL = 0
for _names in (FIGHTER_FLOATS, FIGHTER_INTS, FIGHTER_FLAGS, FIGHT_COUNTERS, FIGHT_FLOATS):
    for _row, _name in enumerate(_names):
        assert globals()["S_" + _name.upper()] == _row, f"state.py's {_name} moved"

MUL_HI, MUL_LO = 0x2360ED051FC65DA4, 0x4385DF649FCCF645  # PCG64's 128-bit multiplier
# a position's terms: itself, its increment, the friction's slide, separation, push, hit
MAX_TERMS = 6


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
def _py_max(first, second):
    return second if second > first else first


@inline
def _py_min(first, second):
    return second if second < first else first


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
def _window(low_one, high_one, low_two, high_two, move):
    if move > 0.0:
        return (low_two - high_one) / move, (high_two - low_one) / move
    if move < 0.0:
        return (high_two - low_one) / move, (low_two - high_one) / move
    if high_one - low_two > EPSILON and high_two - low_one > EPSILON:
        return -np.inf, np.inf
    return np.inf, -np.inf


@inline
def _contact(l1, r1, t1, b1, ix1, iy1, l2, r2, t2, b2, ix2, iy2):
    """Broad phase, then find_contact: (found, vertical, normal, time_of_impact, depth)."""
    low1 = l1 + ix1 if ix1 < 0.0 else l1
    high1 = r1 + ix1 if ix1 > 0.0 else r1
    low2 = l2 + ix2 if ix2 < 0.0 else l2
    high2 = r2 + ix2 if ix2 > 0.0 else r2
    if not (low2 <= high1 and low1 <= high2):
        return False, False, 0.0, 0.0, 0.0
    move_x = ix1 - ix2
    move_y = iy1 - iy2
    entry_x, exit_x = _window(l1, r1, l2, r2, move_x)
    entry_y, exit_y = _window(t1, b1, t2, b2, move_y)
    entry = _py_max(entry_x, entry_y)
    leave = _py_min(exit_x, exit_y)
    if entry >= leave or entry > 1.0 or leave <= 0.0:
        return False, False, 0.0, 0.0, 0.0
    if entry < 0.0:
        depth_x = _py_min(r1, r2) - _py_max(l1, l2)
        depth_y = _py_min(b1, b2) - _py_max(t1, t2)
        # the axis of least penetration, ties to the faster relative motion
        least = depth_x < depth_y if depth_x != depth_y else abs(move_x) > abs(move_y)
        vertical = not least
        if vertical:
            depth, gap, move = depth_y, (t2 + b2) - (t1 + b1), move_y
        else:
            depth, gap, move = depth_x, (l2 + r2) - (l1 + r1), move_x
        toward = gap if gap != 0.0 else move
        if toward == 0.0:
            toward = 1.0  # the older sprite, always the first here
        return True, vertical, 1.0 if toward >= 0.0 else -1.0, 0.0, depth
    vertical = not entry_x > entry_y
    move = move_y if vertical else move_x
    return True, vertical, 1.0 if move > 0.0 else -1.0, _py_max(entry, 0.0) + 0.0, 0.0


@inline
def _add(terms, counts, f, kind, axis, value):
    """Append a non-zero term (kind 0: position shift, 1: velocity change), as PendingResponse."""
    if value != 0.0:
        terms[f, kind, axis, counts[f, kind, axis]] = value
        counts[f, kind, axis] += 1


@jit
def _respawn(f, i, fp, ip, fl, it, fg):
    fl[S_HEIGHT, f, i] = fp[F_HEIGHT]
    fl[S_X, f, i] = fl[S_SPAWN_X, f, i]
    fl[S_Y, f, i] = fl[S_SPAWN_TOP, f, i] - fp[F_HEIGHT]
    fl[S_VX, f, i] = 0.0
    fl[S_VY, f, i] = 0.0
    fl[S_HEALTH, f, i] = fp[HEALTH]
    fl[S_FACING, f, i] = 1.0 if f == 0 else -1.0
    it[S_JUMPS_LEFT, f, i] = ip[AIR_JUMPS]
    fg[S_ON_GROUND, f, i] = True
    fg[S_ON_HEAD, f, i] = False
    fg[S_JUMP_HELD, f, i] = False
    it[S_MOVE, f, i] = 0
    it[S_MOVE_FRAME, f, i] = 0
    it[S_HITSTUN, f, i] = 0
    fg[S_BLOCKING, f, i] = False
    fg[S_CROUCHING, f, i] = False
    fg[S_HIT_ACTIVE, f, i] = False
    fg[S_STRUCK, f, i] = False


@inline
def _within(value, low, high):
    if low > high:
        return 0.5 * (low + high)
    return _py_min(_py_max(value, low), high)


@inline
def _clip32(value):
    """np.clip(np.float32(value), -2, 2), as observations.observe does."""
    clipped = np.float32(value)
    if clipped < -2.0:
        clipped = np.float32(-2.0)
    elif clipped > 2.0:
        clipped = np.float32(2.0)
    return clipped


@jit
def _observe(
    fp, ip, af, ai, index, out, fl, it, fg, ct, stage_left, stage_right, max_cycles, start_stocks
):
    """`observations.observe_both` of the fights `index`, into out[i] (float32, clipped).

    Each fighter's features are computed once, as fighter_0 sees them; fighter_1 sees the
    x-axis ones (x, vx, facing: SIDED) negated, which is exact in float64, in the float32
    rounding and in the symmetric clip. The relative x and y are computed per observer.
    """
    width = fp[F_WIDTH]
    half_width, half_height = fp[W] / 2.0, fp[H] / 2.0
    # the parameters as locals, the scratch on the stack: the stores to `out` may alias an
    # array's values, which are then loaded again (see _stack)
    stage_width, full_health, fighter_height = fp[W], fp[HEALTH], fp[F_HEIGHT]
    # (x, y) features in float64, as fighter_0 sees them
    position = numba.carray(_stack(4, np.float64), (2, 2))
    reach = numba.carray(_stack(4, np.bool_), (2, 2))
    box = numba.carray(_stack(9, np.float64), (3, 3))  # move: width, height, offset_y
    for m in range(1, 3):
        box[m, 0], box[m, 1], box[m, 2] = af[5, m], af[6, m], af[7, m]
    air = ip[AIR_JUMPS]
    for i in index:
        for f in range(2):  # Fight.reach
            o = 1 - f
            toward = (fl[S_X, o, i] + width / 2) - (fl[S_X, f, i] + width / 2)
            direction = fl[S_FACING, f, i] if toward == 0.0 else (1.0 if toward > 0.0 else -1.0)
            left, top = fl[S_X, o, i], fl[S_Y, o, i]
            right, bottom = left + width, top + fl[S_HEIGHT, o, i]
            feet = fl[S_Y, f, i] + fl[S_HEIGHT, f, i] - fighter_height
            for m in range(1, 3):
                hw = box[m, 0]
                hx = fl[S_X, f, i] + width if direction > 0 else fl[S_X, f, i] - hw
                hy = feet + box[m, 2]
                reach[f, m - 1] = (
                    hx < right and left < hx + hw and hy < bottom and top < hy + box[m, 1]
                )
        for f in range(2):
            m = it[S_MOVE, f, i]
            position[f, 0] = 1.0 * (fl[S_X, f, i] + width / 2.0 - half_width) / half_width
            position[f, 1] = (fl[S_Y, f, i] + fl[S_HEIGHT, f, i] / 2.0 - half_height) / half_height
            _feature(out, i, f, 0, _clip32(position[f, 0]), True)
            _feature(out, i, f, 1, _clip32(position[f, 1]), False)
            _feature(out, i, f, 2, _clip32(1.0 * fl[S_VX, f, i] / VELOCITY_SCALE), True)
            _feature(out, i, f, 3, _clip32(fl[S_VY, f, i] / VELOCITY_SCALE), False)
            _feature(out, i, f, 4, _clip32(1.0 * fl[S_FACING, f, i]), True)
            health = fl[S_HEALTH, f, i]
            _feature(out, i, f, 5, _clip32(health / full_health), False)
            _feature(out, i, f, 6, _clip32((full_health - health) / full_health), False)
            _feature(out, i, f, 7, np.float32(1.0 if fg[S_ON_GROUND, f, i] else 0.0), False)
            jumps = _clip32(it[S_JUMPS_LEFT, f, i] / air if air else 1.0)
            _feature(out, i, f, 8, jumps, False)
            _feature(out, i, f, 9, np.float32(1.0 if m == 1 else 0.0), False)
            _feature(out, i, f, 10, np.float32(1.0 if m == 2 else 0.0), False)
            _feature(out, i, f, 11, np.float32(1.0 if fg[S_BLOCKING, f, i] else 0.0), False)
            _feature(out, i, f, 12, np.float32(1.0 if fg[S_CROUCHING, f, i] else 0.0), False)
            progress = _clip32(it[S_MOVE_FRAME, f, i] / ai[2, m] if m != 0 else 0.0)
            _feature(out, i, f, 13, progress, False)
            _feature(out, i, f, 14, np.float32(1.0 if fg[S_HIT_ACTIVE, f, i] else 0.0), False)
            _feature(out, i, f, 15, _clip32(it[S_HITSTUN, f, i] / HITSTUN_SCALE), False)
            _feature(out, i, f, 16, _clip32(it[S_STOCKS, f, i] / start_stocks), False)
            _feature(out, i, f, 17, np.float32(1.0 if reach[f, 0] else 0.0), False)
            _feature(out, i, f, 18, np.float32(1.0 if reach[f, 1] else 0.0), False)
        remaining = _clip32(1.0 - ct[S_STEPS, i] / max_cycles)
        for me in range(2):
            side = 1.0 if me == 0 else -1.0
            other = 1 - me
            own_x, own_y = side * position[me, 0], position[me, 1]
            out[i, me, 19] = _clip32(side * position[other, 0] - own_x)
            out[i, me, 20] = _clip32(position[other, 1] - own_y)
            centre = fl[S_X, me, i] + width / 2.0
            first, second = centre - stage_left, stage_right - centre
            if side < 0:
                first, second = second, first
            out[i, me, 38] = _clip32(first / stage_width)
            out[i, me, 39] = _clip32(second / stage_width)
            out[i, me, 40] = remaining


@inline
def _feature(out, i, f, k, value, sided):
    """Fighter f's feature k (float32, as fighter_0 sees it) into out[i, f, k] (its own) and
    out[i, 1 - f, 19 + k] (its opponent's); fighter_1 sees the SIDED ones negated."""
    if sided:
        out[i, f, k] = -value if f == 1 else value
        out[i, 1 - f, 19 + k] = -value if f == 0 else value
    else:
        out[i, f, k] = value
        out[i, 1 - f, 19 + k] = value


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


@jit
def _reset(
    index,
    fp,
    ip,
    blocks,
    spawns,
    jitter,
    start_stocks,
    state_hi,
    state_lo,
    inc_hi,
    inc_lo,
    fl,
    it,
    fg,
    ct,
    values,
):
    """`Fight.reset` of the fights `index`: jittered spawns, full stocks, both respawned."""
    width = fp[F_WIDTH]
    for i in index:
        for f in range(2):
            if jitter > 0:
                u = -jitter + (jitter - -jitter) * _next_double(
                    state_hi, state_lo, inc_hi, inc_lo, i
                )
                fl[S_SPAWN_X, f, i] = spawns[f] + u
            else:
                fl[S_SPAWN_X, f, i] = spawns[f] + 0.0
            top = np.inf
            sx = fl[S_SPAWN_X, f, i]
            for b in range(blocks.shape[1]):
                bx, by, bw = blocks[0, b], blocks[1, b], blocks[2, b]
                if bx < sx + width and sx < bx + bw and by < top:
                    top = by
            fl[S_SPAWN_TOP, f, i] = top
        for f in range(2):
            it[S_STOCKS, f, i] = start_stocks
            _respawn(f, i, fp, ip, fl, it, fg)
        ct[S_FRAME, i] = 0
        ct[S_STEPS, i] = 0
        values[S_POTENTIAL, i] = _edge_advantage(fp, fl, i)  # HitAndRingOutReward.reset


@inline
def _edge_advantage(fp, fl, i):
    """`HitAndRingOutReward._edge_advantage` of fight i: fighter_0's room to its nearer stage
    edge minus fighter_1's, over the stage width."""
    centre = fl[S_X, 0, i] + fp[F_WIDTH] / 2.0
    room_0 = _py_min(centre - fp[STAGE_LEFT], fp[STAGE_RIGHT] - centre)
    centre = fl[S_X, 1, i] + fp[F_WIDTH] / 2.0
    room_1 = _py_min(centre - fp[STAGE_LEFT], fp[STAGE_RIGHT] - centre)
    return (room_0 - room_1) / (fp[STAGE_RIGHT] - fp[STAGE_LEFT])
