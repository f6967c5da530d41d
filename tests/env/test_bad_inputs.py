"""The fuzz list: bad input at every public entry point of the env side gets a clean error.

Each case is a call a user who makes mistakes might write, the error class it must raise (a
ValueError, TypeError or KeyError, or one of ours deriving from them) and a pattern the message
must match: the field's name, then (where there is one) the value. Calls made in the wrong order
(step before reset) are RuntimeErrors and live at the end, apart. The last tests check the other
half of the rule: numpy scalars pass wherever the plain number they hold passes.
"""

from __future__ import annotations

import math
import re
import subprocess
import sys

import gymnasium
import numpy as np
import pytest

import vooga_env
from vooga_env.envs.gym_env import FightEnv
from vooga_env.game.config import ArenaConfig, ConfigError, FightConfig, PhysicsConfig, load_config
from vooga_env.game.fight import Fight
from vooga_env.kernel.params import UnsupportedConfig
from vooga_env.kernel.vector_fight import VectorFight
from vooga_env.physics import (
    FighterBody,
    FightPhysicsEngine,
    MotionAction,
    PlatformBlock,
    SpriteGroupTemplate,
    SpriteTemplate,
    World,
)
from vooga_env.policies import make_policy
from vooga_env.tools.elo import EloTable, round_robin
from vooga_env.tools.match import run_match

NAN, INF = math.nan, math.inf
OBS = np.zeros(41, dtype=np.float32)


def pattern_of(expected: str) -> str:
    """`expected` is literal text, save that ".*" stands for anything in between."""
    return ".*".join(re.escape(part) for part in expected.split(".*"))


def config(**overrides):
    return lambda: load_config("default", **overrides)


def arena(**values):
    return config(arena=values)


def physics(**values):
    return config(physics=values)


def fighter(**values):
    return config(fighter=values)


def punch(**values):
    return config(fighter={"punch": values})


def stepped(action, backend="engine"):
    """A parallel-env step with `action` for fighter_0 (fighter_1 idles)."""

    def call():
        env = vooga_env.parallel_env(backend=backend)
        env.reset(seed=0)
        env.step({"fighter_0": action, "fighter_1": 0})

    return call


def parallel_call(method, *args, **kwargs):
    def call():
        env = vooga_env.parallel_env()
        if method != "reset":
            env.reset(seed=0)
        getattr(env, method)(*args, **kwargs)

    return call


def aec_step(*actions, finish=False):
    """AEC steps with `actions` in turn (after playing a 1-step episode out, if `finish`)."""

    def call():
        env = vooga_env.env(max_cycles=1)
        env.reset(seed=0)
        if finish:
            env.step(0), env.step(0)
            assert env.truncations[env.agent_selection]
        for action in actions:
            env.step(action)

    return call


def gym_play(opponent=None, action=0, **kwargs):
    def call():
        env = FightEnv(opponent=opponent if opponent is not None else "idle", **kwargs)
        env.reset(seed=0)
        env.step(action)

    return call


def vector(num_fights=2, actions=None, seed=0, **kwargs):
    def call():
        fights = VectorFight(num_fights, **kwargs)
        fights.reset(seed=seed)
        if actions is not None:
            fights.step(actions)

    return call


class BatchOpponent:
    """An opponent for FightVecEnv whose `act` returns `value` (the same for any batch)."""

    def __init__(self, value):
        self.value = value

    def act(self, observations):
        return self.value

    def __repr__(self) -> str:
        return "BatchOpponent()"


def vec_env(actions, **kwargs):
    def call():
        from vooga_env.envs.sb3 import FightVecEnv

        env = FightVecEnv(2, **kwargs)
        env.reset()
        env.step(actions)

    return call


def gym_vector(actions, **kwargs):
    def call():
        from vooga_env.envs.gym_vector import FightVectorEnv

        env = FightVectorEnv(2, **{"opponent": "rush", **kwargs})
        env.reset(seed=0)
        env.step(actions)

    return call


class Predicts:
    """A model-like object whose `predict` gives `action`."""

    def __init__(self, action):
        self.action = action

    def predict(self, observation, state=None, episode_start=None, deterministic=True):
        return self.action, state


def policy_act(spec):
    return lambda: make_policy(spec).act(OBS)


def sprite():
    return SpriteTemplate(10.0, 20.0, 30.0, 40.0)


def assign(attribute, value):
    def call():
        setattr(sprite(), attribute, value)

    return call


