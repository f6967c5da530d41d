"""Attack hitboxes and the reaction that turns a hitbox touching an enemy into a hit."""

from __future__ import annotations

import math
from dataclasses import dataclass

from vooga_env.game import formulas
from vooga_env.game.config import AttackConfig, FighterConfig
from vooga_env.physics import (
    CollisionKindCustom,
    FighterBody,
    PhysicsEngine,
    Reaction,
    SpriteTemplate,
)
from vooga_env.physics.reactions import contact_between, push_velocity


class Fighter(FighterBody):
    """A FighterBody with the fight's state: facing, move, stun, jumps, stocks (frames, px/ms)."""

    def __init__(self, index: int, config: FighterConfig, x: float, y: float) -> None:
        super().__init__(
            x,
            y,
            config.width,
            config.height,
            group_id=index,
            mass=config.mass,
            speed=config.speed,
            health=config.health,
            name=f"fighter_{index}",
        )
        self.index = index
        self.config = config
        self.facing = 1.0 if index == 0 else -1.0
        self.stocks = 0
        self.jumps_left = config.air_jumps
        self.on_ground = False
        self.on_head = False  # resting on the opponent: slides off next frame
        self.jump_held = False
        self.move: str | None = None
        self.move_frame = 0
        self.hitstun = 0
        self.blocking = False
        self.crouching = False
        self.hitbox = Hitbox(self)

    @property
    def damage_taken(self) -> float:
        """Damage taken this stock; knockback grows with it."""
        return self.config.health - self.health

    @property
    def attack(self) -> AttackConfig | None:
        return None if self.move is None else getattr(self.config, self.move)


class Hitbox(SpriteTemplate):
    """The striking part of an attack: active only in the attack's active frames, hits once each.

    Immovable and weightless, placed by the fight in front of its owner every frame; it lives in
    the owner's team, so it never touches its owner.
    """

    def __init__(self, owner: Fighter) -> None:
        super().__init__(
            0.0, 0.0, 1.0, 1.0, mass=math.inf, gravity_scale=0.0, name=f"{owner.name}.hitbox"
        )
        self.owner = owner
        self.active = False
        self.struck: set[Fighter] = set()


@dataclass(frozen=True)
class Hit:
    """One hit landed: who struck whom with what, how hard, and whether it was blocked."""

    attacker: int
    defender: int
    move: str
    damage: float
    blocked: bool


class ReactionHit(Reaction):
    """A hitbox touching an enemy fighter: damage and a knockback launch, once per attack.

    The hit is recorded in `hits` for the fight to apply (health, stun) after the frame, so no
    reaction reads state another changed. Knockback (px/ms) = base + growth * (damage taken so far
    + this hit's damage), at the attack's angle, in the attacker's facing direction; a block facing
    the attacker cuts damage and knockback by the fighter's `block_damage` and `block_knockback`.
    """

    def __init__(self) -> None:
        self.hits: list[Hit] = []

    def act(
        self, sprite_one: SpriteTemplate, sprite_two: SpriteTemplate, engine: PhysicsEngine
    ) -> None:
        hitbox, defender = sprite_one, sprite_two
        if not isinstance(hitbox, Hitbox) or not isinstance(defender, Fighter):
            return
        attacker = hitbox.owner
        attack = attacker.attack
        if defender in hitbox.struck or defender.group_id == attacker.group_id or attack is None:
            return
        hitbox.struck.add(defender)
        blocked = defender.blocking and defender.facing == -attacker.facing
        config = defender.config
        damage = formulas.hit_damage(attack.damage, blocked, config.block_damage)
        power = formulas.knockback(
            attack.knockback,
            attack.knockback_growth,
            defender.damage_taken,
            damage,
            blocked,
            config.block_knockback,
        )
        angle = math.radians(attack.angle)
        contact = contact_between(defender, hitbox)
        launch = (attacker.facing * power * math.cos(angle), -power * math.sin(angle))
        for axis, (speed, now) in enumerate(zip(launch, (defender.vx, defender.vy))):
            push_velocity(defender, contact, axis, speed - now, engine)
        self.hits.append(Hit(attacker.index, defender.index, attacker.move, damage, blocked))


def hit_kind(reaction: ReactionHit) -> CollisionKindCustom:
    """The collision kind 'a hitbox touches a fighter', running `reaction`."""
    kind = CollisionKindCustom(reaction)
    kind.set_type(
        Hitbox,
        CollisionKindCustom.Type.IS,
        CollisionKindCustom.Relation.AND,
        Fighter,
        CollisionKindCustom.Type.SUB,
    )
    return kind
