"""`FightState`: N fights as a struct of arrays; `StepEvents`: what one batched step did.

Fighter fields are (2, N): row f is fighter f of every fight (contiguous, so a fighter's column
of fights is one array). Fight fields are (N,). Units as in the single env: px, px/ms, frames.
Move codes: 0 none, 1 punch, 2 kick (`layout.MOVES`). The fields of one dtype live in one block
(`floats`, `ints`, `flags`, `counters`, `values`), each field a view of it, so that the compiled
kernel takes five arrays, not thirty.
"""

from __future__ import annotations

import numpy as np

from vooga_env.kernel.rng import PCG64Streams

FIGHTER_FLOATS = (
    "x",  # top-left corner (px)
    "y",
    "vx",  # px/ms
    "vy",
    "height",  # px, lower while crouching
    "health",
    "facing",  # +1.0 right, -1.0 left (world frame)
    "hit_x",  # the attack hitbox's box (px), meaningful while hit_active
    "hit_y",
    "hit_w",
    "hit_h",
    "spawn_x",  # this episode's spawn (jitter included) and the top of the block under it
    "spawn_top",
)
FIGHTER_INTS = ("stocks", "jumps_left", "move", "move_frame", "hitstun")
FIGHTER_FLAGS = (
    "on_ground",
    "on_head",  # resting on the opponent: slides off next frame
    "jump_held",
    "blocking",
    "crouching",
    "hit_active",
    "struck",  # this attack has hit the opponent already
)
FIGHT_COUNTERS = ("frame", "steps")
FIGHT_FLOATS = ("potential",)  # the reward's edge potential after the last step or reset
BLOCKS = {"floats": FIGHTER_FLOATS, "ints": FIGHTER_INTS, "flags": FIGHTER_FLAGS}


class _Field:
    """A named view of one row of a block: `state.x` is `state.floats[0]`."""

    def __init__(self, block: str, row: int) -> None:
        self.block, self.row = block, row

    def __get__(self, obj: object, owner: type | None = None) -> np.ndarray:
        return getattr(obj, self.block)[self.row]

    def __set__(self, obj: object, value: np.ndarray) -> None:
        getattr(obj, self.block)[self.row] = value


class FightState:
    """The whole mutable state of N fights (see the module docstring for shapes)."""

    def __init__(self, size: int) -> None:
        self.floats = np.zeros((len(FIGHTER_FLOATS), 2, size))
        self.ints = np.zeros((len(FIGHTER_INTS), 2, size), dtype=np.int64)
        self.flags = np.zeros((len(FIGHTER_FLAGS), 2, size), dtype=bool)
        self.counters = np.zeros((len(FIGHT_COUNTERS), size), dtype=np.int64)
        self.values = np.zeros((len(FIGHT_FLOATS), size))
        self.rng = PCG64Streams(size)
        self.hit_w[:] = self.hit_h[:] = 1.0

    @property
    def size(self) -> int:
        return self.counters.shape[1]

    def blocks(self) -> dict[str, np.ndarray]:
        return {
            "floats": self.floats,
            "ints": self.ints,
            "flags": self.flags,
            "counters": self.counters,
            "values": self.values,
        }

    def arrays(self) -> dict[str, np.ndarray]:
        """Every field by name, as views (the RNG's arrays not included)."""
        names = [*FIGHTER_FLOATS, *FIGHTER_INTS, *FIGHTER_FLAGS, *FIGHT_COUNTERS, *FIGHT_FLOATS]
        return {name: getattr(self, name) for name in names}

    @property
    def nbytes(self) -> int:
        """Bytes held by the state's arrays, the RNG streams included."""
        return sum(block.nbytes for block in self.blocks().values()) + self.rng.nbytes


for _block, _names in BLOCKS.items():
    for _row, _name in enumerate(_names):
        setattr(FightState, _name, _Field(_block, _row))
for _row, _name in enumerate(FIGHT_COUNTERS):
    setattr(FightState, _name, _Field("counters", _row))
for _row, _name in enumerate(FIGHT_FLOATS):
    setattr(FightState, _name, _Field("values", _row))


class StepEvents:
    """One batched step's events, per fighter (2, N) or per fight (N,).

    `damage_dealt`, `damage_taken` (health points), `hits_landed` (hits not blocked, by
    attacker), `hits_blocked` (by defender), `rung_out`, `knocked_out`; `over` (N,): a fighter
    lost its last stock.
    """

    def __init__(self, size: int) -> None:
        self.damage = np.zeros((2, 2, size))  # dealt, taken
        self.hits = np.zeros((2, 2, size), dtype=np.int64)  # landed, blocked
        self.outs = np.zeros((2, 2, size), dtype=bool)  # rung out, knocked out
        self.over = np.zeros(size, dtype=bool)

    damage_dealt = property(lambda self: self.damage[0])
    damage_taken = property(lambda self: self.damage[1])
    hits_landed = property(lambda self: self.hits[0])
    hits_blocked = property(lambda self: self.hits[1])
    rung_out = property(lambda self: self.outs[0])
    knocked_out = property(lambda self: self.outs[1])
