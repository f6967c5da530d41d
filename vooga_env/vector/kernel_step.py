"""The numba backend's step: `Fight.step` of every fight, one after the other.

`vooga_env.fight.Fight._frame` and the engine's `World.step` for the default wiring (push between
the fighters, rebound with friction on blocks, the attack hitboxes), transcribed expression by
expression from the scalar originals; `frame.py` is the same with array operations.
"""

from __future__ import annotations

import numba
import numpy as np

from vooga_env.vector import kernel_parts as kp
from vooga_env.vector.kernel_parts import _contact, _fsum, _respawn, _within, jit
from vooga_env.vector.layout import ATTACK_MOVE, IS_JUMP, IS_WALK, WALK_DIRECTION


@jit
def _step(
    fp,
    ip,
    blocks,
    af,
    ai,
    actions,
    fl,
    it,
    fg,
    ct,
    values,
    damage,
    hits,
    outs,
    over,
    rewards,
    truncated,
    winner,
    start,
    stop,
):
    """One env step of the fights start..stop-1 (see the module docstring), in place.

    State blocks `fl`, `it`, `fg`, `ct` (rows: `kernel_parts.S_*`), events `damage`, `hits`,
    `outs`, `over` (state.StepEvents), outputs `rewards`, `truncated`, `winner`.
    """
    # the parameters as locals (a read of fp[...] after a store to any array is a fresh load)
    p_w = fp[kp.W]
    p_h = fp[kp.H]
    p_gravity = fp[kp.GRAVITY]
    p_factor = fp[kp.FACTOR]
    p_speed_factor = fp[kp.SPEED_FACTOR]
    p_out_distance = fp[kp.OUT_DISTANCE]
    p_dt = fp[kp.DT]
    p_friction = fp[kp.FRICTION]
    p_f_width = fp[kp.F_WIDTH]
    p_f_height = fp[kp.F_HEIGHT]
    p_crouch = fp[kp.CROUCH]
    p_mass = fp[kp.MASS]
    p_speed = fp[kp.SPEED]
    p_health = fp[kp.HEALTH]
    p_jump = fp[kp.JUMP]
    p_fast_fall = fp[kp.FAST_FALL]
    p_head_slide = fp[kp.HEAD_SLIDE]
    p_block_damage = fp[kp.BLOCK_DAMAGE]
    p_block_knockback = fp[kp.BLOCK_KNOCKBACK]
    p_r_damage = fp[kp.R_DAMAGE]
    p_r_ring_out = fp[kp.R_RING_OUT]
    p_r_ko = fp[kp.R_KO]
    p_r_time = fp[kp.R_TIME]
    p_edge = fp[kp.EDGE]
    p_frame_skip = ip[kp.FRAME_SKIP]
    p_air_jumps = ip[kp.AIR_JUMPS]
    p_max_cycles = ip[kp.MAX_CYCLES]
    n_blocks = blocks.shape[1]
    terms = np.zeros((2, 2, 2, kp.MAX_TERMS))  # fighter, kind (position, velocity), axis, term
    half = p_f_width / 2
    width = p_f_width
    dt, factor = p_dt, p_factor
    partials = np.empty(terms.shape[3] + 1)
    # scratch on the stack (see kp._stack): fighter, kind (position, velocity), axis
    counts = numba.carray(kp._stack(8, np.int64), (2, 2, 2))
    rubbing = numba.carray(kp._stack(4, np.bool_), (2, 2))  # fighter, axis: slowed by friction
    carry = numba.carray(kp._stack(4, np.float64), (2, 2))
    low = numba.carray(kp._stack(8, np.float64), (2, 2, 2))
    high = numba.carray(kp._stack(8, np.float64), (2, 2, 2))
    inc = numba.carray(kp._stack(4, np.float64), (2, 2))  # fighter, axis
    has_slide = numba.carray(kp._stack(2, np.bool_), 2)
    has_walk = numba.carray(kp._stack(2, np.bool_), 2)
    increments = numba.carray(kp._stack(4, np.float64), (2, 2))
    hit_toi = numba.carray(kp._stack(2, np.float64), 2)
    hit_toi[0] = hit_toi[1] = 0.0
    collided = numba.carray(kp._stack(2, np.bool_), 2)
    on_immovable = numba.carray(kp._stack(2, np.bool_), 2)
    grounded = numba.carray(kp._stack(2, np.bool_), 2)
    hit = numba.carray(kp._stack(2, np.bool_), 2)
    hit_move = numba.carray(kp._stack(2, np.int64), 2)
    hit_damage = numba.carray(kp._stack(2, np.float64), 2)
    hit_blocked = numba.carray(kp._stack(2, np.bool_), 2)
    for i in range(start, stop):
        for _frame in range(p_frame_skip):
            # ---- Fight._control, fighter 0 then fighter 1
            for f in range(2):
                o = 1 - f
                a = actions[i, f]
                free = it[kp.S_HITSTUN, f, i] == 0 and it[kp.S_MOVE, f, i] == 0
                if free:
                    toward = (fl[kp.S_X, o, i] + half) - (fl[kp.S_X, f, i] + half)
                    if toward != 0.0:
                        fl[kp.S_FACING, f, i] = 1.0 if toward > 0.0 else -1.0
                attack = ATTACK_MOVE[a]
                fg[kp.S_BLOCKING, f, i] = free and a == 9 and fg[kp.S_ON_GROUND, f, i]
                attacking = it[kp.S_MOVE, f, i] != 0 or (free and attack != 0)
                crouch = fg[kp.S_ON_GROUND, f, i] and (
                    (free and a == 6) or (fg[kp.S_CROUCHING, f, i] and attacking)
                )
                if crouch != fg[kp.S_CROUCHING, f, i]:
                    bottom = fl[kp.S_Y, f, i] + fl[kp.S_HEIGHT, f, i]
                    fg[kp.S_CROUCHING, f, i] = crouch
                    fl[kp.S_HEIGHT, f, i] = p_crouch if crouch else p_f_height
                    fl[kp.S_Y, f, i] = bottom - fl[kp.S_HEIGHT, f, i]
                jumping = IS_JUMP[a]
                scale = p_speed * dt * p_speed_factor
                slide = 0.0
                has_slide[f] = False
                if fg[kp.S_ON_HEAD, f, i]:
                    away = (fl[kp.S_X, f, i] + half) - (fl[kp.S_X, o, i] + half)
                    if away != 0.0:
                        direction = 1.0 if away > 0.0 else -1.0
                    else:
                        direction = -fl[kp.S_FACING, f, i]
                    slide = direction * p_head_slide
                    has_slide[f] = True
                    fg[kp.S_ON_HEAD, f, i] = False
                walk = 0.0
                has_walk[f] = False
                if free:
                    if jumping and not fg[kp.S_JUMP_HELD, f, i]:
                        if fg[kp.S_ON_GROUND, f, i]:
                            fl[kp.S_VY, f, i] = -p_jump
                        elif it[kp.S_JUMPS_LEFT, f, i] > 0:
                            it[kp.S_JUMPS_LEFT, f, i] -= 1
                            fl[kp.S_VY, f, i] = -p_jump
                    if a == 6 and not fg[kp.S_ON_GROUND, f, i]:
                        fl[kp.S_VY, f, i] = kp._py_max(fl[kp.S_VY, f, i], p_fast_fall)
                    if attack != 0:
                        it[kp.S_MOVE, f, i] = attack
                        it[kp.S_MOVE_FRAME, f, i] = 0
                        fg[kp.S_STRUCK, f, i] = False
                    if IS_WALK[a]:
                        walk = WALK_DIRECTION[a] * (1.0 if f == 0 else -1.0)
                        has_walk[f] = True
                fg[kp.S_JUMP_HELD, f, i] = jumping
                # the MotionActions' increments, added after integration (slide, then walk)
                inc[f, 0] = scale * slide * factor
                inc[f, 1] = scale * walk * factor
            # ---- Fight._place_hitbox
            for f in range(2):
                m = it[kp.S_MOVE, f, i]
                active = m != 0 and ai[0, m] <= it[kp.S_MOVE_FRAME, f, i] < ai[0, m] + ai[1, m]
                fg[kp.S_HIT_ACTIVE, f, i] = active
                if active:
                    if fl[kp.S_FACING, f, i] > 0:
                        fl[kp.S_HIT_X, f, i] = fl[kp.S_X, f, i] + width
                    else:
                        fl[kp.S_HIT_X, f, i] = fl[kp.S_X, f, i] - af[5, m]
                    fl[kp.S_HIT_Y, f, i] = (
                        fl[kp.S_Y, f, i] + fl[kp.S_HEIGHT, f, i] - p_f_height + af[7, m]
                    )
                    fl[kp.S_HIT_W, f, i] = af[5, m]
                    fl[kp.S_HIT_H, f, i] = af[6, m]
            # ---- World.step: integrate, then the walking MotionActions
            for f in range(2):
                fl[kp.S_VY, f, i] += p_gravity * 1.0 * dt
                increments[f, 0] = 0.0 + fl[kp.S_VX, f, i] * dt * factor
                increments[f, 1] = 0.0 + fl[kp.S_VY, f, i] * dt * factor
                if has_slide[f]:
                    increments[f, 0] += inc[f, 0]
                if has_walk[f]:
                    increments[f, 0] += inc[f, 1]
            for f in range(2):
                collided[f] = False
                on_immovable[f] = False
                grounded[f] = False
                hit[f] = False
                for axis in range(2):
                    rubbing[f, axis] = False
                    carry[f, axis] = 0.0
                    for kind in range(2):
                        counts[f, kind, axis] = 0
                        low[f, kind, axis] = -np.inf
                        high[f, kind, axis] = np.inf
            # ---- detection: blocks x fighters, the fighters, each hitbox x the other fighter
            for b in range(n_blocks):
                bx, by, bw, bh = blocks[0, b], blocks[1, b], blocks[2, b], blocks[3, b]
                for f in range(2):
                    found, vertical, normal, toi, _ = _contact(
                        bx,
                        bx + bw,
                        by,
                        by + bh,
                        0.0,
                        0.0,
                        fl[kp.S_X, f, i],
                        fl[kp.S_X, f, i] + width,
                        fl[kp.S_Y, f, i],
                        fl[kp.S_Y, f, i] + fl[kp.S_HEIGHT, f, i],
                        increments[f, 0],
                        increments[f, 1],
                    )
                    if found:
                        collided[f] = True
                        if vertical and normal < 0.0:
                            on_immovable[f] = True
                            grounded[f] = True
                        # ReactionRebound, no bouncy edge, with friction: done here, as it
                        # changes only low, high, carry and rubbing, which the hits and the push
                        # (ahead of it in the engine) neither read nor write
                        normal = -normal  # seen from the fighter
                        axis = 1 if vertical else 0
                        if axis == 1:
                            face, own, size = by + 0.0, fl[kp.S_HEIGHT, f, i], bh
                        else:
                            face, own, size = bx + 0.0, p_f_width, bw
                        if normal > 0.0:
                            surface = face - own
                            high[f, 0, axis] = kp._py_min(high[f, 0, axis], surface)
                            high[f, 1, axis] = kp._py_min(high[f, 1, axis], 0.0)
                        else:
                            surface = face + size
                            low[f, 0, axis] = kp._py_max(low[f, 0, axis], surface)
                            low[f, 1, axis] = kp._py_max(low[f, 1, axis], 0.0)
                        if p_friction > 0.0:  # slow_down: the strongest (largest carry) wins
                            along = 1 - axis
                            rest_carry = 1.0 * ((1.0 - toi) * dt) * factor
                            if not rubbing[f, along] or rest_carry > carry[f, along]:
                                carry[f, along] = rest_carry
                            rubbing[f, along] = True
            pair_found, pair_vertical, pair_normal, pair_toi, pair_depth = _contact(
                fl[kp.S_X, 0, i],
                fl[kp.S_X, 0, i] + width,
                fl[kp.S_Y, 0, i],
                fl[kp.S_Y, 0, i] + fl[kp.S_HEIGHT, 0, i],
                increments[0, 0],
                increments[0, 1],
                fl[kp.S_X, 1, i],
                fl[kp.S_X, 1, i] + width,
                fl[kp.S_Y, 1, i],
                fl[kp.S_Y, 1, i] + fl[kp.S_HEIGHT, 1, i],
                increments[1, 0],
                increments[1, 1],
            )
            if pair_found:
                collided[0] = True
                collided[1] = True
            for a in range(2):
                d = 1 - a
                if not fg[kp.S_HIT_ACTIVE, a, i]:
                    continue
                hl, hr = fl[kp.S_HIT_X, a, i], fl[kp.S_HIT_X, a, i] + fl[kp.S_HIT_W, a, i]
                ht, hb = fl[kp.S_HIT_Y, a, i], fl[kp.S_HIT_Y, a, i] + fl[kp.S_HIT_H, a, i]
                f_left, f_right = fl[kp.S_X, d, i], fl[kp.S_X, d, i] + width
                f_top, f_bottom = fl[kp.S_Y, d, i], fl[kp.S_Y, d, i] + fl[kp.S_HEIGHT, d, i]
                if a == 0:  # (hitbox 0, fighter 1): the hitbox is the older sprite
                    found, vertical, normal, toi, _ = _contact(
                        hl,
                        hr,
                        ht,
                        hb,
                        0.0,
                        0.0,
                        f_left,
                        f_right,
                        f_top,
                        f_bottom,
                        increments[d, 0],
                        increments[d, 1],
                    )
                    defender_normal = -normal
                else:  # (fighter 0, hitbox 1)
                    found, vertical, normal, toi, _ = _contact(
                        f_left,
                        f_right,
                        f_top,
                        f_bottom,
                        increments[d, 0],
                        increments[d, 1],
                        hl,
                        hr,
                        ht,
                        hb,
                        0.0,
                        0.0,
                    )
                    defender_normal = normal
                if found:
                    collided[d] = True
                    if vertical and defender_normal > 0.0:
                        on_immovable[d] = True
                    hit[a] = not fg[kp.S_STRUCK, a, i]
                    hit_toi[a] = toi
            for a in range(2):  # ReactionHit: hitbox a on fighter d
                if not hit[a]:
                    continue
                d = 1 - a
                fg[kp.S_STRUCK, a, i] = True
                blocked = (
                    fg[kp.S_BLOCKING, d, i] and fl[kp.S_FACING, d, i] == -fl[kp.S_FACING, a, i]
                )
                m = it[kp.S_MOVE, a, i]
                points = af[0, m] * (p_block_damage if blocked else 1.0)
                power = af[1, m] + af[2, m] * ((p_health - fl[kp.S_HEALTH, d, i]) + points)
                power *= p_block_knockback if blocked else 1.0
                remaining = (1.0 - hit_toi[a]) * dt
                delta = fl[kp.S_FACING, a, i] * power * af[3, m] - fl[kp.S_VX, d, i]
                kp._add(terms, counts, d, 1, 0, delta)
                kp._add(terms, counts, d, 0, 0, delta * remaining * factor)
                delta = -power * af[4, m] - fl[kp.S_VY, d, i]
                kp._add(terms, counts, d, 1, 1, delta)
                kp._add(terms, counts, d, 0, 1, delta * remaining * factor)
                hit_move[a] = m
                hit_damage[a] = points
                hit_blocked[a] = blocked
            if pair_found:  # ReactionPush, the contact seen from fighter 0
                axis = 1 if pair_vertical else 0
                normal = pair_normal
                mass = p_mass
                total = mass + mass
                share_one, share_two = mass / total, mass / total
                if pair_depth > 0.0:
                    kp._add(terms, counts, 0, 0, axis, -normal * pair_depth * share_one)
                    kp._add(terms, counts, 1, 0, axis, normal * pair_depth * share_two)
                along0, along1 = increments[0, axis], increments[1, axis]
                if axis == 0:
                    speed0, speed1 = fl[kp.S_VX, 0, i], fl[kp.S_VX, 1, i]
                else:
                    speed0, speed1 = fl[kp.S_VY, 0, i], fl[kp.S_VY, 1, i]
                if (along0 - along1) * normal > 0.0:
                    remaining = 1.0 - pair_toi
                    lower, upper = (1, 0) if normal > 0.0 else (0, 1)
                    if axis == 1 and on_immovable[lower]:
                        inc_upper = increments[upper, 1]
                        kp._add(
                            terms,
                            counts,
                            upper,
                            0,
                            1,
                            remaining * (kp._py_min(inc_upper, 0.0) - inc_upper),
                        )
                        kp._add(
                            terms,
                            counts,
                            upper,
                            1,
                            1,
                            kp._py_min(fl[kp.S_VY, upper, i], 0.0) - fl[kp.S_VY, upper, i],
                        )
                    else:
                        common_increment = (mass * along0 + mass * along1) / (mass + mass)
                        common_velocity = (mass * speed0 + mass * speed1) / (mass + mass)
                        kp._add(terms, counts, 0, 0, axis, remaining * (common_increment - along0))
                        kp._add(terms, counts, 0, 1, axis, common_velocity - speed0)
                        kp._add(terms, counts, 1, 0, axis, remaining * (common_increment - along1))
                        kp._add(terms, counts, 1, 1, axis, common_velocity - speed1)
            # ---- the update and keep_in_bounds
            for f in range(2):
                for axis in range(2):
                    if collided[f]:
                        # PendingResponse.resolve; fsum's order does not matter, and with no
                        # shift (the usual case) it is one addition, done here: a call of _fsum
                        # with its arrays costs more than the sum
                        speed = fl[kp.S_VX, f, i] if axis == 0 else fl[kp.S_VY, f, i]
                        count = counts[f, 1, axis]
                        if count == 0:
                            speed = speed + 0.0
                        else:
                            terms[f, 1, axis, count] = speed
                            speed = _fsum(terms, f, 1, axis, count + 1, partials)
                        slide = 0.0
                        if rubbing[f, axis]:  # friction, after the velocity's changes
                            sliding = speed + -0.0  # + the surface's velocity (a block's: 0)
                            rubbed = abs(sliding) - p_friction * dt
                            slowed = 0.0 + np.copysign(kp._py_max(rubbed, 0.0), sliding)
                            slide = (slowed - speed) * carry[f, axis]
                            speed = slowed
                        speed = _within(speed, low[f, 1, axis], high[f, 1, axis])
                        position = fl[kp.S_X, f, i] if axis == 0 else fl[kp.S_Y, f, i]
                        count = counts[f, 0, axis]
                        if count == 0 and slide == 0.0:
                            position = position + increments[f, axis] + 0.0
                        else:
                            terms[f, 0, axis, count] = position
                            terms[f, 0, axis, count + 1] = increments[f, axis]
                            terms[f, 0, axis, count + 2] = slide
                            position = _fsum(terms, f, 0, axis, count + 3, partials)
                        position = _within(position, low[f, 0, axis], high[f, 0, axis])
                        if axis == 0:
                            fl[kp.S_X, f, i], fl[kp.S_VX, f, i] = position, speed
                        else:
                            fl[kp.S_Y, f, i], fl[kp.S_VY, f, i] = position, speed
                    elif axis == 0:
                        fl[kp.S_X, f, i] = fl[kp.S_X, f, i] + increments[f, 0]
                    else:
                        fl[kp.S_Y, f, i] = fl[kp.S_Y, f, i] + increments[f, 1]
                if fl[kp.S_X, f, i] < 0.0:
                    fl[kp.S_X, f, i] = 0.0 + p_out_distance
                    fl[kp.S_VX, f, i] = kp._py_max(fl[kp.S_VX, f, i], 0.0)
                elif fl[kp.S_X, f, i] + width > p_w:
                    fl[kp.S_X, f, i] = p_w - width - p_out_distance
                    fl[kp.S_VX, f, i] = kp._py_min(fl[kp.S_VX, f, i], 0.0)
                if fl[kp.S_Y, f, i] < 0.0:
                    fl[kp.S_Y, f, i] = 0.0 + p_out_distance
                    fl[kp.S_VY, f, i] = kp._py_max(fl[kp.S_VY, f, i], 0.0)
            # ---- the rest of Fight._frame
            if pair_found and pair_vertical:
                fg[kp.S_ON_HEAD, 0 if pair_normal > 0.0 else 1, i] = True
            for f in range(2):
                fg[kp.S_ON_GROUND, f, i] = grounded[f]
                if grounded[f]:
                    it[kp.S_JUMPS_LEFT, f, i] = p_air_jumps
                if it[kp.S_HITSTUN, f, i] > 0:
                    it[kp.S_HITSTUN, f, i] -= 1
                if it[kp.S_MOVE, f, i] != 0:
                    it[kp.S_MOVE_FRAME, f, i] += 1
                    if it[kp.S_MOVE_FRAME, f, i] >= ai[2, it[kp.S_MOVE, f, i]]:
                        it[kp.S_MOVE, f, i] = 0
            for a in range(2):
                if hit[a]:
                    d = 1 - a
                    m = hit_move[a]
                    fl[kp.S_HEALTH, d, i] = kp._py_max(fl[kp.S_HEALTH, d, i] - hit_damage[a], 0.0)
                    it[kp.S_HITSTUN, d, i] = ai[4, m] if hit_blocked[a] else ai[3, m]
                    it[kp.S_MOVE, d, i] = 0
                    fg[kp.S_BLOCKING, d, i] = fg[kp.S_BLOCKING, d, i] and hit_blocked[a]
                    damage[0, a, i] += hit_damage[a]
                    damage[1, d, i] += hit_damage[a]
                    if hit_blocked[a]:
                        hits[1, d, i] += 1
                    else:
                        hits[0, a, i] += 1
            ct[kp.S_FRAME, i] += 1
            for f in range(2):
                out_down = fl[kp.S_Y, f, i] > p_h
                knocked = fl[kp.S_HEALTH, f, i] <= 0.0
                if out_down or knocked:
                    outs[0, f, i] |= out_down
                    outs[1, f, i] |= knocked and not out_down
                    it[kp.S_STOCKS, f, i] -= 1
                    if it[kp.S_STOCKS, f, i] > 0:
                        _respawn(f, i, fp, ip, fl, it, fg)
            if it[kp.S_STOCKS, 0, i] <= 0 or it[kp.S_STOCKS, 1, i] <= 0:
                over[i] = True
                break
        ct[kp.S_STEPS, i] += 1
        # ---- HitAndRingOutReward (with its edge potential), the episode's end, Fight.winner
        shaping = 0.0
        if p_edge != 0.0:
            potential = kp._edge_advantage(fp, fl, i)
            shaping = p_edge * (potential - values[kp.S_POTENTIAL, i])
            values[kp.S_POTENTIAL, i] = potential
        for me in range(2):
            other = 1 - me
            sign = 1.0 if me == 0 else -1.0
            reward = p_r_damage * (damage[0, me, i] - damage[1, me, i]) / p_health
            reward += p_r_ring_out * (np.int64(outs[0, other, i]) - np.int64(outs[0, me, i]))
            reward += p_r_ko * (np.int64(outs[1, other, i]) - np.int64(outs[1, me, i]))
            rewards[i, me] = reward + sign * shaping - p_r_time
        truncated[i] = not over[i] and ct[kp.S_STEPS, i] >= p_max_cycles
        winner[i] = -2
        if over[i] or truncated[i]:
            if it[kp.S_STOCKS, 0, i] != it[kp.S_STOCKS, 1, i]:
                winner[i] = 0 if it[kp.S_STOCKS, 0, i] > it[kp.S_STOCKS, 1, i] else 1
            elif fl[kp.S_HEALTH, 0, i] != fl[kp.S_HEALTH, 1, i]:
                winner[i] = 0 if fl[kp.S_HEALTH, 0, i] > fl[kp.S_HEALTH, 1, i] else 1
            else:
                winner[i] = -1