def world_step(elapsed=16.0, actions=()):
    def call():
        mover = FighterBody(100.0, 100.0, 10.0, 10.0, group_id=1)
        group = SpriteGroupTemplate()
        group.add_sprite_array([mover])
        World(FightPhysicsEngine(800.0, 600.0), group, []).step(elapsed, actions(mover))

    return call


C, T, V, K = ConfigError, TypeError, ValueError, KeyError
CASES = [
    # --- config: each key refused with its name and value
    (
        "spawn-jitter-off-stage",
        arena(spawns=[81.0, 520.0], spawn_jitter=30.0),
        C,
        "arena.spawns[0]",
    ),
    (
        # the fighter's right edge lands on the block's left edge after rounding: both backends
        # find no block under it (formulas.under), so the check must not either
        "spawn-touching-a-block-by-rounding",
        config(
            arena={
                "spawns": [59.343399059355946, 520.0],
                "spawn_jitter": 0.0,
                "blocks": [{"x": 73.6956812327744, "y": 360.0, "width": 620.0, "height": 40.0}],
            },
            fighter={"width": 14.352282173418466},
        ),
        C,
        "arena.spawns[0]",
    ),
    (
        "spawn-jitter-past-edge",
        arena(spawns=[240.0, 620.0], spawn_jitter=70.0),
        C,
        "arena.spawns[1]",
    ),
    (
        "spawn-between-blocks",
        arena(
            spawns=[240.0, 520.0],
            blocks=[
                {"x": 100.0, "y": 360.0, "width": 200.0, "height": 40.0},
                {"x": 500.0, "y": 360.0, "width": 200.0, "height": 40.0},
            ],
            spawn_jitter=150.0,
        ),
        C,
        "arena.spawns[0]",
    ),  # fmt: skip
    (
        "spawn-under-low-ceiling-block",
        arena(
            spawns=[240.0, 520.0],
            spawn_jitter=40.0,
            blocks=[
                {"x": 120.0, "y": 360.0, "width": 560.0, "height": 40.0},
                {"x": 270.0, "y": 20.0, "width": 40.0, "height": 10.0},
            ],
        ),
        C,
        "too tall",
    ),  # fmt: skip
    ("negative-gravity", physics(gravity=-0.002), C, "physics.gravity = -0.002"),
    ("zero-gravity", physics(gravity=0.0), C, "physics.gravity = 0.0"),
    ("max-cycles-2**64", config(max_cycles=2**64), C, f"max_cycles.*{2**64}"),
    ("max-cycles-negative", config(max_cycles=-1), C, "max_cycles = -1"),
    ("max-cycles-float", config(max_cycles=1.5), C, "max_cycles.*1.5"),
    ("max-cycles-string", config(max_cycles="900"), C, "max_cycles.*'900'"),
    ("max-cycles-bool", config(max_cycles=True), C, "max_cycles.*True"),
    ("max-cycles-numpy-float", config(max_cycles=np.float64(500.0)), C, "max_cycles.*500"),
    ("frame-skip-zero", config(frame_skip=0), C, "frame_skip = 0"),
    ("stocks-zero", config(stocks=0), C, "stocks = 0"),
    ("stocks-huge", config(stocks=10**12), C, "stocks.*1000000000000"),
    ("width-nan", arena(width=NAN), C, "arena.width.*nan"),
    ("width-inf", arena(width=INF), C, "arena.width.*inf"),
    ("width-huge", arena(width=1e300), C, "arena.width.*1e+300"),
    ("height-negative", arena(height=-1.0), C, "arena.height = -1.0"),
    ("blocks-empty", arena(blocks=[]), C, "arena.blocks"),
    ("blocks-not-a-list", arena(blocks="floor"), C, "arena.blocks.*'floor'"),
    (
        "block-missing-key",
        arena(blocks=[{"x": 120.0, "y": 360.0, "width": 560.0}]),
        C,
        "arena.blocks[0].height",
    ),  # fmt: skip
    (
        "block-unknown-key",
        arena(blocks=[{"x": 1.0, "y": 1.0, "w": 5.0, "height": 5.0}]),
        C,
        "arena.blocks[0].w",
    ),  # fmt: skip
    (
        "block-outside",
        arena(blocks=[{"x": 700.0, "y": 360.0, "width": 200.0, "height": 40.0}]),
        C,
        "arena.blocks[0]",
    ),  # fmt: skip
    ("block-not-a-table", arena(blocks=[3]), C, "arena.blocks[0].*3"),
    ("one-spawn", arena(spawns=[240.0]), C, "arena.spawns"),
    ("three-spawns", arena(spawns=[240.0, 400.0, 520.0]), C, "arena.spawns"),
    ("spawn-string", arena(spawns=[240.0, "520"]), C, "arena.spawns[1].*'520'"),
    ("jitter-negative", arena(spawn_jitter=-1.0), C, "arena.spawn_jitter = -1.0"),
    ("frame-time-zero", physics(frame_time=0.0), C, "physics.frame_time = 0.0"),
    ("background-zero", physics(background_factor=0.0), C, "physics.background_factor"),
    ("speed-factor-negative", physics(speed_factor=-1.0), C, "physics.speed_factor = -1.0"),
    ("out-bound-negative", physics(out_bound_distance=-1.0), C, "physics.out_bound_distance"),
    ("friction-negative", physics(ground_friction=-0.1), C, "physics.ground_friction = -0.1"),
    ("physics-not-a-table", config(physics="fast"), C, "physics.*'fast'"),
    ("fighter-width-zero", fighter(width=0.0), C, "fighter.width = 0.0"),
    ("fighter-mass-negative", fighter(mass=-1.0), C, "fighter.mass = -1.0"),
    ("crouch-above-height", fighter(crouch_height=70.0), C, "fighter.crouch_height = 70.0"),
    ("health-zero", fighter(health=0.0), C, "fighter.health = 0.0"),
    ("air-jumps-negative", fighter(air_jumps=-1), C, "fighter.air_jumps = -1"),
    ("air-jumps-float", fighter(air_jumps=1.0), C, "fighter.air_jumps.*1.0"),
    ("punch-active-zero", punch(active=0), C, "fighter.punch.active = 0"),
    ("kick-startup-negative", config(fighter={"kick": {"startup": -1}}), C, "fighter.kick.startup"),
    ("hitbox-width-zero", punch(hitbox_width=0.0), C, "fighter.punch.hitbox_width = 0.0"),
    ("damage-nan", punch(damage=NAN), C, "fighter.punch.damage.*nan"),
    ("damage-huge", punch(damage=1e10), C, "fighter.punch.damage.*10000000000"),
    ("hitstun-huge", punch(hitstun=2**40), C, f"fighter.punch.hitstun.*{2**40}"),
    ("enemy-reaction", config(collisions={"enemy": "hug"}), C, "collisions.enemy = 'hug'"),
    ("neutral-reaction-int", config(collisions={"neutral": 3}), C, "collisions.neutral.*3"),
    ("reward-negative", config(rewards={"ko": -1.0}), C, "rewards.ko = -1.0"),
    ("start-damage-negative", config(start={"damage": -1.0}), C, "start.damage = -1.0.*>= 0"),
    (
        "start-damage-a-ko",
        config(start={"damage": 100.0}),
        C,
        "start.damage = 100.0.*< fighter.health (100)",
    ),
    ("start-steps-over", config(start={"steps": 900}), C, "start.steps = 900.*< max_cycles (900)"),
    ("start-steps-float", config(start={"steps": 1.5}), C, "start.steps.*integer.*1.5"),
    ("rewards-not-a-table", config(rewards="none"), C, "rewards.*'none'"),
    ("unknown-top-key", config(gravity=0.003), C, "'gravity'"),
    ("unknown-nested-key", physics(gravty=0.003), C, "'physics.gravty'"),
    ("name-int", config(name=3), C, "name.*3"),
    ("config-int", lambda: load_config(3), C, "config.*3"),
    ("config-unknown-name", lambda: load_config("nope"), C, "'nope'"),
    (
        "hand-built-config",
        lambda: vooga_env.parallel_env(
            config=FightConfig(arena=ArenaConfig(spawns=(81.0, 520.0), spawn_jitter=30.0))
        ),
        C,
        "arena.spawns[0]",
    ),
    (
        "hand-built-gravity",
        lambda: VectorFight(2, FightConfig(physics=PhysicsConfig(gravity=-1.0))),
        C,
        "physics.gravity = -1.0",
    ),  # fmt: skip
    (
        "hand-built-string-number",
        lambda: load_config(FightConfig(max_cycles="9")),
        C,
        "max_cycles.*'9'",
    ),  # fmt: skip
    ("replace-bad", lambda: load_config("default").replace(max_cycles=0), C, "max_cycles = 0"),
    # --- the game itself
    ("fight-config-name", lambda: Fight("default"), T, "config.*'default'"),
    ("fight-reset-seed", lambda: Fight(load_config()).reset(7), T, "rng.*7"),
    ("fight-step-action", lambda: _fight().step((0, 12)), V, "actions[1] = 12"),
    ("fight-step-string", lambda: _fight().step(("jump", 0)), V, "actions[0] = 'jump'"),
    # --- the parallel env
    ("render-mode", lambda: vooga_env.parallel_env(render_mode="ansi"), V, "render_mode.*'ansi'"),
    ("backend", lambda: vooga_env.parallel_env(backend="gpu"), V, "backend = 'gpu'"),
    ("reward-fn-int", lambda: vooga_env.parallel_env(reward_fn=3), T, "reward_fn = 3"),
    ("reward-fn-string", lambda: vooga_env.parallel_env(reward_fn="ko"), T, "reward_fn = 'ko'"),
    ("env-max-cycles", lambda: vooga_env.parallel_env(max_cycles=2**64), C, "max_cycles"),
    ("env-config-int", lambda: vooga_env.parallel_env(config=3), C, "config.*3"),
    ("seed-negative", parallel_call("reset", seed=-1), V, "seed.*-1"),
    ("seed-float", parallel_call("reset", seed=1.5), V, "seed.*1.5"),
    ("seed-string", parallel_call("reset", seed="7"), V, "seed.*'7'"),
    ("seed-bool", parallel_call("reset", seed=True), V, "seed.*True"),
    ("actions-list", parallel_call("step", [0, 0]), T, "actions.*[0, 0]"),
    ("action-10", stepped(10), V, "fighter_0.*10"),
    ("action-10-compiled", stepped(10, "compiled"), V, "fighter_0.*10"),
    ("action-float", stepped(1.5), T, "fighter_0.*1.5"),
    ("action-string", stepped("kick"), T, "fighter_0.*'kick'"),
    ("action-none", stepped(None), T, "fighter_0.*None"),
    ("action-array", stepped(np.array([1, 2])), T, "fighter_0.*array([1, 2])"),
    ("action-numpy-bool", stepped(np.bool_(True)), T, "fighter_0.*True"),
    ("action-missing", parallel_call("step", {"fighter_0": 0}), K, "fighter_1"),
    (
        "action-unknown-agent",
        parallel_call("step", {"fighter_0": 0, "fighter_1": 0, "me": 0}),
        K,
        "me",
    ),  # fmt: skip
    ("observation-space-agent", parallel_call("observation_space", "fighter_9"), K, "fighter_9"),
    ("action-space-agent", parallel_call("action_space", "nobody"), K, "nobody"),
    # --- the AEC env
    ("aec-action-10", aec_step(10), V, "fighter_0.*10"),
    ("aec-second-agent-action", aec_step(0, -1), V, "fighter_1.*-1"),
    ("aec-action-string", aec_step("kick"), T, "fighter_0.*'kick'"),
    ("aec-action-none-live", aec_step(None), T, "fighter_0.*None"),
    ("aec-action-for-done-agent", aec_step(1, finish=True), V, "fighter_0 = 1.*done"),
    ("aec-observe-agent", lambda: _aec().observe("fighter_9"), K, "fighter_9"),
    ("aec-max-iter", lambda: _aec().agent_iter(max_iter=-1), V, "max_iter.*-1"),
    ("aec-seed", lambda: vooga_env.env().reset(seed=-1), V, "seed.*-1"),
    # --- the Gymnasium env
    (
        "gym-opponent-name",
        lambda: gymnasium.make("vooga_env/Fight-v0", opponent="ninja"),
        V,
        "'ninja'",
    ),  # fmt: skip
    ("gym-opponent-int", lambda: FightEnv(opponent=42), T, "policy.*42"),
    ("gym-opponent-returns-10", gym_play(lambda obs: 10), V, "opponent.*10"),
    ("gym-opponent-returns-none", gym_play(lambda obs: None), T, "opponent.*None"),
    ("gym-opponent-returns-float", gym_play(lambda obs: 2.5), T, "opponent.*2.5"),
    ("gym-opponent-predicts-two", gym_play(Predicts(np.array([1, 2]))), V, "policy.*[1, 2]"),
    ("gym-seat-2", lambda: FightEnv(seat=2), V, "seat.*2"),
    ("gym-seat-bool", lambda: FightEnv(seat=True), T, "seat.*True"),
    ("gym-seat-string", lambda: FightEnv(seat="left"), T, "seat.*'random'.*'left'"),
    ("gym-seat-float", lambda: FightEnv(seat=1.0), T, "seat.*1.0"),
    ("gym-action-10", gym_play(action=10), V, "fighter_0.*10"),
    ("gym-seed-negative", lambda: FightEnv().reset(seed=-1), V, "seed.*-1"),
    ("gym-seed-float", lambda: FightEnv().reset(seed=0.5), V, "seed.*0.5"),
    ("gym-set-opponent", lambda: FightEnv().set_opponent(None), T, "policy.*None"),
    ("gym-reward-fn", lambda: FightEnv(reward_fn=[1, 2]), T, "reward_fn"),
    # --- VectorFight
    ("vector-zero-fights", vector(num_fights=0), V, "num_fights.*0"),
    ("vector-float-fights", vector(num_fights=1.5), T, "num_fights.*1.5"),
    ("vector-bool-fights", vector(num_fights=True), T, "num_fights.*True"),
    ("vector-backend", vector(backend="cuda"), V, "backend.*'cuda'"),
    ("vector-threads-zero", vector(threads=0), V, "threads.*0"),
    ("vector-backend-numpy", vector(backend="numpy"), V, "backend.*numpy.*gone"),
    ("vector-seed-negative", vector(seed=-1), V, "seed.*-1"),
    ("vector-seed-short-list", vector(seed=[0]), V, "seed.*2.*1"),
    ("vector-seed-list-item", vector(seed=[0, "a"]), V, "seed[1] = 'a'"),
    ("vector-seed-list-negative", vector(seed=[0, -5]), V, "seed[1] = -5"),
    ("vector-actions-shape", vector(actions=np.zeros((3, 2), dtype=int)), V, "actions.*(3, 2)"),
    ("vector-actions-10", vector(actions=[[0, 0], [10, 0]]), V, "actions[1, 0] = 10"),
    ("vector-actions-negative", vector(actions=[[0, -1], [0, 0]]), V, "actions[0, 1] = -1"),
    ("vector-actions-float", vector(actions=[[0, 1.5], [0, 0]]), T, "actions.*float64"),
    ("vector-actions-string", vector(actions=[["a", "b"], ["c", "d"]]), T, "actions"),
    (
        "vector-unsupported",
        vector(collisions={"enemy": "momentum"}),
        UnsupportedConfig,
        "collisions.enemy = 'momentum'",
    ),  # fmt: skip
    ("vector-reward-fn", vector(reward_fn=lambda f, e: (0, 0)), UnsupportedConfig, "reward_fn"),
    ("vector-config", vector(max_cycles=-5), C, "max_cycles = -5"),
    # --- FightVecEnv (SB3)
    ("vecenv-seat", vec_env([0, 0], opponent="rush", seat=2), V, "seat.*2"),
    ("vecenv-opponent-int", vec_env([0, 0], opponent=42), T, "opponent.*42"),
    ("vecenv-opponent-name", vec_env([0, 0], opponent="ninja"), V, "'ninja'"),
    (
        "vecenv-opponent-seed",
        vec_env([0, 0], opponent="rush", opponent_seed=-1),
        V,
        "opponent seed.*-1",
    ),  # fmt: skip
    (
        "vecenv-opponent-seed-float",
        vec_env([0, 0], opponent="zoner", opponent_seed=0.5),
        V,
        "opponent seed.*0.5",
    ),  # fmt: skip
    ("vecenv-too-few-actions", vec_env([0, 0, 0]), V, "actions.*4.*(3,)"),
    ("vecenv-too-many-actions", vec_env([0, 0, 0, 0, 0]), V, "actions.*4.*(5,)"),
    ("vecenv-vs-too-many", vec_env([0, 0, 0], opponent="rush"), V, "actions.*2.*(3,)"),
    ("vecenv-action-10", vec_env([0, 10], opponent="rush"), V, "actions[1] = 10"),
    ("vecenv-action-float", vec_env([0, 1.5], opponent="rush"), T, "actions.*1.5"),
    ("vecenv-self-play-action-10", vec_env([0, 0, 10, 0]), V, "actions[1, 0] = 10"),
    ("vecenv-seat-bool", vec_env([0, 0], opponent="rush", seat=True), T, "seat.*True"),
    (
        "vecenv-opponent-shape",
        vec_env([0, 0], opponent=BatchOpponent([1])),
        V,
        "opponent BatchOpponent().*2.*(1,)",
    ),  # fmt: skip
    (
        "vecenv-opponent-range",
        vec_env([0, 0], opponent=BatchOpponent([1, 12])),
        V,
        "opponent BatchOpponent().*0..9",
    ),  # fmt: skip
    (
        "vecenv-opponent-floats",
        vec_env([0, 0], opponent=BatchOpponent([0.5, 1.0])),
        T,
        "opponent BatchOpponent().*0.5",
    ),  # fmt: skip
    (
        "vecenv-opponent-none",
        vec_env([0, 0], opponent=BatchOpponent(None)),
        V,
        "opponent BatchOpponent()",
    ),  # fmt: skip
    # --- FightVectorEnv (Gymnasium's vector API)
    ("gymvec-action-10", gym_vector([0, 10]), V, "actions[1] = 10"),
    ("gymvec-action-float", gym_vector([0.5, 1]), T, "actions.*0.5"),
    ("gymvec-action-count", gym_vector([0, 1, 2]), V, "actions.*(2,).*(3,)"),
    (
        "gymvec-opponent-shape",
        gym_vector([0, 0], opponent=BatchOpponent([1, 2, 3])),
        V,
        "opponent BatchOpponent().*(2,).*(3,)",
    ),  # fmt: skip
    (
        "gymvec-opponent-range",
        gym_vector([0, 0], opponent=BatchOpponent([-1, 0])),
        V,
        "opponent BatchOpponent().*[0] = -1",
    ),  # fmt: skip
    ("gymvec-opponent-int", gym_vector([0, 0], opponent=5), T, "opponent.*5"),
    ("gymvec-seat-bool", gym_vector([0, 0], seat=False), T, "seat.*False"),
    ("gymvec-seat-3", gym_vector([0, 0], seat=3), V, "seat.*3"),
    ("gymvec-render-mode", gym_vector([0, 0], render_mode="human"), V, "render_mode.*'human'"),
    ("gymvec-config", gym_vector([0, 0], frame_skip=0), C, "frame_skip = 0"),
    # --- policies
    ("policy-name", lambda: make_policy("ninja"), V, "'ninja'.*rush"),
    ("policy-int", lambda: make_policy(42), T, "policy.*42"),
    ("policy-none", lambda: make_policy(None), T, "policy.*None"),
    ("policy-seed-negative", lambda: make_policy("rush", seed=-1), V, "seed.*-1"),
    ("policy-seed-float", lambda: make_policy("rush", seed=1.5), V, "seed.*1.5"),
    ("policy-returns-10", policy_act(lambda obs: 10), V, "policy '<lambda>'.*10"),
    ("policy-returns-none", policy_act(lambda obs: None), T, "policy '<lambda>'.*None"),
    ("policy-returns-string", policy_act(lambda obs: "kick"), T, "policy.*'kick'"),
    (
        "policy-predict-not-callable",
        lambda: make_policy(type("M", (), {"predict": 3})()),
        T,
        "predict.*3",
    ),  # fmt: skip
    ("policy-predicts-10", policy_act(Predicts(10)), V, "policy 'Predicts'.*10"),
    (
        "policy-missing-model",
        lambda: make_policy("nowhere/model.zip"),
        FileNotFoundError,
        "nowhere/model",
    ),  # fmt: skip
    # --- matches
    ("match-episodes", lambda: run_match("rush", "idle", episodes=0), V, "episodes.*0"),
    ("match-seed", lambda: run_match("rush", "idle", seed=-3), V, "seed.*-3"),
    ("match-seed-float", lambda: run_match("rush", "idle", seed=0.5), V, "seed.*0.5"),
    (
        "match-record-frames",
        lambda: run_match("rush", "idle", record_frames=-1),
        V,
        "record_frames.*-1",
    ),  # fmt: skip
    ("match-names", lambda: run_match("rush", "idle", names="ab"), T, "names.*'ab'"),
    ("match-names-int", lambda: run_match("rush", "idle", names=3), T, "names.*3"),
    ("match-progress", lambda: run_match("rush", "idle", progress=3), T, "progress.*3"),
    ("match-step-hook", lambda: run_match("rush", "idle", step_hook="log"), T, "step_hook.*'log'"),
    ("match-policy", lambda: run_match("rush", 7), T, "policy.*7"),
    ("match-config", lambda: run_match("rush", "idle", episodes=1, stocks=0), C, "stocks = 0"),
    # --- Elo tables and tournaments
    ("elo-k-zero", lambda: EloTable(["a", "b"], k=0), V, "k.*0"),
    ("elo-k-nan", lambda: EloTable(["a", "b"], k=NAN), V, "k.*nan"),
    ("elo-start-string", lambda: EloTable(["a"], start="1000"), T, "start.*'1000'"),
    ("elo-unknown-name", lambda: EloTable(["a", "b"]).record("a", "c", 1.0), K, "'c'.*a, b"),
    ("elo-score", lambda: EloTable(["a", "b"]).record("a", "b", 2.0), V, "score.*2.0"),
    ("elo-score-nan", lambda: EloTable(["a", "b"]).record("a", "b", NAN), V, "score.*nan"),
    ("tournament-seed", lambda: round_robin(["rush", "idle"], seed=-1), V, "seed.*-1"),
    ("tournament-episodes", lambda: round_robin(["rush", "idle"], episodes=0), V, "episodes.*0"),
    ("tournament-one", lambda: round_robin(["rush"]), V, "two entrants.*rush"),
    ("tournament-entrant", lambda: round_robin(["rush", 3.5]), T, "policy.*3.5"),
    # --- physics sprites and world
    ("sprite-x-nan", assign("x", NAN), V, "x.*nan"),
    ("sprite-y-inf", assign("y", INF), V, "y.*inf"),
    ("sprite-vx-string", assign("vx", "fast"), T, "vx.*'fast'"),
    ("sprite-vy-nan", assign("vy", NAN), V, "vy.*nan"),
    ("sprite-x-none", assign("x", None), T, "x.*None"),
    ("sprite-x-numpy-nan", assign("x", np.float32("nan")), V, "x.*nan"),
    ("sprite-width-numpy-negative", assign("width", np.float64(-2.0)), V, "width.*-2.0"),
    ("sprite-mass-bool", assign("mass", True), T, "mass.*True"),
    ("block-width-zero", lambda: PlatformBlock(0.0, 0.0, 0.0, 10.0), V, "width.*0.0"),
    (
        "engine-gravity-string",
        lambda: FightPhysicsEngine(800.0, 600.0, gravity="down"),
        T,
        "gravity.*'down'",
    ),  # fmt: skip
    ("world-elapsed-zero", world_step(elapsed=0.0, actions=lambda m: []), V, "elapsed_time.*0.0"),
    (
        "world-action-tuple",
        world_step(actions=lambda m: [(1.0, 0.0)]),
        T,
        "motion_actions.*(1.0, 0.0)",
    ),  # fmt: skip
    (
        "world-action-foreign-sprite",
        world_step(actions=lambda m: [MotionAction(sprite(), 1, 0)]),
        V,
        "motion action.*not in this world",
    ),  # fmt: skip
    (
        "increment-nan",
        lambda: FightPhysicsEngine(80, 60).set_next_location_increment(sprite(), NAN, 0.0),
        V,
        "dx.*nan",
    ),  # fmt: skip
    (
        "increment-string",
        lambda: FightPhysicsEngine(80, 60).set_next_location_increment(sprite(), 0.0, "up"),
        T,
        "dy.*'up'",
    ),  # fmt: skip
    ("motion-vector-nan", lambda: MotionAction(sprite(), NAN, 0.0), V, "vector_x.*nan"),
]


