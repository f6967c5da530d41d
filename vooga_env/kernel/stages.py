"""The kernel's stages: one physics frame of one fight, each stage named after its engine twin.

`control` (`Fight._control`), `place_hitboxes` (`Fight._place_hitbox`), `integrate`
(`FightPhysicsEngine.integrate` and the walking `MotionAction`s), `find_contacts`
(`Collision.check_group_collision`: blocks x fighters, the fighters, each hitbox x the other
fighter), `reaction_rebound` (`ReactionRebound` with friction), `reaction_hit` (`ReactionHit`),
`reaction_push` (`ReactionPush`), `resolve` (`PendingResponse.resolve` and the sprite's update),
`keep_in_bounds` (`FightPhysicsEngine.keep_in_bounds`), `after_frame` (the rest of
`Fight._frame`), `reward` (`HitAndRingOutReward`) and `outcome` (the episode's end and
`Fight.winner`). The float formulas are the engine's own, compiled (`parts.F`); what is
written here is the bookkeeping only. Every stage is compiled once and inlined into the step
(`step.py`) by LLVM (`parts.stage`).

Arguments: `p` Params, `s` State, `e` Events, `x` Scratch (parts), `i` the fight.
"""

from __future__ import annotations

import numpy as np

from vooga_env.game.outcome import Outcome
from vooga_env.kernel.layout import (
    ATTACK_MOVE,
    BLOCK,
    DOWN,
    IS_JUMP,
    IS_WALK,
    NO_MOVE,
    S_BLOCKING,
    S_CROUCHING,
    S_FACING,
    S_FRAME,
    S_HEALTH,
    S_HEIGHT,
    S_HIT_ACTIVE,
    S_HIT_H,
    S_HIT_W,
    S_HIT_X,
    S_HIT_Y,
    S_HITSTUN,
    S_JUMP_HELD,
    S_JUMPS_LEFT,
    S_MOVE,
    S_MOVE_FRAME,
    S_ON_GROUND,
    S_ON_HEAD,
    S_POTENTIAL,
    S_SPAWN_TOP,
    S_SPAWN_X,
    S_STEPS,
    S_STOCKS,
    S_STRUCK,
    S_VX,
    S_VY,
    S_X,
    S_Y,
    WALK_DIRECTION,
)
from vooga_env.kernel.parts import F, _fsum, add_term, inline, stage

GOING_ON, DRAW = int(Outcome.GOING_ON), int(Outcome.DRAW)  # the codes besides 0 and 1


@stage
def control(p, s, x, i, f, a):
    """Fighter f's action a this frame: facing, block, crouch, jumps, attacks, slide and walk."""
    fl, it, fg = s.fl, s.it, s.fg
    o = 1 - f
    half = p.f_width / 2
    free = it[S_HITSTUN, f, i] == 0 and it[S_MOVE, f, i] == NO_MOVE
    if free:
        toward = (fl[S_X, o, i] + half) - (fl[S_X, f, i] + half)
        if toward != 0.0:
            fl[S_FACING, f, i] = 1.0 if toward > 0.0 else -1.0
    attack = ATTACK_MOVE[a]
    fg[S_BLOCKING, f, i] = free and a == BLOCK and fg[S_ON_GROUND, f, i]
    attacking = it[S_MOVE, f, i] != NO_MOVE or (free and attack != NO_MOVE)
    crouch = fg[S_ON_GROUND, f, i] and (
        (free and a == DOWN) or (fg[S_CROUCHING, f, i] and attacking)
    )
    if crouch != fg[S_CROUCHING, f, i]:  # Fight._crouch: the feet stay where they are
        bottom = fl[S_Y, f, i] + fl[S_HEIGHT, f, i]
        fg[S_CROUCHING, f, i] = crouch
        fl[S_HEIGHT, f, i] = p.crouch if crouch else p.f_height
        fl[S_Y, f, i] = bottom - fl[S_HEIGHT, f, i]
    jumping = IS_JUMP[a]
    scale = p.speed * p.dt * p.speed_factor
    slide = 0.0
    x.has_slide[f] = False
    if fg[S_ON_HEAD, f, i]:
        away = (fl[S_X, f, i] + half) - (fl[S_X, o, i] + half)
        direction = (1.0 if away > 0.0 else -1.0) if away != 0.0 else -fl[S_FACING, f, i]
        slide = direction * p.head_slide
        x.has_slide[f] = True
        fg[S_ON_HEAD, f, i] = False
    walk = 0.0
    x.has_walk[f] = False
    if free:
        if jumping and not fg[S_JUMP_HELD, f, i]:
            if fg[S_ON_GROUND, f, i]:
                fl[S_VY, f, i] = -p.jump
            elif it[S_JUMPS_LEFT, f, i] > 0:
                it[S_JUMPS_LEFT, f, i] -= 1
                fl[S_VY, f, i] = -p.jump
        if a == DOWN and not fg[S_ON_GROUND, f, i]:
            fl[S_VY, f, i] = F.py_max(fl[S_VY, f, i], p.fast_fall)
        if attack != NO_MOVE:
            it[S_MOVE, f, i] = attack
            it[S_MOVE_FRAME, f, i] = 0
            fg[S_STRUCK, f, i] = False
        if IS_WALK[a]:
            walk = WALK_DIRECTION[a] * (1.0 if f == 0 else -1.0)
            x.has_walk[f] = True
    fg[S_JUMP_HELD, f, i] = jumping
    # the MotionActions' increments, added after integration (slide, then walk)
    x.walk[f, 0] = scale * slide * p.factor
    x.walk[f, 1] = scale * walk * p.factor


