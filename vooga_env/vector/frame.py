"""One physics frame of N fights with array operations: `Fight._frame` over the physics engine.

The order is the single env's: each fighter's control (fighter 0 first), the hitboxes, then the
engine's frame (integrate, walking, contacts, reactions, update, bounds), then the fight's
bookkeeping (landing, stun and move counters, hits in attacker order, ring-outs and KOs).
Reactions collect their shifts and velocity changes as terms that `fsum_columns` adds exactly as
`math.fsum` does, and their bounds as intervals, as `PendingResponse` does.
"""

from __future__ import annotations

import numpy as np

from vooga_env.actions import Action
from vooga_env.fight import SIDES
from vooga_env.vector.contacts import Box, Contacts, find_contacts, py_max, py_min, swept_overlap
from vooga_env.vector.fsum import fsum_columns
from vooga_env.vector.params import FightParams
from vooga_env.vector.state import FightState, StepEvents

# per action code: is it a jump, an attack (its move code), a walk (its direction)
IS_JUMP = np.isin(np.arange(len(Action)), [Action.JUMP, Action.JUMP_LEFT, Action.JUMP_RIGHT])
ATTACK_MOVE = np.zeros(len(Action), dtype=np.int64)
ATTACK_MOVE[Action.PUNCH], ATTACK_MOVE[Action.KICK] = 1, 2
WALK_DIRECTION = np.zeros(len(Action))
WALK_DIRECTION[[Action.LEFT, Action.JUMP_LEFT]] = -1.0
WALK_DIRECTION[[Action.RIGHT, Action.JUMP_RIGHT]] = 1.0
IS_WALK = WALK_DIRECTION != 0.0


class Response:
    """What the reactions ask of one fighter this frame, per axis: terms and bounds."""

    def __init__(self, size: int) -> None:
        self.shifts: tuple[list[np.ndarray], list[np.ndarray]] = ([], [])
        self.changes: tuple[list[np.ndarray], list[np.ndarray]] = ([], [])
        self.low = [np.full(size, -np.inf), np.full(size, -np.inf)]
        self.high = [np.full(size, np.inf), np.full(size, np.inf)]
        self.velocity_low = [np.full(size, -np.inf), np.full(size, -np.inf)]
        self.velocity_high = [np.full(size, np.inf), np.full(size, np.inf)]
        # PendingResponse.slow_down: friction per axis, the strongest once (its carry, px per
        # px/ms of velocity change, for the rest of the frame)
        self.rubbing = [np.zeros(size, dtype=bool), np.zeros(size, dtype=bool)]
        self.carry = [np.zeros(size), np.zeros(size)]

    def along(self, vertical: np.ndarray, mask: np.ndarray, shift=None, change=None) -> None:
        """Add a shift and/or a velocity change on the contact's axis where `mask` holds."""
        for axis, on_axis in enumerate((~vertical, vertical)):
            where = mask & on_axis
            if shift is not None:
                self.shifts[axis].append(np.where(where, shift, 0.0))
            if change is not None:
                self.changes[axis].append(np.where(where, change, 0.0))


def frame(p: FightParams, s: FightState, actions: np.ndarray, events: StepEvents) -> None:
    """Advance every fight one physics frame; `actions` is (2, N) action codes."""
    fighter = p.config.fighter
    slides, walks = [], []
    for f in (0, 1):
        slide, walk = _control(p, s, f, actions[f])
        slides.append(slide)
        walks.append(walk)
    for f in (0, 1):
        _place_hitbox(p, s, f)
    # the engine's frame: integrate (gravity, then velocity into the increment), then walking
    dt, factor = p.frame_time, p.background_factor
    s.vy += p.gravity * 1.0 * dt
    increment_x = 0.0 + s.vx * dt * factor
    increment_y = 0.0 + s.vy * dt * factor
    scale = fighter.speed * dt * p.speed_factor
    for f in (0, 1):
        # slide first, as Fight._control lists them; a vector of 0.0 (no motion) adds +0.0, which
        # changes nothing, as an increment is never -0.0 (it starts as 0.0 + ...)
        increment_x[f] += scale * slides[f] * factor
        increment_x[f] += scale * walks[f] * factor
    contacts = _detect(p, s, increment_x, increment_y)
    grounded, hits = _react_and_update(p, s, increment_x, increment_y, contacts)
    _after_frame(p, s, contacts, grounded, hits, events)


