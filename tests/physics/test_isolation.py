"""The engine is a library of its own: it imports (numpy at most and) nothing from gymnasium,
pettingzoo, pygame or the training stack. Proved in a fresh interpreter with those blocked."""

from __future__ import annotations

import subprocess
import sys
import textwrap
from pathlib import Path

REPO = Path(__file__).resolve().parents[2]

BLOCKER = textwrap.dedent(
    """
    import sys

    BLOCKED = {"gymnasium", "gym", "pettingzoo", "pygame", "stable_baselines3", "torch"}

    class Blocker:
        def find_spec(self, name, path=None, target=None):
            if name.partition(".")[0] in BLOCKED:
                raise ImportError(f"blocked for this test: {name}")
            return None

    sys.meta_path.insert(0, Blocker())
    try:
        import pygame  # noqa: F401
    except ImportError:
        pass
    else:
        raise SystemExit("the blocker does not work")
    before = set(sys.modules)
    """
)

STEP_AND_CHECK = textwrap.dedent(
    """
    from vooga_env.physics import (
        CollisionKindEnemy, CollisionKindNeutral, FighterBody, FightPhysicsEngine, MotionAction,
        PlatformBlock, ReactionPush, ReactionRebound, SpriteGroupTemplate, World,
    )

    group = SpriteGroupTemplate()
    group.add_platform_block_array([PlatformBlock(0.0, 500.0, 800.0, 20.0)])
    a = FighterBody(100.0, 450.0, 30.0, 50.0, group_id=1)
    b = FighterBody(135.0, 450.0, 30.0, 50.0, group_id=2)
    group.add_fighter_sprite_array([a, b])
    world = World(FightPhysicsEngine(800.0, 600.0), group,
                  [CollisionKindEnemy(ReactionPush()), CollisionKindNeutral(ReactionRebound())])
    contacts = []
    for _ in range(30):
        contacts += world.step(16.0, [MotionAction.right(a)])
    assert contacts, "the scene should have contacts"
    assert b.x > 135.0, "a should have pushed b"

    loaded = {name.partition(".")[0] for name in set(sys.modules) - before}
    leaked = sorted(loaded & BLOCKED)
    assert not leaked, leaked
    stdlib = set(sys.stdlib_module_names)
    foreign = sorted(m for m in loaded - stdlib - {"vooga_env", "numpy"} if not m.startswith("_"))
    assert not foreign, f"the engine pulled in {foreign}"
    print("ok", len(contacts))
    """
)

# Import the engine's own modules without running vooga_env/__init__.py (which is the env's
# front door and may import gymnasium): a bare package object stands in for `vooga_env`.
BYPASS_PACKAGE_INIT = textwrap.dedent(
    """
    import importlib.util
    import types

    spec = importlib.util.find_spec("vooga_env")
    package = types.ModuleType("vooga_env")
    package.__path__ = list(spec.submodule_search_locations)
    sys.modules["vooga_env"] = package
    """
)


def run_python(code: str) -> subprocess.CompletedProcess:
    return subprocess.run(
        [sys.executable, "-c", code],
        cwd=REPO,
        capture_output=True,
        text=True,
        timeout=120,
        check=False,
    )


def test_engine_modules_import_and_step_without_gymnasium_pettingzoo_pygame():
    result = run_python(BLOCKER + BYPASS_PACKAGE_INIT + STEP_AND_CHECK)
    assert result.returncode == 0, result.stdout + result.stderr
    assert result.stdout.startswith("ok ")


def test_import_vooga_env_physics_without_gymnasium_pettingzoo_pygame():
    """`import vooga_env.physics` itself must work with those packages missing.

    This runs `vooga_env/__init__.py` first, so that file must not import gymnasium (or anything
    else blocked here) at import time; make its env exports lazy if it needs them.
    """
    result = run_python(BLOCKER + STEP_AND_CHECK)
    assert result.returncode == 0, result.stdout + result.stderr
    assert result.stdout.startswith("ok ")
