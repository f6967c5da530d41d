"""`Collision`: finds this frame's contacts between teams and runs the matching kinds' reactions."""

from __future__ import annotations

import math
from collections.abc import Iterable

from vooga_env.physics import validation
from vooga_env.physics.contact import Contact, find_contact
from vooga_env.physics.engine import PhysicsEngine
from vooga_env.physics.formulas import swept_interval
from vooga_env.physics.groups import SpriteGroupTemplate
from vooga_env.physics.kinds import CollisionKind
from vooga_env.physics.sprites import SpriteTemplate


class Collision:
    """The seed's collision manager: a group of teams, a list of kinds, an engine.

    `check_group_collision` works in two passes so that no result depends on the order of teams or
    sprites: first every contact is found and recorded on both sprites' statuses, then each kind
    that matches a contacting pair runs its reactions once, reading state no reaction has changed.
    """

    def __init__(
        self,
        group: SpriteGroupTemplate,
        kinds: CollisionKind | Iterable[CollisionKind],
        engine: PhysicsEngine,
    ) -> None:
        self.collision_group = group
        if not isinstance(engine, PhysicsEngine):
            raise TypeError(f"engine must be a PhysicsEngine, got {engine!r}")
        self.engine = engine
        self._kinds: list[CollisionKind] = []
        self.add_collision_kind(kinds)

    @property
    def collision_group(self) -> SpriteGroupTemplate:
        return self._group

    @collision_group.setter
    def collision_group(self, group: SpriteGroupTemplate) -> None:
        if not isinstance(group, SpriteGroupTemplate):
            raise TypeError(f"group must be a SpriteGroupTemplate, got {group!r}")
        self._group = group

    @property
    def kinds(self) -> tuple[CollisionKind, ...]:
        return tuple(self._kinds)

    def add_collision_kind(self, kinds: CollisionKind | Iterable[CollisionKind]) -> None:
        """Append one kind or a list of kinds; their order is the order reactions run in."""
        if isinstance(kinds, CollisionKind):
            kinds = [kinds]
        if isinstance(kinds, (str, bytes)) or not isinstance(kinds, Iterable):
            raise TypeError(f"kinds must be a CollisionKind or a list of them, got {kinds!r}")
        kinds = list(kinds)
        for kind in kinds:
            if not isinstance(kind, CollisionKind):
                raise TypeError(f"kinds must hold CollisionKind objects, got {kind!r}")
        self._kinds.extend(kinds)

    def remove_collision_kind(self, kind: CollisionKind) -> None:
        try:
            self._kinds.remove(kind)
        except ValueError:
            raise ValueError(f"collision kind {kind!r} is not in this Collision") from None

    def check_group_collision(self, elapsed_time: float = 0.0) -> list[Contact]:
        """Find, flag and react to every contact of this frame's pending increments.

        `elapsed_time` (ms) is the frame's length, which reactions that change velocities need to
        know how far the change carries a sprite. Returns the contacts, each seen from the sprite of
        the lower team index, in team order.
        """
        elapsed_time = validation.non_negative("elapsed_time", elapsed_time)
        contacts = []
        for one, two in self.candidate_pairs():
            contact = find_contact(one, two, elapsed_time)
            if contact is not None:
                one.status.record(contact)
                two.status.record(contact.flipped())
                contacts.append(contact)
        for contact in contacts:
            one, two = contact.sprite, contact.other
            for kind in self._kinds:
                if kind.is_this_kind(one, two):
                    kind.do_this_reaction(one, two, self.engine)
        return contacts

    def candidate_pairs(self) -> list[tuple[SpriteTemplate, SpriteTemplate]]:
        """Pairs of active sprites of different teams whose swept boxes overlap along x.

        Sort and sweep: sprites sorted by the left edge of the box they sweep this frame, each
        compared only with those whose swept box has not ended yet. Pairs come out in team order.
        """
        # Boxes are (low, order, high, team, movable, sprite): `order` (the sprite's place in team
        # order) is unique, so plain tuple comparison sorts by (low, order) and never reaches the
        # sprite; and as teams are listed in order, comparing orders compares (team, order).
        boxes = []
        order = 0
        for team, members in enumerate(self._group._teams):
            for sprite in members:
                if sprite.active:
                    low, high = swept_interval(
                        sprite.x, sprite.x + sprite.width, sprite.increment_x
                    )
                    boxes.append(
                        (
                            low,
                            order,
                            high,
                            team,
                            sprite.mass != math.inf,
                            sprite,
                        )
                    )
                order += 1
        boxes.sort()
        open_boxes: list[tuple[float, int, float, int, bool, SpriteTemplate]] = []
        pairs = []
        for box in boxes:
            low, _, _, team, movable, _ = box
            if open_boxes:
                open_boxes = [other for other in open_boxes if other[2] >= low]
                for other in open_boxes:
                    if other[3] == team or not (movable or other[4]):
                        continue
                    pairs.append(
                        (other[1], box[1], other[5], box[5])
                        if other[1] < box[1]
                        else (box[1], other[1], box[5], other[5])
                    )
            open_boxes.append(box)
        pairs.sort()
        return [(first, second) for _, _, first, second in pairs]