def _control(p: FightParams, s: FightState, f: int, action: np.ndarray):
    """`Fight._control` for fighter f: its slide and walk vectors (0.0 where none)."""
    c = p.config.fighter
    o = 1 - f
    half = c.width / 2
    free = (s.hitstun[f] == 0) & (s.move[f] == 0)
    toward = (s.x[o] + half) - (s.x[f] + half)
    turn = free & (toward != 0.0)
    s.facing[f] = np.where(turn, np.where(toward > 0.0, 1.0, -1.0), s.facing[f])
    attack_move = ATTACK_MOVE[action]
    s.blocking[f] = free & (action == Action.BLOCK) & s.on_ground[f]
    attacking = (s.move[f] != 0) | (free & (attack_move != 0))
    crouch = s.on_ground[f] & ((free & (action == Action.DOWN)) | (s.crouching[f] & attacking))
    change = crouch != s.crouching[f]
    bottom = s.y[f] + s.height[f]
    new_height = np.where(crouch, c.crouch_height, c.height)
    s.crouching[f] = crouch
    s.height[f] = np.where(change, new_height, s.height[f])
    s.y[f] = np.where(change, bottom - new_height, s.y[f])
    jumping = IS_JUMP[action]
    away = (s.x[f] + half) - (s.x[o] + half)
    direction = np.where(away != 0.0, np.where(away > 0.0, 1.0, -1.0), -s.facing[f])
    slide = np.where(s.on_head[f], direction * c.head_slide, 0.0)
    s.on_head[f] = False
    jump = free & jumping & ~s.jump_held[f]
    air_jump = jump & ~s.on_ground[f] & (s.jumps_left[f] > 0)
    s.jumps_left[f] -= air_jump
    s.vy[f] = np.where((jump & s.on_ground[f]) | air_jump, -c.jump_speed, s.vy[f])
    fast_fall = free & (action == Action.DOWN) & ~s.on_ground[f]
    s.vy[f] = np.where(fast_fall, py_max(s.vy[f], c.fast_fall_speed), s.vy[f])
    start = free & (attack_move != 0)
    s.move[f] = np.where(start, attack_move, s.move[f])
    s.move_frame[f] = np.where(start, 0, s.move_frame[f])
    s.struck[f] &= ~start
    walk = np.where(free & IS_WALK[action], WALK_DIRECTION[action] * SIDES[f], 0.0)
    s.jump_held[f] = jumping
    return slide, walk


def _place_hitbox(p: FightParams, s: FightState, f: int) -> None:
    move = s.move[f]
    startup = p.attack_startup[move]
    active = (
        (move != 0)
        & (startup <= s.move_frame[f])
        & (s.move_frame[f] < startup + p.attack_active[move])
    )
    s.hit_active[f] = active
    width = p.hitbox_w[move]
    x = np.where(s.facing[f] > 0, s.x[f] + p.config.fighter.width, s.x[f] - width)
    y = s.y[f] + s.height[f] - p.config.fighter.height + p.hitbox_offset_y[move]
    s.hit_x[f] = np.where(active, x, s.hit_x[f])
    s.hit_y[f] = np.where(active, y, s.hit_y[f])
    s.hit_w[f] = np.where(active, width, s.hit_w[f])
    s.hit_h[f] = np.where(active, p.hitbox_h[move], s.hit_h[f])


def _boxes(p: FightParams, s: FightState, increment_x, increment_y):
    width = p.config.fighter.width
    fighters = [
        Box(s.x[f], s.y[f], width, s.height[f], increment_x[f], increment_y[f]) for f in (0, 1)
    ]
    hitboxes = [Box(s.hit_x[f], s.hit_y[f], s.hit_w[f], s.hit_h[f]) for f in (0, 1)]
    blocks = [
        Box(bx, by, bw, bh)
        for bx, by, bw, bh in zip(
            p.block_x.tolist(), p.block_y.tolist(), p.block_w.tolist(), p.block_h.tolist()
        )
    ]
    return fighters, hitboxes, blocks


def _detect(p: FightParams, s: FightState, increment_x, increment_y) -> dict:
    """Every pair's contacts: ("block", b, f), ("fighters",), ("hit", attacker)."""
    fighters, hitboxes, blocks = _boxes(p, s, increment_x, increment_y)
    contacts = {}
    for b, block in enumerate(blocks):
        for f in (0, 1):
            candidate = swept_overlap(block, fighters[f])
            contacts["block", b, f] = find_contacts(block, fighters[f], candidate)
    candidate = swept_overlap(fighters[0], fighters[1])
    contacts["fighters"] = find_contacts(fighters[0], fighters[1], candidate)
    # (hitbox 0, fighter 1) and (fighter 0, hitbox 1): the older sprite first, as the engine does
    candidate = s.hit_active[0] & swept_overlap(hitboxes[0], fighters[1])
    contacts["hit", 0] = find_contacts(hitboxes[0], fighters[1], candidate)
    candidate = s.hit_active[1] & swept_overlap(fighters[0], hitboxes[1])
    contacts["hit", 1] = _flipped(find_contacts(fighters[0], hitboxes[1], candidate))
    return contacts