@stage
def place_hitboxes(p, s, i):
    """Each fighter's hitbox, in front of it during its attack's active frames."""
    fl, it, fg = s.fl, s.it, s.fg
    for f in range(2):
        m = it[S_MOVE, f, i]
        active = (
            m != NO_MOVE and p.startup[m] <= it[S_MOVE_FRAME, f, i] < p.startup[m] + p.active[m]
        )
        fg[S_HIT_ACTIVE, f, i] = active
        if active:
            left = fl[S_X, f, i]
            fl[S_HIT_X, f, i] = F.hitbox_x(
                left, left + p.f_width, fl[S_FACING, f, i], p.hitbox_w[m]
            )
            bottom = fl[S_Y, f, i] + fl[S_HEIGHT, f, i]
            fl[S_HIT_Y, f, i] = F.hitbox_y(bottom, p.f_height, p.hitbox_offset_y[m])
            fl[S_HIT_W, f, i] = p.hitbox_w[m]
            fl[S_HIT_H, f, i] = p.hitbox_h[m]


@stage
def integrate(p, s, x, i):
    """Gravity, the velocity's increment, then the walking MotionActions' (slide, then walk)."""
    fl = s.fl
    for f in range(2):
        fl[S_VY, f, i] += p.gravity * 1.0 * p.dt
        x.increments[f, 0] = 0.0 + F.displacement(fl[S_VX, f, i], p.dt, p.factor)
        x.increments[f, 1] = 0.0 + F.displacement(fl[S_VY, f, i], p.dt, p.factor)
        if x.has_slide[f]:
            x.increments[f, 0] += x.walk[f, 0]
        if x.has_walk[f]:
            x.increments[f, 0] += x.walk[f, 1]


@stage
def box_contact(l1, r1, t1, b1, ix1, iy1, l2, r2, t2, b2, ix2, iy2):
    """The broad phase (swept x intervals), then the contact test, box one the older sprite."""
    low1, high1 = F.swept_interval(l1, r1, ix1)
    low2, high2 = F.swept_interval(l2, r2, ix2)
    if not (low2 <= high1 and low1 <= high2):
        return False, 0, 0.0, 0.0, 0.0
    return F.contact(l1, r1, t1, b1, l2, r2, t2, b2, ix1 - ix2, iy1 - iy2, True)


@inline
def fighter_box(p, s, f, i):
    """Fighter f's (left, right, top, bottom)."""
    left, top = s.fl[S_X, f, i], s.fl[S_Y, f, i]
    return left, left + p.f_width, top, top + s.fl[S_HEIGHT, f, i]


