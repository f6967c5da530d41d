"""`Fight`: two fighters on a stage, the rules of the game over the physics engine.

No gymnasium or pettingzoo here: the env (`env.py`) turns this into observations and rewards.
Each `step` takes one action per fighter (in its own mirrored frame) and runs `frame_skip` physics
frames with the actions repeated; it returns what happened as `StepEvents`.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from vooga_env.game import formulas
from vooga_env.game.actions import ATTACKS, JUMPS, WALK, Action
from vooga_env.game.config import AttackConfig, FightConfig, spawn_block
from vooga_env.game.hits import Fighter, Hit, ReactionHit, hit_kind
from vooga_env.physics import (
    CollisionKind,
    CollisionKindEnemy,
    CollisionKindFriends,
    CollisionKindNeutral,
    FightPhysicsEngine,
    MotionAction,
    PlatformBlock,
    Reaction,
    ReactionForce,
    ReactionMomentumConservation,
    ReactionPunch,
    ReactionPush,
    ReactionRebound,
    ReactionStop,
    SpriteGroupTemplate,
    World,
)

SIDES = (1.0, -1.0)  # fighter_1's left and right are mirrored


def make_reaction(name: str, friction: float = 0.0) -> list[Reaction]:
    """The reactions a config name stands for (see config.REACTIONS)."""
    return {
        "push": [ReactionPush()],
        "momentum": [ReactionMomentumConservation()],
        "stop": [ReactionStop()],
        "punch": [ReactionPunch()],
        "rebound": [ReactionRebound(friction=friction)],
        "force": [ReactionForce()],
        "none": [],
    }[name]


@dataclass
class StepEvents:
    """What happened during one env step, per fighter index."""

    hits: list[Hit] = field(default_factory=list)
    damage_dealt: list[float] = field(default_factory=lambda: [0.0, 0.0])
    damage_taken: list[float] = field(default_factory=lambda: [0.0, 0.0])
    rung_out: list[bool] = field(default_factory=lambda: [False, False])
    knocked_out: list[bool] = field(default_factory=lambda: [False, False])
    over: bool = False


def _action(field: str, value: object) -> Action:
    """`value` as an Action, or a ValueError naming `field`, the value and the range."""
    try:
        return Action(value)
    except ValueError:
        raise ValueError(
            f"{field} = {value!r} is not an action: an int in 0..{len(Action) - 1}"
        ) from None


def hitbox_box(
    fighter: Fighter, attack: AttackConfig, facing: float
) -> tuple[float, float, float, float]:
    """(x, y, width, height) of an attack's hitbox: out of the front edge, placed from the feet."""
    x = formulas.hitbox_x(fighter.left, fighter.right, facing, attack.hitbox_width)
    y = formulas.hitbox_y(fighter.bottom, fighter.config.height, attack.offset_y)
    return x, y, attack.hitbox_width, attack.hitbox_height