def _flipped(contacts: Contacts) -> Contacts:
    """The contacts seen from the second sprite (so "hit" contacts are seen from the hitbox)."""
    return Contacts(
        contacts.found, contacts.vertical, -contacts.normal, contacts.time_of_impact, contacts.depth
    )


def _react_and_update(p: FightParams, s: FightState, increment_x, increment_y, contacts):
    """Statuses, reactions (hit, push, rebound), the update; returns who landed on a block."""
    size = s.size
    fighter = p.config.fighter
    responses = [Response(size), Response(size)]
    collided = [np.zeros(size, dtype=bool), np.zeros(size, dtype=bool)]
    on_immovable = [np.zeros(size, dtype=bool), np.zeros(size, dtype=bool)]  # status.on_ground
    grounded = [np.zeros(size, dtype=bool), np.zeros(size, dtype=bool)]  # on a block's top
    for b in range(p.blocks):
        for f in (0, 1):
            c = contacts["block", b, f]
            landed = c.found & c.vertical & (c.normal < 0.0)  # the block's top edge
            collided[f] |= c.found
            on_immovable[f] |= landed
            grounded[f] |= landed
    for a in (0, 1):
        c = contacts["hit", a]  # seen from the hitbox
        collided[1 - a] |= c.found
        on_immovable[1 - a] |= c.found & c.vertical & (c.normal < 0.0)
    c = contacts["fighters"]
    collided[0] |= c.found
    collided[1] |= c.found
    velocity = (s.vx, s.vy)
    increment = (increment_x, increment_y)
    hits = [_hit(p, s, a, contacts["hit", a], responses[1 - a]) for a in (0, 1)]
    _push(p, s, c, increment, velocity, on_immovable, responses)
    for b in range(p.blocks):
        for f in (0, 1):
            _rebound(p, s, b, f, contacts["block", b, f], responses[f])
    # the update (PendingResponse.resolve) where a fighter collided, else its increment: the
    # velocity's changes, then friction, whose slide joins the position's shifts
    speeds = _fsum_all(
        [[velocity[axis][f], *responses[f].changes[axis]] for f in (0, 1) for axis in (0, 1)],
        size,
    )
    amount = p.friction * p.frame_time
    columns = []
    for f in (0, 1):
        r = responses[f]
        for axis in (0, 1):
            k = 2 * f + axis
            sliding = speeds[k] + -0.0  # + the slowed surface's velocity: blocks stand still
            slowed = 0.0 + np.copysign(py_max(np.abs(sliding) - amount, 0.0), sliding)
            slide = np.where(r.rubbing[axis], (slowed - speeds[k]) * r.carry[axis], 0.0)
            speeds[k] = np.where(r.rubbing[axis], slowed, speeds[k])
            position = (s.x, s.y)[axis][f]
            columns.append([position, increment[axis][f], slide, *r.shifts[axis]])
    sums = _fsum_all(columns, size)
    for f in (0, 1):
        r = responses[f]
        for axis in (0, 1):
            k = 2 * f + axis
            position, speed = (s.x, s.y)[axis], (s.vx, s.vy)[axis]
            resolved = _within(sums[k], r.low[axis], r.high[axis])
            resolved_speed = _within(speeds[k], r.velocity_low[axis], r.velocity_high[axis])
            position[f] = np.where(collided[f], resolved, position[f] + increment[axis][f])
            speed[f] = np.where(collided[f], resolved_speed, speed[f])
        # FightPhysicsEngine.keep_in_bounds
        out_left = s.x[f] < 0.0
        out_right = ~out_left & (s.x[f] + fighter.width > p.width)
        s.vx[f] = np.where(
            out_left, py_max(s.vx[f], 0.0), np.where(out_right, py_min(s.vx[f], 0.0), s.vx[f])
        )
        s.x[f] = np.where(
            out_left,
            0.0 + p.out_bound_distance,
            np.where(out_right, p.width - fighter.width - p.out_bound_distance, s.x[f]),
        )
        out_up = s.y[f] < 0.0
        s.vy[f] = np.where(out_up, py_max(s.vy[f], 0.0), s.vy[f])
        s.y[f] = np.where(out_up, 0.0 + p.out_bound_distance, s.y[f])
    return grounded, hits