@stage
def find_contacts(p, s, x, i):
    """Every contact of the frame, flagged; rebounds recorded as found. Returns the fighters' pair
    contact (found, axis, normal, time_of_impact, depth), seen from fighter 0."""
    for f in range(2):
        x.collided[f] = x.on_immovable[f] = x.grounded[f] = x.hit[f] = False
        for axis in range(2):
            x.rubbing[f, axis] = False
            x.carry[f, axis] = 0.0
            for kind in range(2):
                x.counts[f, kind, axis] = 0
                x.low[f, kind, axis] = -np.inf
                x.high[f, kind, axis] = np.inf
    for b in range(p.blocks.shape[1]):
        bx, by, bw, bh = p.blocks[0, b], p.blocks[1, b], p.blocks[2, b], p.blocks[3, b]
        for f in range(2):
            left, right, top, bottom = fighter_box(p, s, f, i)
            found, axis, normal, toi, _ = box_contact(
                bx, bx + bw, by, by + bh, 0.0, 0.0,
                left, right, top, bottom, x.increments[f, 0], x.increments[f, 1],
            )  # fmt: skip
            if found:
                x.collided[f] = True
                if axis == 1 and normal < 0.0:  # the block's top edge
                    x.on_immovable[f] = x.grounded[f] = True
                # done here: it changes only the bounds and the friction, which the hits and
                # the push (ahead of it in the engine) neither read nor write
                reaction_rebound(p, s, x, i, f, b, axis, -normal, toi)
    l0, r0, t0, b0 = fighter_box(p, s, 0, i)
    l1, r1, t1, b1 = fighter_box(p, s, 1, i)
    pair = box_contact(
        l0, r0, t0, b0, x.increments[0, 0], x.increments[0, 1],
        l1, r1, t1, b1, x.increments[1, 0], x.increments[1, 1],
    )  # fmt: skip
    if pair[0]:
        x.collided[0] = x.collided[1] = True
    for a in range(2):
        if s.fg[S_HIT_ACTIVE, a, i]:
            hitbox_contact(p, s, x, i, a)
    return pair


@stage
def hitbox_contact(p, s, x, i, a):
    """Fighter a's hitbox against the other fighter d: flags d, records a hit not yet struck."""
    fl, d = s.fl, 1 - a
    hl, hr = fl[S_HIT_X, a, i], fl[S_HIT_X, a, i] + fl[S_HIT_W, a, i]
    ht, hb = fl[S_HIT_Y, a, i], fl[S_HIT_Y, a, i] + fl[S_HIT_H, a, i]
    left, right, top, bottom = fighter_box(p, s, d, i)
    ix, iy = x.increments[d, 0], x.increments[d, 1]
    if a == 0:  # (hitbox 0, fighter 1): the hitbox is the older sprite
        found, axis, normal, toi, _ = box_contact(
            hl, hr, ht, hb, 0.0, 0.0, left, right, top, bottom, ix, iy
        )
        normal = -normal  # seen from the defender
    else:  # (fighter 0, hitbox 1)
        found, axis, normal, toi, _ = box_contact(
            left, right, top, bottom, ix, iy, hl, hr, ht, hb, 0.0, 0.0
        )
    if found:
        x.collided[d] = True
        if axis == 1 and normal > 0.0:
            x.on_immovable[d] = True
        x.hit[a] = not s.fg[S_STRUCK, a, i]
        x.hit_toi[a] = toi


@stage
def reaction_rebound(p, s, x, i, f, b, axis, normal, toi):
    """ReactionRebound (no bouncy edge) of fighter f on block b; `normal` seen from the fighter."""
    bx, by, bw, bh = p.blocks[0, b], p.blocks[1, b], p.blocks[2, b], p.blocks[3, b]
    if axis == 1:
        face, own, size = by + 0.0, s.fl[S_HEIGHT, f, i], bh
    else:
        face, own, size = bx + 0.0, p.f_width, bw
    surface = F.rebound_surface(face, size, own, normal)
    if normal > 0.0:
        x.high[f, 0, axis] = F.py_min(x.high[f, 0, axis], surface)
        x.high[f, 1, axis] = F.py_min(x.high[f, 1, axis], 0.0)
    else:
        x.low[f, 0, axis] = F.py_max(x.low[f, 0, axis], surface)
        x.low[f, 1, axis] = F.py_max(x.low[f, 1, axis], 0.0)
    if p.friction > 0.0:  # slow_down: the strongest (largest carry) wins
        along = 1 - axis
        carry = F.displacement(1.0, (1.0 - toi) * p.dt, p.factor)
        if not x.rubbing[f, along] or carry > x.carry[f, along]:
            x.carry[f, along] = carry
        x.rubbing[f, along] = True


