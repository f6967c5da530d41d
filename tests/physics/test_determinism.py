"""Behaviour 7: the same setup and the same calls give bit-identical floats, in any process."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

REPO = Path(__file__).resolve().parents[2]

# A busy scene using every reaction; run here and in fresh interpreters. Prints one line per
# frame: every sprite's x, y, vx, vy as float.hex.
SCENE = r"""
from vooga_env.physics import *

def run(frames):
    engine = FightPhysicsEngine(800.0, 600.0, gravity=0.002, background_factor=0.9)
    floor = PlatformBlock(0.0, 550.0, 800.0, 20.0)
    ledge = PlatformBlock(250.0, 420.0, 150.0, 12.0)
    fighters = [
        FighterBody(100.0 + 90.0 * i, 100.0 + 37.0 * i, 30.0 + i, 50.0, group_id=i % 3,
                    mass=150.0 + 40.0 * i, vx=0.13 * (i - 2), vy=-0.05 * i)
        for i in range(5)
    ]
    rocks = [SpriteTemplate(50.0 + 140.0 * i, 20.0, 12.0, 12.0, mass=30.0, vx=0.07 * i)
             for i in range(4)]
    group = SpriteGroupTemplate()
    group.add_platform_block_array([floor, ledge])
    group.add_fighter_sprite_array(fighters)
    group.add_sprite_array(rocks)
    custom = CollisionKindCustom(ReactionForce(3.0, -2.0, -3.0, 2.0))
    custom.set_type(SpriteTemplate, CollisionKindCustom.Type.IS, CollisionKindCustom.Relation.AND,
                    FighterBody, CollisionKindCustom.Type.SUB)
    kinds = [
        CollisionKindFriends([ReactionMomentumConservation(), ReactionStop(0.3)]),
        CollisionKindEnemy([ReactionPush(), ReactionPunch(left=20.0, right=780.0)]),
        CollisionKindNeutral(ReactionRebound(up=False, left=True, distance=1.5, friction=4e-4)),
        custom,
    ]
    world = World(engine, group, kinds)
    sprites = list(group.sprites())
    lines = []
    for frame in range(frames):
        actions = [MotionAction(f, ((frame // 30 + i) % 3) - 1.0, -1.0 if (frame + i) % 50 < 8
                                else 0.0) for i, f in enumerate(fighters)]
        world.step(16.0 if frame % 7 else 17.5, actions)
        lines.append(" ".join(v.hex() for s in sprites for v in (s.x, s.y, s.vx, s.vy)))
    return lines
"""


def run_here(frames: int) -> list[str]:
    namespace: dict = {}
    exec(SCENE, namespace)  # noqa: S102 - our own constant
    return namespace["run"](frames)


def test_same_setup_same_calls_bit_identical():
    first, second = run_here(600), run_here(600)
    assert first == second
    assert len(set(first)) > 500  # the scene really moves


def test_bit_identical_across_processes_and_hash_seeds():
    code = SCENE + "\nprint('\\n'.join(run(300)))\n"
    outputs = []
    for seed in ("0", "12345"):
        env = dict(os.environ, PYTHONHASHSEED=seed)
        result = subprocess.run(
            [sys.executable, "-c", code],
            cwd=REPO,
            env=env,
            capture_output=True,
            text=True,
            timeout=120,
            check=False,
        )
        assert result.returncode == 0, result.stderr
        outputs.append(result.stdout.splitlines())
    assert outputs[0] == outputs[1]
    assert outputs[0] == run_here(300)
