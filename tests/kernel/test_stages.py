"""The kernel stage by stage against its engine twin, bit for bit, on hypothesis-drawn states.

Formulas: each one of `physics/formulas.py` and `formulas.py`, in Python and compiled, on drawn
floats. Stages: a fight played by the engine to a drawn point is copied into a one-fight
`FightState`; the kernel's `control` + `place_hitboxes`, its whole frame (every reaction, the
update, the bookkeeping: one step of a one-frame config), its `observe` and its reset must then
leave exactly the state the engine's `Fight._control` / `_place_hitbox`, `Fight._frame`,
`observe_both` and `Fight.reset` leave. The recorded reference games (test_equivalence.py)
stay the end-to-end contract.
"""

from __future__ import annotations

import inspect
import math
import struct

import numba
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from vooga_env.game import formulas as fight_formulas
from vooga_env.game.actions import Action
from vooga_env.game.config import load_config, spawn_block
from vooga_env.game.fight import Fight
from vooga_env.game.observations import observe_both
from vooga_env.kernel import stages
from vooga_env.kernel.compiled import Kernel, kernel_arrays, state_blocks
from vooga_env.kernel.layout import MOVES
from vooga_env.kernel.params import FightParams
from vooga_env.kernel.parts import F, params_record, scratch, state_record
from vooga_env.kernel.state import FightState
from vooga_env.kernel.state import StepEvents as BatchEvents
from vooga_env.physics import formulas as physics_formulas

CONFIGS = ("default", "platforms", "water")
FORMULAS = [
    (module.__name__.rsplit(".", 2)[-2] + "." + name, function)
    for module in (physics_formulas, fight_formulas)
    for name, function in vars(module).items()
    if inspect.isfunction(function) and function.__module__ == module.__name__
]
# floats where the formulas branch: zeros of both signs, ties, infinities (immovable masses)
number = st.one_of(
    st.floats(-1e6, 1e6, allow_nan=False),
    st.sampled_from([0.0, -0.0, 1.0, -1.0, 0.5, 1e-9, 2e-9, math.inf, -math.inf]),
)
ARGUMENTS = {"float": number, "bool": st.booleans(), "int": st.integers(-(2**40), 2**40)}


def bits(value) -> tuple:
    """A value (or tuple of values) as comparable bytes: -0.0 and 0.0 differ, as do NaNs."""
    if isinstance(value, tuple):
        return tuple(bits(v) for v in value)
    if isinstance(value, bool | np.bool_):
        return ("bool", bool(value))
    if isinstance(value, int | np.integer):
        return ("int", int(value))
    return ("float", struct.pack("<d", float(value)))


@pytest.mark.parametrize(("name", "function"), FORMULAS, ids=[name for name, _ in FORMULAS])
@settings(max_examples=100, deadline=None)
@given(data=st.data())
def test_every_formula_compiles_to_the_same_bits(name, function, data):
    parameters = inspect.signature(function).parameters.values()
    arguments = [data.draw(ARGUMENTS[p.annotation], label=p.name) for p in parameters]
    compiled = getattr(F, function.__name__)
    try:
        expected = function(*arguments)
    except ZeroDivisionError:  # numba keeps Python's error model
        with pytest.raises(ZeroDivisionError):
            compiled(*arguments)
        return
    assert bits(compiled(*arguments)) == bits(expected), (name, arguments)


# ---- the stages, on states the engine reached


def played(config: str, seed: int, actions: list[tuple[int, int]], **overrides) -> Fight:
    """A fight reset with `seed` and stepped through `actions` by the engine."""
    fight = Fight(load_config(config, **overrides))
    fight.reset(np.random.default_rng(seed))
    for pair in actions:
        fight.step(pair)
        if fight.over:
            break
    return fight


def kernel_state(fight: Fight) -> FightState:
    """The engine's fight as a one-fight `FightState` (every field the kernel keeps)."""
    s = FightState(1)
    for f, fighter in enumerate(fight.fighters):
        hitbox = fighter.hitbox
        values = {
            "x": fighter.x, "y": fighter.y, "vx": fighter.vx, "vy": fighter.vy,
            "height": fighter.height, "health": fighter.health, "facing": fighter.facing,
            "hit_x": hitbox.x, "hit_y": hitbox.y, "hit_w": hitbox.width, "hit_h": hitbox.height,
            "spawn_x": fight.spawns[f],
            "spawn_top": spawn_block(fight.config.arena, fight.spawns[f], fighter.width).y,
            "stocks": fighter.stocks, "jumps_left": fighter.jumps_left,
            "move": 0 if fighter.move is None else MOVES.index(fighter.move) + 1,
            "move_frame": fighter.move_frame, "hitstun": fighter.hitstun,
            "on_ground": fighter.on_ground, "on_head": fighter.on_head,
            "jump_held": fighter.jump_held, "blocking": fighter.blocking,
            "crouching": fighter.crouching, "hit_active": hitbox.active,
            "struck": bool(hitbox.struck),
        }  # fmt: skip
        for name, value in values.items():
            getattr(s, name)[f, 0] = value
    s.frame[0], s.steps[0] = fight.frame, fight.steps
    return s