def _fsum_all(columns: list[list[np.ndarray]], size: int) -> list[np.ndarray]:
    """`math.fsum` of every list of term arrays, in one call on a zero-padded (K, len * N) array."""
    rows = max(len(terms) for terms in columns)
    stacked = np.zeros((rows, len(columns) * size))
    for j, terms in enumerate(columns):
        for k, term in enumerate(terms):
            stacked[k, j * size : (j + 1) * size] = term
    sums = fsum_columns(stacked)
    return [sums[j * size : (j + 1) * size] for j in range(len(columns))]


def _within(value, low, high):
    """`response._within`: clamp into [low, high]; contradicting bounds meet halfway."""
    with np.errstate(invalid="ignore"):  # -inf + inf where the bounds are open: not taken
        middle = 0.5 * (low + high)
    return np.where(low > high, middle, py_min(py_max(value, low), high))


def _hit(p: FightParams, s: FightState, a: int, c: Contacts, response: Response) -> tuple:
    """`ReactionHit`: attacker a's hitbox on fighter 1 - a; launches it, records the hit."""
    d = 1 - a
    fighter = p.config.fighter
    hit = c.found & ~s.struck[a]
    s.struck[a] |= hit
    blocked = s.blocking[d] & (s.facing[d] == -s.facing[a])
    move = s.move[a].copy()  # the hit's move, kept: a hit on the attacker may end its move
    damage = p.attack_damage[move] * np.where(blocked, fighter.block_damage, 1.0)
    power = p.attack_knockback[move] + p.attack_growth[move] * (
        (fighter.health - s.health[d]) + damage
    )
    power = power * np.where(blocked, fighter.block_knockback, 1.0)
    launch = (s.facing[a] * power * p.attack_cos[move], -power * p.attack_sin[move])
    remaining = (1.0 - c.time_of_impact) * p.frame_time
    for axis, now in ((0, s.vx[d]), (1, s.vy[d])):
        delta = launch[axis] - now
        response.changes[axis].append(np.where(hit, delta, 0.0))
        response.shifts[axis].append(np.where(hit, delta * remaining * p.background_factor, 0.0))
    return hit, move, damage, blocked


def _push(p, s, c: Contacts, increment, velocity, on_immovable, responses) -> None:
    """`ReactionPush` on the fighters' contact (seen from fighter 0)."""
    mass = p.config.fighter.mass
    total = mass + mass
    share_one, share_two = mass / total, mass / total
    vertical, normal, found = c.vertical, c.normal, c.found
    separate = found & (c.depth > 0.0)
    responses[0].along(vertical, separate, shift=-normal * c.depth * share_one)
    responses[1].along(vertical, separate, shift=normal * c.depth * share_two)
    along = [np.where(vertical, increment[1][f], increment[0][f]) for f in (0, 1)]
    speed = [np.where(vertical, velocity[1][f], velocity[0][f]) for f in (0, 1)]
    closing = found & ((along[0] - along[1]) * normal > 0.0)
    # vertical, and the lower fighter stands on something immovable: the upper one stops falling
    lower_stands = np.where(normal > 0.0, on_immovable[1], on_immovable[0])
    stop = closing & vertical & lower_stands
    remaining = 1.0 - c.time_of_impact
    for upper, is_upper in ((0, normal > 0.0), (1, normal < 0.0)):
        mask = stop & is_upper
        inc, vel = increment[1][upper], velocity[1][upper]
        r = responses[upper]
        r.shifts[1].append(np.where(mask, remaining * (py_min(inc, 0.0) - inc), 0.0))
        r.changes[1].append(np.where(mask, py_min(vel, 0.0) - vel, 0.0))
    push = closing & ~stop
    common_increment = (mass * along[0] + mass * along[1]) / (mass + mass)
    common_velocity = (mass * speed[0] + mass * speed[1]) / (mass + mass)
    for f in (0, 1):
        responses[f].along(
            vertical,
            push,
            shift=remaining * (common_increment - along[f]),
            change=common_velocity - speed[f],
        )


