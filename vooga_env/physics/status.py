"""`CollisionStatus`: which edges of a sprite touched something this frame (the seed's detail)."""

from __future__ import annotations

from typing import Protocol


class Partner(Protocol):
    """What a status reads of the sprite on the other side of a contact."""

    movable: bool


class EdgeContact(Protocol):
    """What a status reads of a contact: `physics.contact.Contact` is one. Protocols rather than
    imports, so that status sits below the sprites and contacts that hold and make statuses."""

    edge: str
    other: Partner


class CollisionStatus:
    """Per-frame contact flags of one sprite, plus the contact with each partner.

    `up`/`down`/`left`/`right` say which of the sprite's own edges touched something; `on_ground`
    that its bottom edge rests on an immovable sprite (a platform). `contacts` maps each partner to
    the contact seen from this sprite, so a reaction reads its own pair's geometry rather than flags
    that another pair produced (the original engine's flags were per sprite only).
    """

    __slots__ = ("left", "right", "up", "down", "on_ground", "contacts")

    def __init__(self) -> None:
        self.contacts: dict[Partner, EdgeContact] = {}
        self.reset()

    def reset(self) -> None:
        """Clear every flag and contact; the world does this after each frame's update."""
        self.left = self.right = self.up = self.down = self.on_ground = False
        self.contacts.clear()

    @property
    def collided(self) -> bool:
        """True when any edge touched something this frame."""
        return self.left or self.right or self.up or self.down

    def record(self, contact: EdgeContact) -> None:
        """Flag the edge `contact` touched and remember the contact under its partner."""
        setattr(self, contact.edge, True)
        self.contacts[contact.other] = contact
        if contact.edge == "down" and not contact.other.movable:
            self.on_ground = True

    def __repr__(self) -> str:
        edges = [
            name for name in ("left", "right", "up", "down", "on_ground") if getattr(self, name)
        ]
        return f"CollisionStatus({', '.join(edges) or 'clear'})"