def _fight():
    fight = Fight(load_config())
    fight.reset(np.random.default_rng(0))
    return fight


def _aec():
    env = vooga_env.env()
    env.reset(seed=0)
    return env


def _iterate_without_stepping(env):
    for _ in env.agent_iter():
        pass


def test_the_list_is_long_enough():
    assert len(CASES) >= 80
    assert len({case[0] for case in CASES}) == len(CASES)


@pytest.mark.parametrize(
    ("call", "error", "pattern"), [pytest.param(*c[1:], id=c[0]) for c in CASES]
)
def test_bad_input_gets_a_clean_error(call, error, pattern):
    with pytest.raises(error) as raised:
        call()
    assert isinstance(raised.value, (ValueError, TypeError, KeyError, FileNotFoundError))
    assert not isinstance(raised.value, AssertionError)
    message = str(raised.value.args[0]) if raised.value.args else ""
    assert re.search(pattern_of(pattern), message, re.DOTALL), message


ORDER = [
    ("parallel-step-before-reset", lambda: vooga_env.parallel_env().step({})),
    ("aec-step-before-reset", lambda: vooga_env.env().step(0)),
    ("aec-observe-before-reset", lambda: vooga_env.env().observe("fighter_0")),
    ("aec-state-before-reset", lambda: vooga_env.env().state()),
    ("aec-iter-without-step", lambda: _iterate_without_stepping(_aec())),
    ("gym-step-before-reset", lambda: FightEnv().step(0)),
    ("vector-step-before-reset", lambda: VectorFight(2).step(np.zeros((2, 2), dtype=int))),
]


