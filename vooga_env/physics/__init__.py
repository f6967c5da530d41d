"""The VOOGA physics and collision engine: sprites, an engine, teams, collision kinds, reactions.

A library of its own: it imports numpy at most, never gymnasium, pettingzoo or pygame. Units:
pixels, milliseconds, px/ms for velocities, px/ms^2 for accelerations; screen coordinates (x right,
y down); a sprite's `x, y` is its top-left corner. See docs/physics.md for the frame order.
"""

from vooga_env.physics.collision import Collision
from vooga_env.physics.contact import Contact, find_contact
from vooga_env.physics.engine import FightPhysicsEngine, PhysicsEngine
from vooga_env.physics.groups import SpriteGroupTemplate
from vooga_env.physics.kinds import (
    CollisionKind,
    CollisionKindCustom,
    CollisionKindEnemy,
    CollisionKindFriends,
    CollisionKindNeutral,
)
from vooga_env.physics.motion import MotionAction
from vooga_env.physics.reactions import (
    Reaction,
    ReactionForce,
    ReactionMomentumConservation,
    ReactionPunch,
    ReactionPush,
    ReactionRebound,
    ReactionStop,
)
from vooga_env.physics.sprites import FighterBody, PlatformBlock, SpriteTemplate
from vooga_env.physics.status import CollisionStatus
from vooga_env.physics.world import World

__all__ = [
    "Collision",
    "CollisionKind",
    "CollisionKindCustom",
    "CollisionKindEnemy",
    "CollisionKindFriends",
    "CollisionKindNeutral",
    "CollisionStatus",
    "Contact",
    "FightPhysicsEngine",
    "FighterBody",
    "MotionAction",
    "PhysicsEngine",
    "PlatformBlock",
    "Reaction",
    "ReactionForce",
    "ReactionMomentumConservation",
    "ReactionPunch",
    "ReactionPush",
    "ReactionRebound",
    "ReactionStop",
    "SpriteGroupTemplate",
    "SpriteTemplate",
    "World",
    "find_contact",
]
