"""`CollisionKind` and its subclasses: which pairs of sprites a list of reactions applies to."""

from __future__ import annotations

import enum
from abc import ABC, abstractmethod
from collections.abc import Iterable

from vooga_env.physics.engine import PhysicsEngine
from vooga_env.physics.reactions import Reaction
from vooga_env.physics.sprites import FighterBody, SpriteTemplate


class CollisionKind(ABC):
    """A predicate over a pair of sprites with the reactions to run, in order, when it holds."""

    def __init__(self, reactions: Reaction | Iterable[Reaction] | None = None) -> None:
        self._reactions: list[Reaction] = []
        self.set_reaction([] if reactions is None else reactions)

    @abstractmethod
    def is_this_kind(self, sprite_one: SpriteTemplate, sprite_two: SpriteTemplate) -> bool:
        """True if this kind applies to the pair (in either order)."""

    def ordered(
        self, sprite_one: SpriteTemplate, sprite_two: SpriteTemplate
    ) -> tuple[SpriteTemplate, SpriteTemplate]:
        """The pair in the order the reactions expect; symmetric kinds keep it as given."""
        return sprite_one, sprite_two

    def do_this_reaction(
        self, sprite_one: SpriteTemplate, sprite_two: SpriteTemplate, engine: PhysicsEngine
    ) -> None:
        """Run every reaction of this kind on the pair, in list order."""
        first, second = self.ordered(sprite_one, sprite_two)
        for reaction in self._reactions:
            reaction.act(first, second, engine)

    @property
    def reactions(self) -> tuple[Reaction, ...]:
        return tuple(self._reactions)

    def add_reaction(self, reaction: Reaction) -> None:
        self._reactions.append(_checked_reaction(reaction))

    def remove_reaction(self, reaction: Reaction) -> None:
        try:
            self._reactions.remove(reaction)
        except ValueError:
            raise ValueError(f"reaction {reaction!r} is not in {self!r}") from None

    def set_reaction(self, reactions: Reaction | Iterable[Reaction]) -> None:
        """Replace the reactions with one reaction or a list of them."""
        if isinstance(reactions, Reaction):
            reactions = [reactions]
        if isinstance(reactions, (str, bytes)) or not isinstance(reactions, Iterable):
            raise TypeError(f"reactions must be a Reaction or a list of them, got {reactions!r}")
        self._reactions = [_checked_reaction(reaction) for reaction in reactions]

    def __repr__(self) -> str:
        return f"{type(self).__name__}({self._reactions!r})"


class CollisionKindFriends(CollisionKind):
    """Two fighters of the same team (`group_id`)."""

    def is_this_kind(self, sprite_one: SpriteTemplate, sprite_two: SpriteTemplate) -> bool:
        return (
            isinstance(sprite_one, FighterBody)
            and isinstance(sprite_two, FighterBody)
            and sprite_one.group_id == sprite_two.group_id
        )


class CollisionKindEnemy(CollisionKind):
    """Two fighters of different teams."""

    def is_this_kind(self, sprite_one: SpriteTemplate, sprite_two: SpriteTemplate) -> bool:
        return (
            isinstance(sprite_one, FighterBody)
            and isinstance(sprite_two, FighterBody)
            and sprite_one.group_id != sprite_two.group_id
        )


class CollisionKindNeutral(CollisionKind):
    """A pair in which at least one sprite is not a fighter: a block, a projectile, a power-up."""

    def is_this_kind(self, sprite_one: SpriteTemplate, sprite_two: SpriteTemplate) -> bool:
        return not (isinstance(sprite_one, FighterBody) and isinstance(sprite_two, FighterBody))


class CollisionKindCustom(CollisionKind):
    """A kind built from two classes: call `set_type` before use.

    `Type.IS` matches exactly that class, `Type.SUB` the class or a subclass of it, `Type.SUPER` the
    class or a superclass of it. `Relation.AND` needs both sprites to match, `Relation.OR` either.
    The test is symmetric in the pair's order; the reactions receive the sprite matching
    `class_one` first.
    """

    class Type(enum.Enum):
        IS = "is"
        SUPER = "super"
        SUB = "sub"

    class Relation(enum.Enum):
        AND = "and"
        OR = "or"

    def __init__(self, reactions: Reaction | Iterable[Reaction] | None = None) -> None:
        super().__init__(reactions)
        self._spec: (
            tuple[
                type,
                CollisionKindCustom.Type,
                CollisionKindCustom.Relation,
                type,
                CollisionKindCustom.Type,
            ]
            | None
        ) = None
        self._matched: dict[tuple[type, type], bool] = {}  # _matches by the pair's classes

    def set_type(
        self,
        class_one: type,
        type_one: CollisionKindCustom.Type,
        relation: CollisionKindCustom.Relation,
        class_two: type,
        type_two: CollisionKindCustom.Type,
    ) -> None:
        for name, value in (("class_one", class_one), ("class_two", class_two)):
            if not isinstance(value, type):
                raise TypeError(f"{name} must be a class, got {value!r}")
        for name, value in (("type_one", type_one), ("type_two", type_two)):
            if not isinstance(value, CollisionKindCustom.Type):
                raise TypeError(f"{name} must be a CollisionKindCustom.Type, got {value!r}")
        if not isinstance(relation, CollisionKindCustom.Relation):
            raise TypeError(f"relation must be a CollisionKindCustom.Relation, got {relation!r}")
        self._spec = (class_one, type_one, relation, class_two, type_two)
        self._matched = {}

    def is_this_kind(self, sprite_one: SpriteTemplate, sprite_two: SpriteTemplate) -> bool:
        return self._matches(sprite_one, sprite_two) or self._matches(sprite_two, sprite_one)

    def ordered(
        self, sprite_one: SpriteTemplate, sprite_two: SpriteTemplate
    ) -> tuple[SpriteTemplate, SpriteTemplate]:
        if self._matches(sprite_one, sprite_two):
            return sprite_one, sprite_two
        return sprite_two, sprite_one

    def _matches(self, first: SpriteTemplate, second: SpriteTemplate) -> bool:
        classes = (type(first), type(second))
        matched = self._matched.get(classes)
        if matched is None:
            if self._spec is None:
                raise RuntimeError("CollisionKindCustom has no type: call set_type(...) before use")
            class_one, type_one, relation, class_two, type_two = self._spec
            one = _class_matches(classes[0], class_one, type_one)
            two = _class_matches(classes[1], class_two, type_two)
            matched = (
                (one and two) if relation is CollisionKindCustom.Relation.AND else (one or two)
            )
            self._matched[classes] = matched
        return matched

    def __repr__(self) -> str:
        return f"CollisionKindCustom({self._reactions!r}, spec={self._spec!r})"


def _class_matches(actual: type, wanted: type, how: CollisionKindCustom.Type) -> bool:
    if how is CollisionKindCustom.Type.IS:
        return actual is wanted
    if how is CollisionKindCustom.Type.SUB:
        return issubclass(actual, wanted)
    return issubclass(wanted, actual)


def _checked_reaction(reaction: object) -> Reaction:
    if not isinstance(reaction, Reaction):
        raise TypeError(f"reaction must be a Reaction, got {reaction!r}")
    return reaction