@stage
def reaction_hit(p, s, x, i, a):
    """ReactionHit of fighter a's hitbox on fighter d: the launch as terms, the hit recorded."""
    fl, fg, d = s.fl, s.fg, 1 - a
    fg[S_STRUCK, a, i] = True
    blocked = fg[S_BLOCKING, d, i] and fl[S_FACING, d, i] == -fl[S_FACING, a, i]
    m = s.it[S_MOVE, a, i]
    points = F.hit_damage(p.damage[m], blocked, p.block_damage)
    taken = p.health - fl[S_HEALTH, d, i]
    power = F.knockback(p.knockback[m], p.growth[m], taken, points, blocked, p.block_knockback)
    remaining = (1.0 - x.hit_toi[a]) * p.dt
    delta = fl[S_FACING, a, i] * power * p.cos[m] - fl[S_VX, d, i]
    add_term(x, d, 1, 0, delta)
    add_term(x, d, 0, 0, F.displacement(delta, remaining, p.factor))
    delta = -power * p.sin[m] - fl[S_VY, d, i]
    add_term(x, d, 1, 1, delta)
    add_term(x, d, 0, 1, F.displacement(delta, remaining, p.factor))
    x.hit_move[a] = m
    x.hit_damage[a] = points
    x.hit_blocked[a] = blocked


@stage
def reaction_push(p, s, x, i, axis, normal, toi, depth):
    """ReactionPush of the fighters' contact (seen from fighter 0): separation, then the common
    motion while they close, or the upper one stopped on a grounded lower one."""
    share_one, share_two = F.shares(p.mass, p.mass)
    if depth > 0.0:
        add_term(x, 0, 0, axis, -normal * depth * share_one)
        add_term(x, 1, 0, axis, normal * depth * share_two)
    along0, along1 = x.increments[0, axis], x.increments[1, axis]
    velocity = S_VX if axis == 0 else S_VY
    speed0, speed1 = s.fl[velocity, 0, i], s.fl[velocity, 1, i]
    if (along0 - along1) * normal > 0.0:
        lower, upper = (1, 0) if normal > 0.0 else (0, 1)
        if axis == 1 and x.on_immovable[lower]:
            before = x.increments[upper, 1]
            add_term(x, upper, 0, 1, F.redirect_shift(toi, F.py_min(before, 0.0), before))
            speed = s.fl[S_VY, upper, i]
            add_term(x, upper, 1, 1, F.py_min(speed, 0.0) - speed)
        else:
            common_increment = F.common(p.mass, along0, p.mass, along1)
            common_velocity = F.common(p.mass, speed0, p.mass, speed1)
            add_term(x, 0, 0, axis, F.redirect_shift(toi, common_increment, along0))
            add_term(x, 0, 1, axis, common_velocity - speed0)
            add_term(x, 1, 0, axis, F.redirect_shift(toi, common_increment, along1))
            add_term(x, 1, 1, axis, common_velocity - speed1)


