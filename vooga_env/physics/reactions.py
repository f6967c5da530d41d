"""`Reaction` and the seed's six reactions: what a contact does to the two sprites.

A reaction reads the pair's `Contact` (from `sprite.status.contacts`) and the sprites' state as it
was before any reaction ran, and writes only into each movable sprite's `response`; the update
applies the result once. Quantities along the contact axis: `increment` (px this frame, the seed's
pending displacement) and `velocity` (px/ms). A reaction that changes them at the time of impact t
shifts the sprite by (1 - t) times the change, so it meets the other sprite and then moves on.
"""

from __future__ import annotations

from abc import ABC, abstractmethod

from vooga_env.physics import validation
from vooga_env.physics.contact import Contact
from vooga_env.physics.engine import PhysicsEngine
from vooga_env.physics.formulas import common, elastic, rebound_surface, redirect_shift, shares
from vooga_env.physics.sprites import PlatformBlock, SpriteTemplate


class Reaction(ABC):
    """What a collision kind does to the two sprites of a contact."""

    @abstractmethod
    def act(
        self, sprite_one: SpriteTemplate, sprite_two: SpriteTemplate, engine: PhysicsEngine
    ) -> None:
        """Record this reaction's result in the sprites' responses."""

    def __repr__(self) -> str:
        fields = ", ".join(f"{key}={value!r}" for key, value in vars(self).items())
        return f"{type(self).__name__}({fields})"


class ReactionForce(Reaction):
    """Each sprite's velocity changes by the other's force over its own mass (an impulse).

    Sprite one gets (force_x2 / mass_one, force_y2 / mass_one) px/ms, sprite two
    (force_x1 / mass_two, force_y1 / mass_two), whatever side they touch on.
    """

    def __init__(
        self,
        force_x1: float = 0.0,
        force_y1: float = 0.0,
        force_x2: float = 0.0,
        force_y2: float = 0.0,
    ) -> None:
        self.force_x1 = validation.finite("force_x1", force_x1)
        self.force_y1 = validation.finite("force_y1", force_y1)
        self.force_x2 = validation.finite("force_x2", force_x2)
        self.force_y2 = validation.finite("force_y2", force_y2)

    def act(
        self, sprite_one: SpriteTemplate, sprite_two: SpriteTemplate, engine: PhysicsEngine
    ) -> None:
        contact = contact_between(sprite_one, sprite_two)
        for sprite, forces in (
            (sprite_one, (self.force_x2, self.force_y2)),
            (sprite_two, (self.force_x1, self.force_y1)),
        ):
            if sprite.movable:
                for axis, force in enumerate(forces):
                    push_velocity(sprite, contact, axis, force / sprite.mass, engine)


class ReactionMomentumConservation(Reaction):
    """A perfectly elastic collision along the contact axis: momentum and kinetic energy conserved.

    v1' = (m1 - m2) / (m1 + m2) * v1 + 2 * m2 / (m1 + m2) * v2, and symmetrically; equal masses
    swap velocities, an immovable partner reflects the sprite. Applied to the increment and the
    velocity alike (the formula is linear), only while the sprites approach each other.
    """

    def act(
        self, sprite_one: SpriteTemplate, sprite_two: SpriteTemplate, engine: PhysicsEngine
    ) -> None:
        contact = contact_between(sprite_one, sprite_two)
        separate(sprite_one, sprite_two, contact)
        if not closing(sprite_one, sprite_two, contact):
            return
        axis = contact.axis
        increments = elastic(
            sprite_one.mass,
            sprite_two.mass,
            increment(sprite_one, axis),
            increment(sprite_two, axis),
        )
        velocities = elastic(
            sprite_one.mass, sprite_two.mass, velocity(sprite_one, axis), velocity(sprite_two, axis)
        )
        redirect(sprite_one, contact, increments[0], velocities[0])
        redirect(sprite_two, contact, increments[1], velocities[1])