def assert_same_state(got: FightState, expected: FightState, what: str) -> None:
    for name, array in expected.arrays().items():
        if name != "potential":  # the reward's, not the fight's
            assert getattr(got, name).tobytes() == array.tobytes(), (
                f"{what}: {name} {getattr(got, name)!r} != {array!r}"
            )


@numba.njit
def run_control(fp, ip, blocks, spawns, af, ai, fl, it, fg, ct, values, actions):
    """Fight 0 through the kernel's `control` of both fighters, then `place_hitboxes`."""
    p, s = params_record(fp, ip, blocks, spawns, af, ai), state_record(fl, it, fg, ct, values)
    x = scratch()
    for f in range(2):
        stages.control(p, s, x, 0, f, actions[0, f])
    stages.place_hitboxes(p, s, 0)


drawn_fights = st.tuples(
    st.sampled_from(CONFIGS),
    st.integers(0, 2**16),
    st.lists(st.tuples(st.integers(0, 9), st.integers(0, 9)), max_size=80),
    st.tuples(st.integers(0, 9), st.integers(0, 9)),
)


@settings(max_examples=40, deadline=None)
@given(drawn_fights)
def test_control_and_place_hitboxes_match_the_fights(drawn):
    config, seed, history, pair = drawn
    fight = played(config, seed, history)
    s, p = kernel_state(fight), kernel_arrays(FightParams.from_config(fight.config))
    run_control(*p, *state_blocks(s), np.array([pair]))
    for fighter, action in zip(fight.fighters, pair, strict=True):
        fight._control(fighter, Action(action))
    for fighter in fight.fighters:
        fight._place_hitbox(fighter)
    assert_same_state(s, kernel_state(fight), f"{config}, seed {seed}, {len(history)} steps")


@settings(max_examples=60, deadline=None)
@given(drawn_fights)
def test_one_frame_matches_the_fights(drawn):
    # one step of a frame_skip = 1 fight is one frame: every reaction, the update, the
    # bookkeeping; through the kernel's own compiled step (no second compile of the stages)
    config, seed, history, pair = drawn
    fight = played(config, seed, history, frame_skip=1)
    s, batch_events = kernel_state(fight), BatchEvents(1)
    kernel = Kernel(FightParams.from_config(fight.config))
    rewards, truncated = np.empty((1, 2)), np.empty(1, dtype=bool)
    kernel.step(s, np.array([pair]), batch_events, rewards, truncated, np.empty(1, np.int64))
    events = fight.step(pair)
    what = f"{config}, seed {seed}, {len(history)} steps, then {pair}"
    assert_same_state(s, kernel_state(fight), what)
    assert batch_events.over[0] == events.over, what
    assert batch_events.damage_dealt[:, 0].tolist() == events.damage_dealt, what
    assert batch_events.rung_out[:, 0].tolist() == events.rung_out, what
    assert batch_events.knocked_out[:, 0].tolist() == events.knocked_out, what


@settings(max_examples=40, deadline=None)
@given(drawn_fights)
def test_observe_matches_observe_both(drawn):
    config, seed, history, _ = drawn
    fight = played(config, seed, history)
    kernel = Kernel(FightParams.from_config(fight.config))
    out = np.empty((1, 2, 41), dtype=np.float32)
    kernel.observe(kernel_state(fight), out, np.zeros(1, dtype=np.int64))
    assert out[0].tobytes() == observe_both(fight).tobytes()


@settings(max_examples=30, deadline=None)
@given(st.sampled_from(CONFIGS), st.integers(0, 2**32), st.integers(0, 3))
def test_reset_matches_the_fights_reset_and_draws_the_same_numbers(config, seed, resets):
    fight = Fight(load_config(config, arena={"spawn_jitter": 25.0}))
    rng = np.random.default_rng(seed)
    s = FightState(1)
    s.rng.set_state(0, rng.bit_generator.state)
    kernel = Kernel(FightParams.from_config(fight.config))
    for _ in range(resets + 1):
        fight.reset(rng)
        kernel.reset(s, np.zeros(1, dtype=np.int64))
        assert_same_state(s, kernel_state(fight), f"{config}, seed {seed}")
        assert s.rng.get_state(0) == rng.bit_generator.state
