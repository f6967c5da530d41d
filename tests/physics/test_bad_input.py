"""Bad input fails where it is given, with an error that names the argument and the value."""

from __future__ import annotations

import math
import re

import pytest

from vooga_env.physics import (
    Collision,
    CollisionKindCustom,
    CollisionKindEnemy,
    FighterBody,
    FightPhysicsEngine,
    MotionAction,
    PlatformBlock,
    ReactionForce,
    ReactionPunch,
    ReactionPush,
    ReactionRebound,
    ReactionStop,
    SpriteGroupTemplate,
    SpriteTemplate,
    World,
)

from .helpers import make_world

NAN, INF = math.nan, math.inf
IS = CollisionKindCustom.Type.IS
AND = CollisionKindCustom.Relation.AND


def sprite(**overrides):
    args = {"x": 10.0, "y": 20.0, "width": 30.0, "height": 40.0}
    args.update(overrides)
    x, y, w, h = (args.pop(k) for k in ("x", "y", "width", "height"))
    return SpriteTemplate(x, y, w, h, **args)


def names(argument: str, value: str) -> str:
    """A pattern for a message that names `argument` and then `value`."""
    return rf"\b{re.escape(argument)}\b.*{re.escape(value)}"


@pytest.mark.parametrize(
    ("build", "error", "argument", "value"),
    [
        (lambda: sprite(mass=0.0), ValueError, "mass", "0.0"),
        (lambda: sprite(mass=-5), ValueError, "mass", "-5"),
        (lambda: sprite(mass=NAN), ValueError, "mass", "nan"),
        (lambda: sprite(mass=-INF), ValueError, "mass", "-inf"),
        (lambda: sprite(mass="heavy"), TypeError, "mass", "'heavy'"),
        (lambda: sprite(mass=True), TypeError, "mass", "True"),
        (lambda: sprite(width=0.0), ValueError, "width", "0.0"),
        (lambda: sprite(width=-3.0), ValueError, "width", "-3.0"),
        (lambda: sprite(height=-1), ValueError, "height", "-1"),
        (lambda: sprite(height=INF), ValueError, "height", "inf"),
        (lambda: sprite(x=NAN), ValueError, "x", "nan"),
        (lambda: sprite(y=INF), ValueError, "y", "inf"),
        (lambda: sprite(x="1"), TypeError, "x", "'1'"),
        (lambda: sprite(vx=NAN), ValueError, "vx", "nan"),
        (lambda: sprite(vy=-INF), ValueError, "vy", "-inf"),
        (lambda: sprite(speed=-0.3), ValueError, "speed", "-0.3"),
        (lambda: sprite(gravity_scale=NAN), ValueError, "gravity_scale", "nan"),
        (lambda: PlatformBlock(0.0, 0.0, 0.0, 10.0), ValueError, "width", "0.0"),
        (lambda: PlatformBlock(NAN, 0.0, 10.0, 10.0), ValueError, "x", "nan"),
        (lambda: FighterBody(0, 0, 10, 10, group_id=None), TypeError, "group_id", "None"),
        (lambda: FighterBody(0, 0, 10, 10, group_id=[1]), TypeError, "group_id", "[1]"),
        (lambda: FighterBody(0, 0, 10, 10, group_id=1, mass=-1.0), ValueError, "mass", "-1.0"),
        (lambda: FighterBody(0, 0, 10, 10, group_id=1, health=NAN), ValueError, "health", "nan"),
    ],
)
def test_bad_sprite_arguments(build, error, argument, value):
    with pytest.raises(error, match=names(argument, value)):
        build()


@pytest.mark.parametrize(
    ("attribute", "value", "error", "shown"),
    [
        ("mass", 0.0, ValueError, "0.0"),
        ("mass", -2.0, ValueError, "-2.0"),
        ("width", -1.0, ValueError, "-1.0"),
        ("height", NAN, ValueError, "nan"),
        ("speed", "fast", TypeError, "'fast'"),
        ("increment_x", NAN, ValueError, "nan"),  # else update() would write it past x's check
        ("increment_y", INF, ValueError, "inf"),
    ],
)
def test_bad_sprite_assignment(attribute, value, error, shown):
    target = sprite()
    with pytest.raises(error, match=names(attribute, shown)):
        setattr(target, attribute, value)


def test_infinite_mass_is_allowed():
    assert not sprite(mass=INF).movable
    assert sprite(mass=1e-3).movable


@pytest.mark.parametrize(
    ("kwargs", "error", "argument", "value"),
    [
        ({"width": 0.0}, ValueError, "width", "0.0"),
        ({"height": -600.0}, ValueError, "height", "-600.0"),
        ({"width": NAN}, ValueError, "width", "nan"),
        ({"background_factor": 0.0}, ValueError, "background_factor", "0.0"),
        ({"background_factor": -0.8}, ValueError, "background_factor", "-0.8"),
        ({"speed_factor": -1.0}, ValueError, "speed_factor", "-1.0"),
        ({"out_bound_distance": -1.0}, ValueError, "out_bound_distance", "-1.0"),
        ({"gravity": NAN}, ValueError, "gravity", "nan"),
        ({"gravity": "down"}, TypeError, "gravity", "'down'"),
    ],
)
def test_bad_engine_arguments(kwargs, error, argument, value):
    args = {"width": 800.0, "height": 600.0}
    args.update(kwargs)
    with pytest.raises(error, match=names(argument, value)):
        FightPhysicsEngine(args.pop("width"), args.pop("height"), **args)