@pytest.mark.parametrize("call", [pytest.param(c, id=i) for i, c in ORDER])
def test_calls_out_of_order_say_what_to_call_first(call):
    with pytest.raises(RuntimeError, match=r"reset\(\)|step\(\)"):
        call()


def test_numpy_scalars_in_a_config_are_the_plain_numbers_they_hold():
    plain = load_config(
        "default", max_cycles=500, arena={"spawns": [240.0, 520.0]}, physics={"gravity": 0.0025}
    )
    numpy = load_config(
        "default",
        max_cycles=np.int64(500),
        arena={"spawns": [np.float32(240.0), np.int32(520)]},
        physics={"gravity": np.float64(0.0025)},
    )
    assert numpy == plain
    assert type(numpy.max_cycles) is int and type(numpy.arena.spawns[0]) is float


def test_numpy_scalars_at_the_other_entry_points_are_accepted():
    env = vooga_env.parallel_env(max_cycles=np.int64(40), frame_skip=np.uint8(2))
    env.reset(seed=np.int64(3))
    env.step({"fighter_0": np.int16(2), "fighter_1": np.array(7)})
    gym_env = FightEnv(opponent="rush", seat=np.int64(1))
    gym_env.reset(seed=np.uint32(5))
    gym_env.step(np.int64(3))
    assert make_policy("random", seed=np.int64(4)).act(OBS) in range(10)
    fights = VectorFight(np.int64(2), max_cycles=np.int32(30))
    fights.reset(seed=[np.int64(1), None])
    fights.step(np.ones((2, 2), dtype=np.int8))
    body = SpriteTemplate(np.float32(1.5), np.int64(2), np.float32(3.0), np.float16(4.0))
    body.x, body.vy = np.float32(2.5), np.int32(-1)
    assert (body.x, body.y, body.vy) == (2.5, 2.0, -1.0) and type(body.x) is float
    engine = FightPhysicsEngine(np.float32(800.0), 600, gravity=np.float32(0.002))
    group = SpriteGroupTemplate()
    group.add_sprite_array([body])
    World(engine, group, []).step(np.float32(16.0), [MotionAction(body, np.float32(1.0), 0)])
    group.add_sprite(SpriteTemplate(0, 0, 1, 1), np.int64(1))
    aec = vooga_env.env(max_cycles=np.int64(2))
    aec.reset(seed=np.int64(0))
    assert len(list(aec.agent_iter(max_iter=np.int64(0)))) == 0
    assert run_match("rush", "idle", episodes=np.int64(1), seed=np.uint8(2)).games == 1


