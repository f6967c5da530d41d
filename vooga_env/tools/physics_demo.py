"""A scripted physics scene: two fighters, a platform, and every reaction firing once.

Run with `python -m vooga_env.tools.physics_demo`; it prints each new contact and the final
positions.
"""

from __future__ import annotations

from collections.abc import Callable

from vooga_env.physics import (
    CollisionKind,
    CollisionKindCustom,
    CollisionKindEnemy,
    CollisionKindFriends,
    CollisionKindNeutral,
    FighterBody,
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
    SpriteTemplate,
    World,
)

FRAME_MS = 20.0  # the original game loop's 50 frames per second


def run_scene(
    title: str,
    fighters: list[FighterBody],
    kinds: list[CollisionKind],
    frames: int,
    inputs: Callable[[int], list[MotionAction]] = lambda frame: [],
    others: list[SpriteTemplate] = (),
    gravity: float = 0.002,
) -> list[str]:
    """Run one scene on the original 544x544 arena with a platform; return its log lines."""
    engine = FightPhysicsEngine(544, 544, gravity=gravity)
    group = SpriteGroupTemplate()
    group.add_platform_block_array([PlatformBlock(72, 400, 400, 24, name="platform")])
    group.add_fighter_sprite_array(fighters)
    if others:
        group.add_sprite_array(others)
    world = World(engine, group, kinds)
    lines = [f"== {title}"]
    touching: set[tuple[str, str]] = set()
    for frame in range(frames):
        contacts = world.step(FRAME_MS, inputs(frame))
        now = {(c.sprite.name, c.other.name) for c in contacts}
        for contact in contacts:
            pair = (contact.sprite.name, contact.other.name)
            if pair not in touching:
                kinds_fired = [
                    reaction_names(kind)
                    for kind in kinds
                    if kind.is_this_kind(contact.sprite, contact.other)
                ]
                lines.append(
                    f"  frame {frame:3d}: {pair[0]} ({contact.edge} edge) meets {pair[1]}"
                    f" -> {', '.join(kinds_fired) or 'no reaction'}"
                )
        touching = now
    for sprite in [*fighters, *others]:
        lines.append(
            f"  end: {sprite.name:<8} x={sprite.x:7.2f} y={sprite.y:7.2f} "
            f"vx={sprite.vx:+.3f} vy={sprite.vy:+.3f}"
        )
    return lines


def reaction_names(kind: CollisionKind) -> str:
    return "+".join(type(reaction).__name__.removeprefix("Reaction") for reaction in kind.reactions)


def main() -> None:
    rebound: Reaction = ReactionRebound(friction=0.001)
    neutral = CollisionKindNeutral(rebound)
    logs = []

    a = FighterBody(100, 100, 40, 60, group_id="red", name="red")
    b = FighterBody(300, 340, 40, 60, group_id="blue", name="blue")
    logs += run_scene(
        "red falls onto the platform and walks into blue (Rebound, Push)",
        [a, b],
        [CollisionKindEnemy(ReactionPush()), neutral],
        90,
        lambda frame: [MotionAction.right(a)] if frame >= 20 else [],
    )

    a = FighterBody(100, 340, 40, 60, group_id="red", name="red", vx=0.4)
    b = FighterBody(300, 340, 40, 60, group_id="red", name="red2", vx=-0.1)
    logs += run_scene(
        "two team-mates slide into each other (MomentumConservation: equal masses swap)",
        [a, b],
        [
            CollisionKindFriends(ReactionMomentumConservation()),
            CollisionKindNeutral(ReactionRebound()),
        ],
        30,
    )

    fighter = FighterBody(300, 340, 40, 60, group_id="red", name="red")
    ball = SpriteTemplate(120, 350, 16, 16, mass=50.0, vx=0.5, gravity_scale=0.0, name="ball")
    hit = CollisionKindCustom(ReactionForce(force_x1=30.0, force_y1=-60.0))
    hit.set_type(
        SpriteTemplate,
        CollisionKindCustom.Type.IS,
        CollisionKindCustom.Relation.AND,
        FighterBody,
        CollisionKindCustom.Type.SUB,
    )
    logs += run_scene(
        "a ball hits red (CollisionKindCustom -> Force)",
        [fighter],
        [hit, neutral],
        30,
        others=[ball],
    )

    a = FighterBody(120, 340, 40, 60, group_id="red", name="red")
    b = FighterBody(260, 340, 40, 60, group_id="blue", name="blue")
    logs += run_scene(
        "red dashes into a standing blue (Punch: blue is sent to the right wall)",
        [a, b],
        [CollisionKindEnemy(ReactionPunch()), neutral],
        20,
        lambda frame: [MotionAction(a, 4.0, 0.0)],
    )

    a = FighterBody(100, 340, 40, 60, group_id="red", name="red", vx=0.3)
    b = FighterBody(360, 340, 40, 60, group_id="blue", name="blue", vx=-0.3)
    logs += run_scene(
        "red and blue run into each other (Stop: 5 px apart)",
        [a, b],
        [CollisionKindEnemy(ReactionStop(distance=5.0)), CollisionKindNeutral(ReactionRebound())],
        30,
    )

    ball = FighterBody(250, 150, 20, 20, group_id="ball", name="ball")
    logs += run_scene(
        "a ball drops on a bouncy platform (Rebound with the up edge active)",
        [ball],
        [CollisionKindNeutral(ReactionRebound(up=True, distance=2.0))],
        40,
    )
    print("\n".join(logs))


if __name__ == "__main__":
    main()