class ReactionPunch(Reaction):
    """The struck sprite is sent to the punch bound on the far side, its velocity there zeroed.

    The puncher is the sprite closing faster along the contact axis; the other is struck and lands
    against the bound beyond it (both are struck when they close equally fast). Bounds default to
    the engine's arena.
    """

    def __init__(
        self,
        left: float | None = None,
        right: float | None = None,
        up: float | None = None,
        down: float | None = None,
    ) -> None:
        self.left = None if left is None else validation.finite("left", left)
        self.right = None if right is None else validation.finite("right", right)
        self.up = None if up is None else validation.finite("up", up)
        self.down = None if down is None else validation.finite("down", down)

    def act(
        self, sprite_one: SpriteTemplate, sprite_two: SpriteTemplate, engine: PhysicsEngine
    ) -> None:
        contact = contact_between(sprite_one, sprite_two)
        axis, normal = contact.axis, contact.normal
        closing_one = increment(sprite_one, axis) * normal
        closing_two = -increment(sprite_two, axis) * normal
        if max(closing_one, closing_two) <= 0.0:
            return
        struck = []
        if closing_one >= closing_two:
            struck.append((sprite_two, normal))
        if closing_two >= closing_one:
            struck.append((sprite_one, -normal))
        for sprite, direction in struck:
            if not sprite.movable:
                continue
            if axis == 0:
                low = engine.bound_left if self.left is None else self.left
                high = engine.bound_right if self.right is None else self.right
            else:
                low = engine.bound_up if self.up is None else self.up
                high = engine.bound_down if self.down is None else self.down
            target = high - size(sprite, axis) if direction > 0.0 else low
            sprite.response.bound_position(axis, target, target)
            sprite.response.bound_velocity(axis, 0.0, 0.0)


class ReactionPush(Reaction):
    """The pusher and the pushed go on together at the common velocity (m1 v1 + m2 v2) / (m1 + m2).

    Only while they approach each other along the contact axis. A pushed sprite resting on the
    ground is not pushed into it: the sprite on top just stops moving down.
    """

    def act(
        self, sprite_one: SpriteTemplate, sprite_two: SpriteTemplate, engine: PhysicsEngine
    ) -> None:
        contact = contact_between(sprite_one, sprite_two)
        separate(sprite_one, sprite_two, contact)
        if not closing(sprite_one, sprite_two, contact):
            return
        axis = contact.axis
        if axis == 1:
            lower, upper = (
                (sprite_two, sprite_one) if contact.normal > 0.0 else (sprite_one, sprite_two)
            )
            if lower.status.on_ground:
                redirect(
                    upper, contact, min(increment(upper, 1), 0.0), min(velocity(upper, 1), 0.0)
                )
                return
        common_increment = common(
            sprite_one.mass,
            increment(sprite_one, axis),
            sprite_two.mass,
            increment(sprite_two, axis),
        )
        common_velocity = common(
            sprite_one.mass, velocity(sprite_one, axis), sprite_two.mass, velocity(sprite_two, axis)
        )
        redirect(sprite_one, contact, common_increment, common_velocity)
        redirect(sprite_two, contact, common_increment, common_velocity)


class ReactionRebound(Reaction):
    """A sprite against a `PlatformBlock`; other pairs are left alone.

    `up`, `down`, `left`, `right` name the block's edges that rebound. On an edge that does not,
    the sprite stops at the surface: no penetration, velocity into the block zeroed (a fighter lands
    and rests without jitter). On one that does, it ends `distance` px off the surface with its
    velocity into the block reversed. `friction` (px/ms^2) slows sliding along the surface.
    """

    def __init__(
        self,
        up: bool = False,
        down: bool = False,
        left: bool = False,
        right: bool = False,
        distance: float = 1.0,
        friction: float = 0.0,
    ) -> None:
        for name, flag in (("up", up), ("down", down), ("left", left), ("right", right)):
            if not isinstance(flag, bool):
                raise TypeError(f"{name} must be a bool, got {flag!r}")
        self.up, self.down, self.left, self.right = up, down, left, right
        self.distance = validation.non_negative("distance", distance)
        self.friction = validation.non_negative("friction", friction)

    def act(
        self, sprite_one: SpriteTemplate, sprite_two: SpriteTemplate, engine: PhysicsEngine
    ) -> None:
        if isinstance(sprite_one, PlatformBlock) == isinstance(sprite_two, PlatformBlock):
            return
        block, sprite = (
            (sprite_one, sprite_two)
            if isinstance(sprite_one, PlatformBlock)
            else (sprite_two, sprite_one)
        )
        if not sprite.movable:
            return
        contact = contact_between(sprite, block)
        axis, normal = contact.axis, contact.normal
        block_edge = _BLOCK_EDGES[(axis, normal)]
        block_start = coordinate(block, axis) + increment(block, axis)
        surface = rebound_surface(block_start, size(block, axis), size(sprite, axis), normal)
        block_velocity = velocity(block, axis)
        if getattr(self, block_edge):
            target = surface - normal * self.distance
            sprite.response.bound_position(axis, target, target)
            relative = velocity(sprite, axis) - block_velocity
            bounced = (
                block_velocity - relative if relative * normal > 0.0 else velocity(sprite, axis)
            )
            sprite.response.bound_velocity(axis, bounced, bounced)
        elif normal > 0.0:
            sprite.response.bound_position(axis, high=surface)
            sprite.response.bound_velocity(axis, high=block_velocity)
        else:
            sprite.response.bound_position(axis, low=surface)
            sprite.response.bound_velocity(axis, low=block_velocity)
        if self.friction > 0.0:
            along = 1 - axis
            rest = (1.0 - contact.time_of_impact) * contact.elapsed_time
            sprite.response.slow_down(
                along,
                self.friction * contact.elapsed_time,
                velocity(block, along),
                engine.displacement(1.0, rest),
            )