def test_bad_engine_assignment():
    engine = FightPhysicsEngine(800.0, 600.0)
    with pytest.raises(ValueError, match=names("background_factor", "0.0")):
        engine.background_factor = 0.0
    with pytest.raises(ValueError, match=names("gravity", "inf")):
        engine.gravity = INF


@pytest.mark.parametrize(
    ("build", "error", "argument", "value"),
    [
        (lambda: ReactionForce(force_x1=NAN), ValueError, "force_x1", "nan"),
        (lambda: ReactionForce(0.0, 0.0, 0.0, INF), ValueError, "force_y2", "inf"),
        (lambda: ReactionStop(distance=-1.0), ValueError, "distance", "-1.0"),
        (lambda: ReactionRebound(distance=NAN), ValueError, "distance", "nan"),
        (lambda: ReactionRebound(friction=-0.1), ValueError, "friction", "-0.1"),
        (lambda: ReactionRebound(up=1), TypeError, "up", "1"),
        (lambda: ReactionRebound(left="yes"), TypeError, "left", "'yes'"),
        (lambda: ReactionPunch(left=INF), ValueError, "left", "inf"),
        (lambda: ReactionPunch(down="floor"), TypeError, "down", "'floor'"),
    ],
)
def test_bad_reaction_arguments(build, error, argument, value):
    with pytest.raises(error, match=names(argument, value)):
        build()


def test_bad_kinds_and_reactions():
    group, engine = SpriteGroupTemplate(), FightPhysicsEngine(800.0, 600.0)
    with pytest.raises(TypeError, match=names("kinds", "'Push'")):
        World(engine, group, [CollisionKindEnemy(), "Push"])
    with pytest.raises(TypeError, match=names("kinds", "42")):
        Collision(group, 42, engine)
    with pytest.raises(TypeError, match=names("kinds", "'CollisionKindEnemy'")):
        Collision(group, "CollisionKindEnemy", engine)
    with pytest.raises(TypeError, match=names("reaction", "3")):
        CollisionKindEnemy([ReactionPush(), 3])
    with pytest.raises(TypeError, match=names("reactions", "'push'")):
        CollisionKindEnemy("push")
    with pytest.raises(TypeError, match=names("reaction", "None")):
        CollisionKindEnemy().add_reaction(None)
    with pytest.raises(ValueError, match="not in this Collision"):
        Collision(group, [], engine).remove_collision_kind(CollisionKindEnemy())


@pytest.mark.parametrize(
    ("args", "argument", "value"),
    [
        (("FighterBody", IS, AND, PlatformBlock, IS), "class_one", "'FighterBody'"),
        ((FighterBody, IS, AND, PlatformBlock(0, 0, 1, 1), IS), "class_two", "PlatformBlock("),
        ((FighterBody, "is", AND, PlatformBlock, IS), "type_one", "'is'"),
        ((FighterBody, IS, AND, PlatformBlock, None), "type_two", "None"),
        ((FighterBody, IS, "and", PlatformBlock, IS), "relation", "'and'"),
    ],
)
def test_bad_set_type(args, argument, value):
    with pytest.raises(TypeError, match=names(argument, value)):
        CollisionKindCustom().set_type(*args)


@pytest.mark.parametrize(
    ("elapsed", "error", "value"),
    [
        (0.0, ValueError, "0.0"),
        (-16.0, ValueError, "-16.0"),
        (NAN, ValueError, "nan"),
        (INF, ValueError, "inf"),
        ("16", TypeError, "'16'"),
        (None, TypeError, "None"),
    ],
)
def test_bad_elapsed_time(elapsed, error, value):
    mover = FighterBody(100.0, 100.0, 10.0, 10.0, group_id=1)
    world = make_world([[mover]])
    with pytest.raises(error, match=names("elapsed_time", value)):
        world.step(elapsed)
    with pytest.raises(error, match=names("elapsed_time", value)):
        world.engine.process(MotionAction.left(mover), elapsed)
    if elapsed != 0.0:  # a zero-length collision check is allowed
        with pytest.raises(error, match=names("elapsed_time", value)):
            world.collision.check_group_collision(elapsed)
    assert (mover.x, mover.y) == (100.0, 100.0)  # nothing moved


def test_bad_motion_actions():
    mover = FighterBody(100.0, 100.0, 10.0, 10.0, group_id=1)
    world = make_world([[mover]])
    with pytest.raises(ValueError, match=names("vector_x", "nan")):
        MotionAction(mover, NAN, 0.0)
    with pytest.raises(TypeError, match=names("vector_y", "'up'")):
        MotionAction(mover, 0.0, "up")
    with pytest.raises(TypeError, match=names("sprite", "'mover'")):
        MotionAction("mover", 1.0, 0.0)
    with pytest.raises(TypeError, match=names("motion_actions", "(1.0, 0.0)")):
        world.step(16.0, [(1.0, 0.0)])
    assert (mover.x, mover.y) == (100.0, 100.0)
