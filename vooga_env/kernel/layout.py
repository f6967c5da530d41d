"""The kernel's named numbers: action tables, move codes, observation slots, state rows, terms.

The compiled kernel reads plain arrays and ints, so every number that stands for an action, an
attack, an observation entry or a state field is named here once, derived from `Action`,
`ATTACKS`, `OBSERVATION_NAMES` and `state.py` (or checked against them) rather than written as a
literal.
"""

from __future__ import annotations

import numpy as np

from vooga_env.game.actions import ATTACKS, JUMPS, WALK, Action
from vooga_env.game.observations import FIGHTER_FEATURES, GLOBAL_FEATURES, OBSERVATION_NAMES
from vooga_env.kernel.state import (
    FIGHT_COUNTERS,
    FIGHT_FLOATS,
    FIGHTER_FLAGS,
    FIGHTER_FLOATS,
    FIGHTER_INTS,
)

# move codes (the state's `move`, the attack tables' index): 0 none, then the attacks
MOVES = tuple(dict.fromkeys(ATTACKS.values()))  # ("punch", "kick")
NO_MOVE = 0
PUNCH, KICK = (MOVES.index(name) + 1 for name in ("punch", "kick"))

# actions the kernel tests one by one
DOWN, BLOCK = int(Action.DOWN), int(Action.BLOCK)
# per action code: is it a jump, its move code (NO_MOVE if none), its walk direction (0: none)
IS_JUMP = np.array([a in JUMPS for a in Action])
ATTACK_MOVE = np.array([MOVES.index(ATTACKS[a]) + 1 if a in ATTACKS else NO_MOVE for a in Action])
WALK_DIRECTION = np.array([WALK.get(a, 0.0) for a in Action])
IS_WALK = WALK_DIRECTION != 0.0

# observation slots: a fighter's features, the same features of its opponent, then the globals
FEATURES = len(FIGHTER_FEATURES)
SELF = {name: k for k, name in enumerate(FIGHTER_FEATURES)}
OPPONENT = FEATURES  # opponent feature k sits at OPPONENT + k
OBS_X, OBS_Y, OBS_VX, OBS_VY, OBS_FACING = (SELF[n] for n in ("x", "y", "vx", "vy", "facing"))
OBS_HEALTH, OBS_DAMAGE_TAKEN, OBS_ON_GROUND, OBS_JUMPS_LEFT = (
    SELF[n] for n in ("health", "damage_taken", "on_ground", "jumps_left")
)
OBS_PUNCHING, OBS_KICKING, OBS_BLOCKING, OBS_CROUCHING = (
    SELF[n] for n in ("punching", "kicking", "blocking", "crouching")
)
OBS_MOVE_PROGRESS, OBS_HITBOX_ACTIVE, OBS_HITSTUN, OBS_STOCKS = (
    SELF[n] for n in ("move_progress", "hitbox_active", "hitstun", "stocks")
)
OBS_PUNCH_REACH, OBS_KICK_REACH = SELF["punch_reach"], SELF["kick_reach"]
OBS_STAGE_LEFT, OBS_STAGE_RIGHT, OBS_TIME_LEFT = (
    OBSERVATION_NAMES.index(name) for name in GLOBAL_FEATURES
)
assert OBSERVATION_NAMES[OPPONENT] == "opponent_" + FIGHTER_FEATURES[0]
assert MOVES == ("punch", "kick") and (PUNCH, KICK) == (1, 2), "the reach slots assume these"

# rows of the state's blocks (state.py): fl = fighter floats, it = fighter ints, fg = fighter
# flags, ct = fight counters, values = fight floats
S_X, S_Y, S_VX, S_VY, S_HEIGHT, S_HEALTH, S_FACING = range(7)
S_HIT_X, S_HIT_Y, S_HIT_W, S_HIT_H, S_SPAWN_X, S_SPAWN_TOP = range(7, 13)
S_STOCKS, S_JUMPS_LEFT, S_MOVE, S_MOVE_FRAME, S_HITSTUN = range(5)
S_ON_GROUND, S_ON_HEAD, S_JUMP_HELD, S_BLOCKING, S_CROUCHING, S_HIT_ACTIVE, S_STRUCK = range(7)
S_FRAME, S_STEPS = range(2)
S_POTENTIAL = 0
for _names in (FIGHTER_FLOATS, FIGHTER_INTS, FIGHTER_FLAGS, FIGHT_COUNTERS, FIGHT_FLOATS):
    for _row, _name in enumerate(_names):
        assert globals()["S_" + _name.upper()] == _row, f"state.py's {_name} moved"

# A coordinate's terms in `PendingResponse.resolve`: itself, its increment, the friction's slide,
# then one shift per reaction that can shift a fighter in a frame: the push's separation and its
# redirect (the one pair of fighters), and the opponent's hitbox (one hit a frame at most). A
# velocity's terms are fewer (itself, the push's change, the hit's), so one size serves both.
# numba does not bounds-check, so tests/kernel/test_stages.py checks that no stage adds more.
FIXED_TERMS = 3
SHIFTS = {"separation": 1, "push": 1, "hit": 1}
MAX_TERMS = FIXED_TERMS + sum(SHIFTS.values())