def _rebound(p: FightParams, s: FightState, b: int, f: int, c: Contacts, r: Response) -> None:
    """`ReactionRebound` (no bouncy edge) of fighter f on block b; contact seen from the block."""
    normal = -c.normal  # seen from the fighter
    vertical = c.vertical
    start = np.where(vertical, p.block_y[b] + 0.0, p.block_x[b] + 0.0)
    own_size = np.where(vertical, s.height[f], p.config.fighter.width)
    block_size = np.where(vertical, p.block_h[b], p.block_w[b])
    surface = np.where(normal > 0.0, start - own_size, start + block_size)
    for axis, on_axis in ((0, ~vertical), (1, vertical)):
        above = c.found & on_axis & (normal > 0.0)  # the block is ahead along the axis
        below = c.found & on_axis & (normal < 0.0)
        r.high[axis] = np.where(above, py_min(r.high[axis], surface), r.high[axis])
        r.velocity_high[axis] = np.where(
            above, py_min(r.velocity_high[axis], 0.0), r.velocity_high[axis]
        )
        r.low[axis] = np.where(below, py_max(r.low[axis], surface), r.low[axis])
        r.velocity_low[axis] = np.where(
            below, py_max(r.velocity_low[axis], 0.0), r.velocity_low[axis]
        )
    if p.friction > 0.0:  # slow_down along the surface; the largest carry wins the tuple max
        carry = 1.0 * ((1.0 - c.time_of_impact) * p.frame_time) * p.background_factor
        for axis, along in ((0, vertical), (1, ~vertical)):
            rubs = c.found & along
            r.carry[axis] = np.where(rubs & (carry > r.carry[axis]), carry, r.carry[axis])
            r.rubbing[axis] |= rubs


def _after_frame(p: FightParams, s: FightState, contacts, grounded, hits, events: StepEvents):
    """`Fight._frame` after the engine's frame: heads, landings, counters, hits, ring-outs."""
    fighter = p.config.fighter
    c = contacts["fighters"]
    on_top = c.found & c.vertical
    s.on_head[0] |= on_top & (c.normal > 0.0)
    s.on_head[1] |= on_top & (c.normal < 0.0)
    for f in (0, 1):
        s.on_ground[f] = grounded[f]
        s.jumps_left[f] = np.where(grounded[f], fighter.air_jumps, s.jumps_left[f])
        s.hitstun[f] = np.where(s.hitstun[f] > 0, s.hitstun[f] - 1, s.hitstun[f])
        moving = s.move[f] != 0
        s.move_frame[f] += moving
        s.move[f] = np.where(moving & (s.move_frame[f] >= p.attack_total[s.move[f]]), 0, s.move[f])
    for a in (0, 1):  # hits in attacker order
        d = 1 - a
        hit, move, damage, blocked = hits[a]
        s.health[d] = np.where(hit, py_max(s.health[d] - damage, 0.0), s.health[d])
        stun = np.where(blocked, p.attack_blocked_hitstun[move], p.attack_hitstun[move])
        s.hitstun[d] = np.where(hit, stun, s.hitstun[d])
        s.move[d] = np.where(hit, 0, s.move[d])
        s.blocking[d] &= ~hit | blocked
        events.damage_dealt[a] += np.where(hit, damage, 0.0)
        events.damage_taken[d] += np.where(hit, damage, 0.0)
        events.hits_landed[a] += hit & ~blocked
        events.hits_blocked[d] += hit & blocked
    s.frame += 1
    for f in (0, 1):
        rung_out = s.y[f] > p.height
        knocked_out = s.health[f] <= 0.0
        out = rung_out | knocked_out
        events.rung_out[f] |= rung_out
        events.knocked_out[f] |= knocked_out & ~rung_out
        s.stocks[f] -= out
        respawn(p, s, f, out & (s.stocks[f] > 0))
    events.over |= (s.stocks[0] <= 0) | (s.stocks[1] <= 0)


def respawn(p: FightParams, s: FightState, f: int, mask: np.ndarray) -> None:
    """`Fight._respawn` for fighter f where `mask` holds."""
    if not mask.any():
        return
    c = p.config.fighter
    s.height[f][mask] = c.height
    s.x[f][mask] = s.spawn_x[f][mask]
    s.y[f][mask] = s.spawn_top[f][mask] - c.height
    s.vx[f][mask] = 0.0
    s.vy[f][mask] = 0.0
    s.health[f][mask] = c.health
    s.facing[f][mask] = SIDES[f]
    s.jumps_left[f][mask] = c.air_jumps
    s.on_ground[f][mask] = True
    for name in ("on_head", "jump_held", "blocking", "crouching", "hit_active", "struck"):
        getattr(s, name)[f][mask] = False
    for name in ("move", "move_frame", "hitstun"):
        getattr(s, name)[f][mask] = 0