class Fight:
    """The game: stage, fighters, attacks, stocks; stepped by actions, reset by a seeded RNG."""

    def __init__(self, config: FightConfig) -> None:
        if not isinstance(config, FightConfig):
            raise TypeError(f"config must be a FightConfig (see load_config), got {config!r}")
        self.config = config
        arena, physics = config.arena, config.physics
        self.engine = FightPhysicsEngine(
            arena.width,
            arena.height,
            background_factor=physics.background_factor,
            out_bound_distance=physics.out_bound_distance,
            speed_factor=physics.speed_factor,
            gravity=physics.gravity,
        )
        self.blocks = [
            PlatformBlock(b.x, b.y, b.width, b.height, name=f"block_{i}")
            for i, b in enumerate(arena.blocks)
        ]
        self.fighters = [Fighter(i, config.fighter, 0.0, 0.0) for i in (0, 1)]
        self.hit_reaction = ReactionHit()
        collisions = config.collisions
        kinds: list[CollisionKind] = [
            hit_kind(self.hit_reaction),
            CollisionKindEnemy(make_reaction(collisions.enemy)),
            CollisionKindFriends(make_reaction(collisions.friends)),
            CollisionKindNeutral(make_reaction(collisions.neutral, physics.ground_friction)),
        ]
        group = SpriteGroupTemplate()
        group.add_platform_block_array(self.blocks)
        for fighter in self.fighters:
            group.add_sprite_array([fighter, fighter.hitbox])
        self.world = World(self.engine, group, kinds)
        self.stage_left, self.stage_right = arena.stage_left, arena.stage_right
        self.frame = 0
        self.steps = 0
        self.spawns = [0.0, 0.0]
        self._before_step = self.snapshot()
        # MotionActions are immutable: one per fighter and walking action, and per slide direction
        self._walks = [
            {a: MotionAction(f, WALK[a] * SIDES[f.index], 0.0) for a in WALK} for f in self.fighters
        ]
        self._slides = [
            {d: MotionAction(f, d * config.fighter.head_slide, 0.0) for d in (1.0, -1.0)}
            for f in self.fighters
        ]

    def reset(self, rng: np.random.Generator) -> None:
        """Start a new fight: full stocks and health, spawns jittered (and, with `random_sides`,
        swapped half the time) by `rng`, then the [start] damage and clock drawn from it."""
        if not isinstance(rng, np.random.Generator):
            raise TypeError(f"rng must be a numpy Generator (np.random.default_rng), got {rng!r}")
        arena = self.config.arena
        jitter = arena.spawn_jitter
        self.spawns = [
            x + (float(rng.uniform(-jitter, jitter)) if jitter > 0 else 0.0) for x in arena.spawns
        ]
        if arena.random_sides and rng.random() < 0.5:
            self.spawns.reverse()
        for fighter in self.fighters:
            fighter.stocks = self.config.stocks
            self._respawn(fighter)
        self.frame = 0
        self.steps = 0
        start = self.config.start
        if start.damage > 0:
            for fighter in self.fighters:
                fighter.health -= start.damage * rng.random()
        if start.steps > 0:
            self.steps = int(rng.random() * (start.steps + 1))

    def step(self, actions: tuple[int, int]) -> StepEvents:
        """Run one env step (frame_skip physics frames) with each fighter's action repeated.

        A step that raises (a custom collision kind's error, say) leaves the fight as it was.
        """
        events = StepEvents()
        actions = (_action("actions[0]", actions[0]), _action("actions[1]", actions[1]))
        self._before_step = self.snapshot()
        try:
            for _ in range(self.config.frame_skip):
                self._frame(actions, events)
                if events.over:
                    break
        except BaseException:
            self.undo_step()
            raise
        self.steps += 1
        return events

    def undo_step(self) -> None:
        """Go back to just before the last `step` (the env's reward failed: it did not happen)."""
        self.restore(self._before_step)

    def snapshot(self) -> tuple:
        """What a step changes: the frame and step counts, every fighter's and hitbox's state."""
        sprites = [sprite for fighter in self.fighters for sprite in (fighter, fighter.hitbox)]
        struck = [set(fighter.hitbox.struck) for fighter in self.fighters]
        attributes = [(sprite, sprite.__dict__.copy()) for sprite in sprites]
        return self.frame, self.steps, attributes, struck

    def restore(self, snapshot: tuple) -> None:
        """Go back to a `snapshot()` of this fight (its values were checked when first set)."""
        self.frame, self.steps, sprites, struck = snapshot
        for sprite, attributes in sprites:
            sprite.__dict__.update(attributes)
            sprite.status.reset()
            sprite.response.reset()
        for fighter, hits in zip(self.fighters, struck):
            fighter.hitbox.struck.clear()
            fighter.hitbox.struck.update(hits)
        self.hit_reaction.hits.clear()

    @property
    def over(self) -> bool:
        return any(fighter.stocks <= 0 for fighter in self.fighters)

    def winner(self) -> int | None:
        """The leading fighter's index (more stocks, then more health), None for a draw."""
        scores = [(fighter.stocks, fighter.health) for fighter in self.fighters]
        if scores[0] == scores[1]:
            return None
        return 0 if scores[0] > scores[1] else 1

    def _frame(self, actions: tuple[Action, Action], events: StepEvents) -> None:
        fighters = self.fighters
        motions = self._control(fighters[0], actions[0])
        motions += self._control(fighters[1], actions[1])
        for fighter in fighters:
            self._place_hitbox(fighter)
        self.hit_reaction.hits.clear()
        contacts = self.world.step(self.config.physics.frame_time, motions)
        one, two = fighters
        grounded = set()
        for contact in contacts:
            sprite, other = contact.sprite, contact.other
            if contact.axis == 1 and (
                (sprite is one and other is two) or (sprite is two and other is one)
            ):
                upper = sprite if contact.normal > 0 else other
                upper.on_head = True
            # a fighter on a block's top: the block's edge "up" or the fighter's edge "down"
            if isinstance(sprite, PlatformBlock):
                if contact.axis == 1 and contact.normal < 0.0:
                    grounded.add(other)
            elif isinstance(other, PlatformBlock) and contact.axis == 1 and contact.normal > 0.0:
                grounded.add(sprite)
        for fighter in fighters:
            fighter.on_ground = fighter in grounded
            if fighter.on_ground:
                fighter.jumps_left = fighter.config.air_jumps
            self._advance(fighter)
        for hit in sorted(self.hit_reaction.hits, key=lambda hit: hit.attacker):
            self._apply_hit(hit, events)
        self.frame += 1
        for fighter in self.fighters:
            rung_out = self.engine.is_out_down(fighter)
            knocked_out = fighter.health <= 0.0
            if rung_out or knocked_out:
                events.rung_out[fighter.index] |= rung_out
                events.knocked_out[fighter.index] |= knocked_out and not rung_out
                fighter.stocks -= 1
                if fighter.stocks > 0:
                    self._respawn(fighter)
        events.over = self.over

    def _control(self, fighter: Fighter, action: Action) -> list[MotionAction]:
        """Apply one fighter's action for this frame; the walking it asks for, as MotionActions."""
        config = fighter.config
        free = fighter.hitstun == 0 and fighter.move is None
        opponent = self.fighters[1 - fighter.index]
        if free:
            toward = (opponent.x + opponent.width / 2) - (fighter.x + fighter.width / 2)
            if toward != 0.0:
                fighter.facing = 1.0 if toward > 0.0 else -1.0
        fighter.blocking = free and action == Action.BLOCK and fighter.on_ground
        attacking = fighter.move is not None or (free and action in ATTACKS)
        self._crouch(
            fighter,
            fighter.on_ground
            and ((free and action == Action.DOWN) or (fighter.crouching and attacking)),
        )
        jumping = action in JUMPS
        motions = []
        if fighter.on_head:
            away = (fighter.x + fighter.width / 2) - (opponent.x + opponent.width / 2)
            direction = (1.0 if away > 0.0 else -1.0) if away != 0.0 else -fighter.facing
            motions.append(self._slides[fighter.index][direction])
            fighter.on_head = False
        if free:
            if jumping and not fighter.jump_held:
                if fighter.on_ground:
                    fighter.vy = -config.jump_speed
                elif fighter.jumps_left > 0:
                    fighter.jumps_left -= 1
                    fighter.vy = -config.jump_speed
            if action == Action.DOWN and not fighter.on_ground:
                fighter.vy = max(fighter.vy, config.fast_fall_speed)
            if action in ATTACKS:
                fighter.move = ATTACKS[action]
                fighter.move_frame = 0
                fighter.hitbox.struck.clear()
            if action in WALK:
                motions.append(self._walks[fighter.index][action])
        fighter.jump_held = jumping
        return motions

    def _crouch(self, fighter: Fighter, crouch: bool) -> None:
        """Crouching lowers the fighter's top edge; its feet stay where they are.

        An attack started from a crouch stays crouched until it ends (a low kick beats a high
        punch), and its hitbox sits where a standing one would: attacks are placed from the feet.
        """
        if crouch == fighter.crouching:
            return
        bottom = fighter.bottom
        fighter.crouching = crouch
        fighter.height = fighter.config.crouch_height if crouch else fighter.config.height
        fighter.y = bottom - fighter.height

    def _place_hitbox(self, fighter: Fighter) -> None:
        """Put the hitbox in front of its owner during the attack's active frames."""
        hitbox, attack = fighter.hitbox, fighter.attack
        hitbox.active = attack is not None and (
            attack.startup <= fighter.move_frame < attack.startup + attack.active
        )
        if hitbox.active:
            hitbox.x, hitbox.y, hitbox.width, hitbox.height = hitbox_box(
                fighter, attack, fighter.facing
            )

    def reach(self, attacker: Fighter) -> tuple[bool, bool]:
        """Would a punch, and a kick, started now towards the opponent touch it where it stands?"""
        defender = self.fighters[1 - attacker.index]
        toward = (defender.x + defender.width / 2) - (attacker.x + attacker.width / 2)
        facing = attacker.facing if toward == 0.0 else (1.0 if toward > 0.0 else -1.0)
        left, top = defender.x, defender.y
        right, bottom = left + defender.width, top + defender.height
        reach = []
        for attack in (attacker.config.punch, attacker.config.kick):
            x, y, width, height = hitbox_box(attacker, attack, facing)
            reach.append(formulas.reaches(left, top, right, bottom, x, y, width, height))
        return reach[0], reach[1]

    def _advance(self, fighter: Fighter) -> None:
        """Count down stun and move frames after a physics frame."""
        if fighter.hitstun > 0:
            fighter.hitstun -= 1
        attack = fighter.attack
        if attack is not None:
            fighter.move_frame += 1
            if fighter.move_frame >= attack.startup + attack.active + attack.recovery:
                fighter.move = None

    def _apply_hit(self, hit: Hit, events: StepEvents) -> None:
        defender = self.fighters[hit.defender]
        attack = getattr(self.fighters[hit.attacker].config, hit.move)
        defender.health = max(defender.health - hit.damage, 0.0)
        defender.hitstun = attack.hitstun // 3 if hit.blocked else attack.hitstun
        defender.move = None
        defender.blocking = defender.blocking and hit.blocked
        events.hits.append(hit)
        events.damage_dealt[hit.attacker] += hit.damage
        events.damage_taken[hit.defender] += hit.damage

    def _respawn(self, fighter: Fighter) -> None:
        """Back on the spawn point, standing, at full health, with no move or stun."""
        config = fighter.config
        x = self.spawns[fighter.index]
        fighter.height = config.height
        fighter.x = x
        fighter.y = spawn_block(self.config.arena, x, config.width).y - config.height
        fighter.vx = fighter.vy = 0.0
        fighter.health = config.health
        fighter.facing = SIDES[fighter.index]
        fighter.jumps_left = config.air_jumps
        fighter.on_ground = True
        fighter.on_head = False
        fighter.jump_held = False
        fighter.move = None
        fighter.move_frame = 0
        fighter.hitstun = 0
        fighter.blocking = False
        fighter.crouching = False
        fighter.hitbox.active = False
        fighter.hitbox.struck.clear()