@stage
def resolve(p, s, x, i, f):
    """Fighter f's update: the reactions' result if it collided (exact sums, friction, bounds),
    else its increment."""
    fl = s.fl
    for axis in range(2):
        position_row, velocity_row = (S_X, S_VX) if axis == 0 else (S_Y, S_VY)
        if not x.collided[f]:
            fl[position_row, f, i] = fl[position_row, f, i] + x.increments[f, axis]
            continue
        # fsum's order does not matter, and with no term (the usual case) it is one addition,
        # done here: a call of _fsum with its arrays costs more than the sum
        speed = fl[velocity_row, f, i]
        count = x.counts[f, 1, axis]
        if count == 0:
            speed = speed + 0.0
        else:
            x.terms[f, 1, axis, count] = speed
            speed = _fsum(x.terms, f, 1, axis, count + 1, x.partials)
        slide = 0.0
        if x.rubbing[f, axis]:  # friction, after the velocity's changes; a block's velocity is 0
            slowed = F.friction(speed, p.friction * p.dt, -0.0)
            slide = (slowed - speed) * x.carry[f, axis]
            speed = slowed
        speed = F.within(speed, x.low[f, 1, axis], x.high[f, 1, axis])
        position = fl[position_row, f, i]
        count = x.counts[f, 0, axis]
        if count == 0 and slide == 0.0:
            position = position + x.increments[f, axis] + 0.0
        else:
            x.terms[f, 0, axis, count] = position
            x.terms[f, 0, axis, count + 1] = x.increments[f, axis]
            x.terms[f, 0, axis, count + 2] = slide
            position = _fsum(x.terms, f, 0, axis, count + 3, x.partials)
        fl[position_row, f, i] = F.within(position, x.low[f, 0, axis], x.high[f, 0, axis])
        fl[velocity_row, f, i] = speed


@stage
def keep_in_bounds(p, s, i, f):
    """Fighter f back inside the arena's left, right and top bounds (not the bottom: ring-out)."""
    fl = s.fl
    if fl[S_X, f, i] < 0.0:
        fl[S_X, f, i] = 0.0 + p.out_distance
        fl[S_VX, f, i] = F.py_max(fl[S_VX, f, i], 0.0)
    elif fl[S_X, f, i] + p.f_width > p.width:
        fl[S_X, f, i] = p.width - p.f_width - p.out_distance
        fl[S_VX, f, i] = F.py_min(fl[S_VX, f, i], 0.0)
    if fl[S_Y, f, i] < 0.0:
        fl[S_Y, f, i] = 0.0 + p.out_distance
        fl[S_VY, f, i] = F.py_max(fl[S_VY, f, i], 0.0)


@stage
def after_frame(p, s, e, x, i, pair_found, pair_axis, pair_normal):
    """The rest of Fight._frame: on-head, landing, stun and move counters, the hits in attacker
    order, ring-outs and KOs (respawns). True when a fighter lost its last stock."""
    it = s.it
    if pair_found and pair_axis == 1:
        s.fg[S_ON_HEAD, 0 if pair_normal > 0.0 else 1, i] = True
    for f in range(2):
        s.fg[S_ON_GROUND, f, i] = x.grounded[f]
        if x.grounded[f]:
            it[S_JUMPS_LEFT, f, i] = p.air_jumps
        if it[S_HITSTUN, f, i] > 0:
            it[S_HITSTUN, f, i] -= 1
        if it[S_MOVE, f, i] != NO_MOVE:
            it[S_MOVE_FRAME, f, i] += 1
            if it[S_MOVE_FRAME, f, i] >= p.total[it[S_MOVE, f, i]]:
                it[S_MOVE, f, i] = NO_MOVE
    for a in range(2):
        if x.hit[a]:
            apply_hit(p, s, e, x, i, a)
    s.ct[S_FRAME, i] += 1
    for f in range(2):
        out_down = s.fl[S_Y, f, i] > p.height
        knocked = s.fl[S_HEALTH, f, i] <= 0.0
        if out_down or knocked:
            e.outs[0, f, i] |= out_down
            e.outs[1, f, i] |= knocked and not out_down
            it[S_STOCKS, f, i] -= 1
            if it[S_STOCKS, f, i] > 0:
                respawn(p, s, f, i)
    return it[S_STOCKS, 0, i] <= 0 or it[S_STOCKS, 1, i] <= 0


@stage
def apply_hit(p, s, e, x, i, a):
    """Fight._apply_hit of fighter a's hit: health, stun, the defender's move and block, events."""
    d, m, points, blocked = 1 - a, x.hit_move[a], x.hit_damage[a], x.hit_blocked[a]
    s.fl[S_HEALTH, d, i] = F.py_max(s.fl[S_HEALTH, d, i] - points, 0.0)
    s.it[S_HITSTUN, d, i] = p.blocked_hitstun[m] if blocked else p.hitstun[m]
    s.it[S_MOVE, d, i] = NO_MOVE
    s.fg[S_BLOCKING, d, i] = s.fg[S_BLOCKING, d, i] and blocked
    e.damage[0, a, i] += points
    e.damage[1, d, i] += points
    if blocked:
        e.hits[1, d, i] += 1
    else:
        e.hits[0, a, i] += 1