def test_a_numpy_max_cycles_plays_the_same_game_as_a_plain_one():
    games = []
    for max_cycles in (60, np.int64(60)):
        env = vooga_env.parallel_env(max_cycles=max_cycles, backend="compiled")
        env.reset(seed=1)
        games.append([env.step({"fighter_0": 2, "fighter_1": 8})[0] for _ in range(60)])
    assert all(a[k].tobytes() == b[k].tobytes() for a, b in zip(*games) for k in a)


def test_the_checks_survive_python_dash_o():
    """No check is an `assert`: under `python -O` the same inputs get the same errors."""
    code = """
import vooga_env
from vooga_env.game.config import ConfigError
aec = vooga_env.env(backend="engine")  # numba takes seconds to load
for call, error in [
    (lambda: aec.step(0), RuntimeError),
    (lambda: (aec.reset(seed=0), aec.step(10)), ValueError),
    (lambda: aec.step("kick"), TypeError),
    (lambda: vooga_env.parallel_env(physics={"gravity": -1.0}), ConfigError),
    (lambda: vooga_env.parallel_env(arena={"spawns": [81, 520], "spawn_jitter": 30}), ConfigError),
]:
    try:
        call()
    except error:
        pass
    else:
        raise SystemExit(f"no {error.__name__} under -O")
"""
    subprocess.run([sys.executable, "-O", "-c", code], check=True, timeout=120)