class ReactionStop(Reaction):
    """Both sprites stop along the contact axis with exactly `distance` px between them.

    The gap is opened from where they met, each moving by a share inversely proportional to its mass
    (an immovable sprite does not move).
    """

    def __init__(self, distance: float = 0.2) -> None:
        self.distance = validation.non_negative("distance", distance)

    def act(
        self, sprite_one: SpriteTemplate, sprite_two: SpriteTemplate, engine: PhysicsEngine
    ) -> None:
        contact = contact_between(sprite_one, sprite_two)
        axis, normal, when = contact.axis, contact.normal, contact.time_of_impact
        start_one = coordinate(sprite_one, axis) + when * increment(sprite_one, axis)
        start_two = coordinate(sprite_two, axis) + when * increment(sprite_two, axis)
        if normal > 0.0:
            gap = start_two - (start_one + size(sprite_one, axis))
        else:
            gap = start_one - (start_two + size(sprite_two, axis))
        extra = self.distance - gap
        share_one, share_two = shares(sprite_one.mass, sprite_two.mass)
        for sprite, start, direction, share in (
            (sprite_one, start_one, -normal, share_one),
            (sprite_two, start_two, normal, share_two),
        ):
            if sprite.movable:
                target = start + direction * extra * share
                sprite.response.bound_position(axis, target, target)
                sprite.response.bound_velocity(axis, 0.0, 0.0)


# The block edge a sprite touches, from the sprite's contact axis and normal.
_BLOCK_EDGES = {(1, 1.0): "up", (1, -1.0): "down", (0, 1.0): "left", (0, -1.0): "right"}


def contact_between(sprite_one: SpriteTemplate, sprite_two: SpriteTemplate) -> Contact:
    """The contact of `sprite_one` with `sprite_two` this frame, seen from `sprite_one`."""
    try:
        return sprite_one.status.contacts[sprite_two]
    except KeyError:
        raise LookupError(
            f"{sprite_one!r} has no contact with {sprite_two!r} this frame; reactions run "
            "from Collision.check_group_collision()"
        ) from None


def coordinate(sprite: SpriteTemplate, axis: int) -> float:
    return sprite.x if axis == 0 else sprite.y


def size(sprite: SpriteTemplate, axis: int) -> float:
    return sprite.width if axis == 0 else sprite.height


def increment(sprite: SpriteTemplate, axis: int) -> float:
    return sprite.increment_x if axis == 0 else sprite.increment_y


def velocity(sprite: SpriteTemplate, axis: int) -> float:
    return sprite.vx if axis == 0 else sprite.vy


def closing(sprite_one: SpriteTemplate, sprite_two: SpriteTemplate, contact: Contact) -> bool:
    """True if the sprites move towards each other along the contact axis this frame."""
    axis = contact.axis
    return (increment(sprite_one, axis) - increment(sprite_two, axis)) * contact.normal > 0.0


def redirect(
    sprite: SpriteTemplate, contact: Contact, increment_after: float, velocity_after: float
) -> None:
    """From the time of impact on, the sprite moves as `increment_after`, keeps `velocity_after`."""
    if not sprite.movable:
        return
    axis = contact.axis
    sprite.response.shift(
        axis, redirect_shift(contact.time_of_impact, increment_after, increment(sprite, axis))
    )
    sprite.response.change_velocity(axis, velocity_after - velocity(sprite, axis))


def push_velocity(
    sprite: SpriteTemplate, contact: Contact, axis: int, delta: float, engine: PhysicsEngine
) -> None:
    """Change the sprite's velocity by `delta` px/ms at the time of impact."""
    sprite.response.change_velocity(axis, delta)
    remaining = (1.0 - contact.time_of_impact) * contact.elapsed_time
    sprite.response.shift(axis, engine.displacement(delta, remaining))


def separate(sprite_one: SpriteTemplate, sprite_two: SpriteTemplate, contact: Contact) -> None:
    """Push apart sprites that already overlapped when the frame began, by their overlap depth."""
    if contact.depth <= 0.0:
        return
    share_one, share_two = shares(sprite_one.mass, sprite_two.mass)
    if sprite_one.movable:
        sprite_one.response.shift(contact.axis, -contact.normal * contact.depth * share_one)
    if sprite_two.movable:
        sprite_two.response.shift(contact.axis, contact.normal * contact.depth * share_two)