@stage
def respawn(p, s, f, i):
    """Fight._respawn: back on the spawn point, standing, at full health, with no move or stun."""
    fl, it, fg = s.fl, s.it, s.fg
    fl[S_HEIGHT, f, i] = p.f_height
    fl[S_X, f, i] = fl[S_SPAWN_X, f, i]
    fl[S_Y, f, i] = fl[S_SPAWN_TOP, f, i] - p.f_height
    fl[S_VX, f, i] = 0.0
    fl[S_VY, f, i] = 0.0
    fl[S_HEALTH, f, i] = p.health
    fl[S_FACING, f, i] = 1.0 if f == 0 else -1.0
    it[S_JUMPS_LEFT, f, i] = p.air_jumps
    fg[S_ON_GROUND, f, i] = True
    fg[S_ON_HEAD, f, i] = False
    fg[S_JUMP_HELD, f, i] = False
    it[S_MOVE, f, i] = NO_MOVE
    it[S_MOVE_FRAME, f, i] = 0
    it[S_HITSTUN, f, i] = 0
    fg[S_BLOCKING, f, i] = False
    fg[S_CROUCHING, f, i] = False
    fg[S_HIT_ACTIVE, f, i] = False
    fg[S_STRUCK, f, i] = False


@stage
def edge_advantage(p, s, i):
    """The reward's edge potential of fight i (formulas.edge_advantage)."""
    room_0 = F.edge_room(s.fl[S_X, 0, i] + p.f_width / 2.0, p.stage_left, p.stage_right)
    room_1 = F.edge_room(s.fl[S_X, 1, i] + p.f_width / 2.0, p.stage_left, p.stage_right)
    return F.edge_advantage(room_0, room_1, p.stage_left, p.stage_right)


@stage
def reward(p, s, e, i, rewards):
    """HitAndRingOutReward of the step (its edge shaping included) into rewards[i]."""
    shaping = 0.0
    if p.edge != 0.0:
        potential = edge_advantage(p, s, i)
        shaping = p.edge * (potential - s.values[S_POTENTIAL, i])
        s.values[S_POTENTIAL, i] = potential
    for me in range(2):
        other = 1 - me
        sign = 1.0 if me == 0 else -1.0
        value = p.r_damage * (e.damage[0, me, i] - e.damage[1, me, i]) / p.health
        value += p.r_ring_out * (np.int64(e.outs[0, other, i]) - np.int64(e.outs[0, me, i]))
        value += p.r_ko * (np.int64(e.outs[1, other, i]) - np.int64(e.outs[1, me, i]))
        rewards[i, me] = value + sign * shaping - p.r_time


@stage
def time_out_reward(p, winner, i, rewards):
    """HitAndRingOutReward's win on time: + `time_out` to the leader of a fight that ran out of
    time, - to the other, added last (as there); nothing on a draw."""
    if p.r_time_out != 0.0 and (winner == 0 or winner == 1):
        rewards[i, winner] += p.r_time_out
        rewards[i, 1 - winner] -= p.r_time_out


@stage
def outcome(p, s, e, i):
    """(truncated, winner) after the step: 0 or 1 (more stocks, then more health), DRAW, or
    GOING_ON while the fight neither ended nor ran out of steps."""
    truncated = F.time_out(e.over[i], s.ct[S_STEPS, i], p.max_cycles)
    if not (e.over[i] or truncated):
        return truncated, GOING_ON
    it, fl = s.it, s.fl
    if it[S_STOCKS, 0, i] != it[S_STOCKS, 1, i]:
        return truncated, 0 if it[S_STOCKS, 0, i] > it[S_STOCKS, 1, i] else 1
    if fl[S_HEALTH, 0, i] != fl[S_HEALTH, 1, i]:
        return truncated, 0 if fl[S_HEALTH, 0, i] > fl[S_HEALTH, 1, i] else 1
    return truncated, DRAW
