"""The random-style opponent: it plays the style it drew, draws others, and repeats from its seed
and its saved state."""

import numpy as np
import pytest

from vooga_env.envs.sb3 import FightVecEnv
from vooga_env.game.actions import Action
from vooga_env.game.config import load_config
from vooga_env.game.observations import OBSERVATION_NAMES
from vooga_env.policies.random_styles import MOVES, PHASES, RandomStyles

X = OBSERVATION_NAMES.index("opponent_x")
EDGES = [OBSERVATION_NAMES.index("stage_left"), OBSERVATION_NAMES.index("stage_right")]


def observations_of_real_fights(count=64, steps=40):
    """What fighters see in fights of random play, both seats, most of them on the stage."""
    envs = FightVecEnv(count, load_config("default"), opponent="random", opponent_seed=3)
    envs.seed(3)
    observations = envs.reset()
    rng = np.random.default_rng(3)
    for _ in range(steps):
        observations, *_ = envs.step(rng.integers(len(Action), size=count))
    return observations


def one_move_style(styles, move, attack=0.0):
    styles.moves = np.zeros((PHASES, MOVES))
    styles.moves[:, move] = 1.0
    styles.attack = np.full(PHASES, attack)


def test_it_plays_the_style_drawn_forward_meaning_toward_the_opponent():
    observations = observations_of_real_fights()
    on_stage = (observations[:, EDGES] >= 0).all(axis=1)
    toward = np.where(observations[:, X] > 0, Action.RIGHT, Action.LEFT)
    away = np.where(observations[:, X] > 0, Action.LEFT, Action.RIGHT)
    styles = RandomStyles(0)
    one_move_style(styles, 0)  # forward
    assert (styles.act(observations)[on_stage] == toward[on_stage]).all()
    one_move_style(styles, 1)  # back
    assert (styles.act(observations)[on_stage] == away[on_stage]).all()
    one_move_style(styles, 5)  # crouch
    assert (styles.act(observations)[on_stage] == Action.DOWN).all()
    one_move_style(styles, 6, attack=1.0)  # block, but always attack when in reach
    reach = observations[:, OBSERVATION_NAMES.index("self_kick_reach")] != 0
    actions = styles.act(observations)
    assert np.isin(actions[on_stage & reach], [Action.PUNCH, Action.KICK]).all()
    assert (actions[on_stage & ~reach] == Action.BLOCK).all()
    off = observations[:8].copy()
    off[:, EDGES[0]] = -0.05  # past the stage's left edge: it heads back right, whatever its style
    assert np.isin(styles.act(off), [Action.RIGHT, Action.JUMP_RIGHT]).all()


def test_styles_lean_on_different_moves_and_redraw_draws_a_new_one():
    styles = RandomStyles(1)
    leaning = set()
    for _ in range(40):
        before = styles.moves.copy()
        styles.redraw()
        assert not np.array_equal(before, styles.moves)
        assert styles.moves.sum(axis=1) == pytest.approx(np.ones(PHASES))
        leaning.update(styles.moves.argmax(axis=1).tolist())
    assert leaning == set(range(MOVES))  # every move is some style's favourite


def test_the_same_seed_and_state_give_the_same_actions():
    observations = observations_of_real_fights(count=16, steps=10)
    first, second = RandomStyles(5), RandomStyles(5)
    assert [first.act(observations).tolist() for _ in range(5)] == [
        second.act(observations).tolist() for _ in range(5)
    ]
    first.redraw()
    saved = first.state()
    later = [first.act(observations).tolist() for _ in range(5)]
    restored = RandomStyles(99)
    restored.load_state(saved)
    assert [restored.act(observations).tolist() for _ in range(5)] == later
    assert RandomStyles(6).act(observations).tolist() != RandomStyles(5).act(observations).tolist()
