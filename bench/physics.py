"""Benchmark of the physics engine: frame steps, the collision check and the broad phase.

For 10, 100 and 1000 sprites (random boxes spread over an arena 50 px wide per sprite, a tenth of
them platform blocks, the rest fighters in four teams), it times `World.step` and
`Collision.check_group_collision`, and counts the candidate pairs the sort-and-sweep broad phase
(`Collision.candidate_pairs()`) hands to the narrow phase against all n * (n - 1) / 2 pairs.

    python -m bench.physics                 # the full run (a few seconds)
    python -m bench.physics --quick         # a few frames per size, for CI
    python -m bench.physics --json out.json # also write the rows as JSON
"""

from __future__ import annotations

import argparse
import json
import platform
import random
import sys
import time
from collections.abc import Sequence
from dataclasses import asdict, dataclass
from pathlib import Path

from vooga_env.physics import (
    CollisionKindEnemy,
    CollisionKindNeutral,
    FighterBody,
    FightPhysicsEngine,
    PlatformBlock,
    ReactionMomentumConservation,
    ReactionRebound,
    SpriteGroupTemplate,
    World,
)

SIZES = (10, 100, 1000)
TEAMS = 4
FRAME_MS = 16.0
ARENA_HEIGHT = 600.0  # px
PX_PER_SPRITE = 50.0  # arena width per sprite, so density is the same at every size


@dataclass(frozen=True)
class Row:
    """One size's results. Rates are per second of wall time."""

    n: int
    steps: int
    steps_per_s: float
    checks_per_s: float
    candidate_pairs: int
    all_pairs: int
    ratio: float
    contacts_per_step: float


def build_world(n: int, seed: int) -> World:
    """`n` random sprites: n // 10 (at least 1) platform blocks in one team, fighters in TEAMS."""
    rng = random.Random(seed)
    width = PX_PER_SPRITE * n
    group = SpriteGroupTemplate()
    blocks = [
        PlatformBlock(
            rng.uniform(0.0, width - 100.0),
            rng.uniform(0.0, ARENA_HEIGHT - 40.0),
            rng.uniform(20.0, 100.0),
            rng.uniform(5.0, 20.0),
        )
        for _ in range(max(1, n // 10))
    ]
    group.add_platform_block_array(blocks)
    fighters = [
        FighterBody(
            rng.uniform(0.0, width - 40.0),
            rng.uniform(0.0, ARENA_HEIGHT - 40.0),
            rng.uniform(10.0, 40.0),
            rng.uniform(10.0, 40.0),
            group_id=index % TEAMS,
            mass=rng.uniform(100.0, 300.0),
            vx=rng.uniform(-0.2, 0.2),
            vy=rng.uniform(-0.05, 0.05),
        )
        for index in range(n - len(blocks))
    ]
    for team in range(TEAMS):
        group.add_sprite_array([f for f in fighters if f.group_id == team])
    engine = FightPhysicsEngine(width, ARENA_HEIGHT, gravity=0.0)
    kinds = [
        CollisionKindEnemy(ReactionMomentumConservation()),
        CollisionKindNeutral(ReactionRebound()),
    ]
    return World(engine, group, kinds)


def measure(n: int, steps: int, checks: int, seed: int) -> Row:
    world = build_world(n, seed)
    sprites = list(world.group.sprites())

    contacts = 0
    start = time.perf_counter()
    for _ in range(steps):
        contacts += len(world.step(FRAME_MS))
    step_time = time.perf_counter() - start

    for sprite in sprites:  # this frame's pending increments, as a step makes them
        world.engine.integrate(sprite, FRAME_MS)
    candidates = len(world.collision.candidate_pairs())
    check_time = 0.0
    for _ in range(checks):
        start = time.perf_counter()
        world.collision.check_group_collision(FRAME_MS)
        check_time += time.perf_counter() - start
        for sprite in sprites:  # forget the check's results, keep the increments
            sprite.status.reset()
            sprite.response.reset()

    all_pairs = n * (n - 1) // 2
    return Row(
        n=n,
        steps=steps,
        steps_per_s=steps / step_time if step_time > 0 else float("inf"),
        checks_per_s=checks / check_time if check_time > 0 else float("inf"),
        candidate_pairs=candidates,
        all_pairs=all_pairs,
        ratio=candidates / all_pairs if all_pairs else 0.0,
        contacts_per_step=contacts / steps if steps else 0.0,
    )


def format_table(rows: Sequence[Row]) -> str:
    header = (
        f"{'n':>6} {'steps/s':>10} {'checks/s':>10} {'candidate pairs':>16} "
        f"{'all pairs':>10} {'ratio':>8} {'contacts/step':>14}"
    )
    lines = [header, "-" * len(header)]
    for row in rows:
        lines.append(
            f"{row.n:>6} {row.steps_per_s:>10.1f} {row.checks_per_s:>10.1f} "
            f"{row.candidate_pairs:>16} {row.all_pairs:>10} {row.ratio:>8.4f} "
            f"{row.contacts_per_step:>14.2f}"
        )
    return "\n".join(lines)


def parse_args(argv: Sequence[str] | None) -> argparse.Namespace:
    parser = argparse.ArgumentParser(
        prog="python -m bench.physics",
        description=__doc__,
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    parser.add_argument("--quick", action="store_true", help="a few frames per size (for CI)")
    parser.add_argument("--json", type=Path, metavar="PATH", help="also write the rows as JSON")
    parser.add_argument(
        "--sizes",
        type=int,
        nargs="+",
        default=list(SIZES),
        metavar="N",
        help=f"sprite counts (default: {' '.join(map(str, SIZES))})",
    )
    parser.add_argument("--seed", type=int, default=0, help="scene seed (default: 0)")
    args = parser.parse_args(argv)
    if any(n < 2 for n in args.sizes):
        parser.error(f"--sizes must be at least 2, got {args.sizes}")
    return args


def main(argv: Sequence[str] | None = None) -> int:
    args = parse_args(argv)
    rows = []
    for n in args.sizes:
        # enough frames for a stable rate: fewer for large scenes, a handful in quick mode
        steps = 3 if args.quick else max(50, 100_000 // n)
        checks = 3 if args.quick else max(50, 100_000 // n)
        rows.append(measure(n, steps, checks, args.seed))
    print(format_table(rows))
    if args.json is not None:
        report = {
            "benchmark": "physics",
            "quick": args.quick,
            "seed": args.seed,
            "frame_ms": FRAME_MS,
            "python": platform.python_version(),
            "rows": [asdict(row) for row in rows],
        }
        args.json.write_text(json.dumps(report, indent=2) + "\n")
        print(f"wrote {args.json}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
