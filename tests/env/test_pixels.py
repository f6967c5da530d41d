"""Pixel observations: the same images from numpy and numba, mirrored seats, what is drawn."""

import subprocess
import sys

import gymnasium
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import vooga_env
from vooga_env.game import pixels as px
from vooga_env.game.pixel_formulas import HUD_ROWS
from vooga_env.game.pixels import PixelRenderer, PixelSpec
from vooga_env.kernel.vector_fight import VectorFight

CONFIGS = ("default", "water", "platforms", "small")


def random_actions(seed, steps):
    return np.random.default_rng(seed).integers(0, 10, size=(steps, 2))


def assert_same(first, second):
    if isinstance(first, dict):
        assert first.keys() == second.keys()
        for key in first:
            assert_same(first[key], second[key])
    else:
        assert first.dtype == second.dtype and np.array_equal(first, second)


@pytest.mark.parametrize("config", CONFIGS)
@pytest.mark.parametrize(("size", "rgb"), [((84, 84), False), ((40, 96), True)])
def test_the_backends_draw_the_same_images(config, size, rgb):
    kwargs = dict(config=config, obs_type="both", pixel_size=size, pixel_rgb=rgb, max_cycles=120)
    engine = vooga_env.parallel_env(backend="engine", **kwargs)
    compiled = vooga_env.parallel_env(backend="compiled", **kwargs)
    hitbox = PixelSpec(*size, rgb).palette[px.HITBOX]
    drew_a_hitbox = False
    for episode in range(2):
        first, _ = engine.reset(seed=episode)
        second, _ = compiled.reset(seed=episode)
        assert_same(first, second)
        for one, two in random_actions(episode, 120):
            actions = {"fighter_0": int(one), "fighter_1": int(two)}
            first, *_ = engine.step(actions)
            second, *_ = compiled.step(actions)
            assert_same(first, second)
            image = first["fighter_0"]["pixels"].reshape(*size, -1)
            drew_a_hitbox |= bool((image == hitbox).all(axis=-1).any())
            if not engine.agents:
                break
    assert engine.observation_space("fighter_0").contains(first["fighter_0"])
    assert drew_a_hitbox  # random fighters attack: the comparison covered the hitboxes too


def test_the_batch_draws_each_fights_single_env_images():
    n, steps = 3, 150
    batch = VectorFight(n, obs_type="pixels", max_cycles=40)
    singles = [vooga_env.parallel_env(backend="engine", obs_type="pixels", max_cycles=40)
               for _ in range(n)]  # fmt: skip
    images = batch.reset(seed=7)
    for i, env in enumerate(singles):
        observations, _ = env.reset(seed=7 + i)
        assert np.array_equal(images[i, 0], observations["fighter_0"])
    actions = np.random.default_rng(0).integers(0, 10, size=(steps, n, 2))
    resets = 0
    for step in range(steps):
        images, _, _, _, info = batch.step(actions[step])
        for i, env in enumerate(singles):
            observations, *_ = env.step({"fighter_0": int(actions[step, i, 0]),
                                          "fighter_1": int(actions[step, i, 1])})  # fmt: skip
            if not env.agents:  # the batch reset it in the same step: its last image is final
                row = list(info["done_index"]).index(i)
                assert np.array_equal(info["final_observation"][row, 1], observations["fighter_1"])
                observations, _ = env.reset()
                resets += 1
            assert np.array_equal(images[i, 0], observations["fighter_0"])
            assert np.array_equal(images[i, 1], observations["fighter_1"])
    assert resets >= n  # every fight ended (max_cycles 40) and restarted at least once


@pytest.mark.parametrize("rgb", [False, True])
def test_one_seats_images_are_that_seat_of_both(rgb):
    n, steps = 4, 120
    kwargs = dict(obs_type="pixels", pixel_size=(40, 56), pixel_rgb=rgb, max_cycles=30)
    both = VectorFight(n, **kwargs)
    one = VectorFight(n, pixel_seats="alternate", **kwargs)
    seats = np.arange(n) % 2
    first, second = both.reset(seed=3), one.reset(seed=3)
    assert second.shape == (n, *first.shape[2:])
    assert np.array_equal(first[np.arange(n), seats], second)
    actions = np.random.default_rng(1).integers(0, 10, size=(steps, n, 2))
    ended = 0
    for step in range(steps):
        first, *_, info = both.step(actions[step])
        second, *_, info_one = one.step(actions[step])
        assert np.array_equal(first[np.arange(n), seats], second)
        done = info["done_index"]
        assert np.array_equal(done, info_one["done_index"])
        finals = info["final_observation"][np.arange(done.size), seats[done]]
        assert np.array_equal(finals, info_one["final_observation"])
        ended += done.size
    assert ended >= n  # the final images were compared too


@pytest.mark.parametrize("face", ["sb3", "gymnasium"])
def test_the_one_learner_faces_see_the_learners_seat(face):
    from vooga_env.envs.sb3 import FightVecEnv

    n, kwargs = 3, dict(obs_type="pixels", pixel_size=(32, 48), max_cycles=30)
    if face == "sb3":
        env = FightVecEnv(n, opponent="random", seat="alternate", **kwargs)
        seats, observations = np.arange(n) % 2, env.reset()
    else:
        env = gymnasium.make_vec("vooga_env/Fight-v0", num_envs=n, seat=1, opponent="random",
                                 vectorization_mode="vector_entry_point", **kwargs)  # fmt: skip
        seats, (observations, _) = np.ones(n, dtype=int), env.reset(seed=0)
    fights = env.fights if face == "sb3" else env.unwrapped.fights
    both = np.empty((n, 2, 32, 48, 1), dtype=np.uint8)
    for _ in range(60):
        fights._raster.render(fights.state, np.arange(n), both)
        assert np.array_equal(observations.reshape(n, 32, 48), both[np.arange(n), seats, ..., 0])
        observations, *_ = env.step(np.random.default_rng(0).integers(0, 10, size=n))


# Dyadic values keep x' = width - x - w exact in floating point (as in test_mirror).
coordinate = st.integers(0, 2000).map(lambda n: n / 4)
fighter_state = st.fixed_dictionaries(
    {
        "x": coordinate.filter(lambda x: x <= 760),
        "y": coordinate.filter(lambda y: y <= 440),
        "facing": st.sampled_from([-1.0, 1.0]),
        "health": st.integers(0, 100).map(float),
        "move": st.sampled_from([None, "punch", "kick"]),
        "move_frame": st.integers(0, 12),
        "hitstun": st.integers(0, 3),
        "blocking": st.booleans(),
        "crouching": st.booleans(),
    }
)


def place(fight, fighter, state, mirrored):
    for key, value in state.items():
        setattr(fighter, key, value)
    fighter.height = fighter.config.crouch_height if state["crouching"] else fighter.config.height
    if mirrored:
        fighter.x = fight.config.arena.width - state["x"] - fighter.width
        fighter.facing = -state["facing"]


@settings(max_examples=150, deadline=None)
@given(fighter_state, fighter_state, st.integers(0, 899), st.booleans())
def test_mirroring_the_world_swaps_the_images_exactly(first, second, steps, rgb):
    env = vooga_env.parallel_env(backend="engine")
    env.reset(seed=0)
    fight = env.fight
    fight.steps = steps
    renderer = PixelRenderer(fight, PixelSpec(84, 84, rgb))
    one, two = fight.fighters

    def draw(a, b, mirrored):
        place(fight, one, a, mirrored)
        place(fight, two, b, mirrored)
        for fighter in fight.fighters:
            fight._place_hitbox(fighter)
        return renderer.render()

    before = draw(first, second, mirrored=False)
    after = draw(second, first, mirrored=True)
    assert np.array_equal(after[0], before[1])
    assert np.array_equal(after[1], before[0])


def fighter_zero_sees(changes, observer=0):
    """fighter `observer`'s grayscale image after setting fighter_0's attributes."""
    env = vooga_env.parallel_env(backend="engine", obs_type="pixels")
    env.reset(seed=0)
    fight = env.fight
    for key, value in changes.items():
        setattr(fight.fighters[0], key, value)
    for fighter in fight.fighters:
        fight._place_hitbox(fighter)
    return PixelRenderer(fight, PixelSpec()).render()[observer, :, :, 0]


def test_what_a_fighter_sees_tells_its_states_apart():
    standing = fighter_zero_sees({})
    assert (standing == px.GRAY[px.SELF]).any() and (standing == px.GRAY[px.OPPONENT]).any()
    assert (standing == px.GRAY[px.STAGE]).any() and (standing == px.GRAY[px.EYE]).any()
    them = fighter_zero_sees({}, observer=1)  # fighter_0 is fighter_1's opponent, flipped
    assert (them == px.GRAY[px.SELF]).any() and (them == px.GRAY[px.OPPONENT]).any()
    assert not np.array_equal(them, standing)
    turned = fighter_zero_sees({"facing": -1.0})
    assert not np.array_equal(turned, standing)
    assert (turned == px.GRAY[px.EYE]).sum() == (standing == px.GRAY[px.EYE]).sum()
    crouching = fighter_zero_sees({"crouching": True, "height": 38.0, "y": 360.0 - 38.0})
    assert (crouching == px.GRAY[px.SELF]).sum() < (standing == px.GRAY[px.SELF]).sum()
    blocking = fighter_zero_sees({"blocking": True})
    assert (blocking == px.GRAY[px.SHIELD]).any() and not (standing == px.GRAY[px.SHIELD]).any()
    stunned = fighter_zero_sees({"hitstun": 5})
    arena = stunned[HUD_ROWS:]  # the HUD's first row is the observer's health, in its shade
    assert (arena == px.GRAY[px.SELF_STUNNED]).any() and not (arena == px.GRAY[px.SELF]).any()
    punching = fighter_zero_sees({"move": "punch", "move_frame": 3})
    assert (punching == px.GRAY[px.HITBOX]).any() and not (standing == px.GRAY[px.HITBOX]).any()
    hurt = fighter_zero_sees({"health": 50.0})
    assert (hurt[0] == px.GRAY[px.SELF]).sum() == 42 and (standing[0] == px.GRAY[px.SELF]).all()
    assert (fighter_zero_sees({"health": 50.0}, observer=1)[1] == px.GRAY[px.OPPONENT]).sum() == 42


def test_frame_stacks_hold_the_last_images():
    env = gymnasium.wrappers.FrameStackObservation(
        gymnasium.make("vooga_env/Fight-v0", opponent="rush", obs_type="pixels"), 4
    )
    stacked, _ = env.reset(seed=0)
    assert stacked.shape == (4, 84, 84) and stacked.dtype == np.uint8
    frames = []
    for _ in range(6):
        stacked, *_ = env.step(2)
        frames.append(env.unwrapped.fight_env._renderer.render()[env.unwrapped.seat, :, :, 0])
    assert np.array_equal(stacked, np.stack(frames[-4:]))
    assert not np.array_equal(stacked[0], stacked[-1])  # the fighters moved

    from stable_baselines3.common.vec_env import VecFrameStack

    from vooga_env.envs.sb3 import FightVecEnv

    vec = VecFrameStack(FightVecEnv(2, opponent="rush", obs_type="pixels"), 3)
    stacked = vec.reset()
    assert stacked.shape == (2, 84, 84, 3) and vec.observation_space.shape == (84, 84, 3)
    for _ in range(4):
        stacked, *_ = vec.step(np.array([2, 2]))
    images = vec.venv.fights.observe()["pixels"]  # seat 0's alone: the learner's
    assert np.array_equal(stacked[..., -1], images)


@pytest.mark.parametrize("obs_type", ["vector", "pixels", "both"])
def test_every_face_gives_what_its_space_says(obs_type):
    from vooga_env.envs.sb3 import FightVecEnv

    kwargs = {"obs_type": obs_type, "pixel_size": (48, 64)}
    single = gymnasium.make("vooga_env/Fight-v0", opponent="random", **kwargs)
    observation, _ = single.reset(seed=0)
    assert single.observation_space.contains(observation)
    batch = gymnasium.make_vec("vooga_env/Fight-v0", num_envs=3,
                               vectorization_mode="vector_entry_point", **kwargs)  # fmt: skip
    observations, _ = batch.reset(seed=0)
    assert batch.observation_space.contains(observations)
    sb3 = FightVecEnv(2, **kwargs)  # self-play: 4 slots
    slots = sb3.reset()
    for slot in range(4):
        row = {k: v[slot] for k, v in slots.items()} if obs_type == "both" else slots[slot]
        assert sb3.observation_space.contains(row)
    aec = vooga_env.env(**kwargs)
    aec.reset(seed=0)
    assert aec.observation_space("fighter_1").contains(aec.observe("fighter_1"))
    if obs_type == "pixels":
        assert observation.shape == (48, 64) and observations.shape == (3, 48, 64)
        assert slots.shape == (4, 48, 64, 1)


BAD = [
    ({"obs_type": "rgb"}, "obs_type = 'rgb' is not allowed: one of 'vector', 'pixels', 'both'"),
    ({"obs_type": "pixels", "pixel_size": (8, 84)}, r"pixel_size = \(8, 84\) is not allowed"),
    ({"obs_type": "pixels", "pixel_size": 84}, "pixel_size = 84 is not allowed: .height, width."),
    ({"obs_type": "pixels", "pixel_size": (84.0, 84)}, "two ints in 16..512"),
    ({"obs_type": "both", "pixel_rgb": "yes"}, "pixel_rgb = 'yes' is not allowed"),
]


@pytest.mark.parametrize(
    ("kwargs", "message"),
    [
        ({"pixel_seats": 2}, "pixel_seats = 2 is not allowed: 0, 1, 'alternate' or one seat"),
        ({"pixel_seats": [0, 1, 0]}, r"pixel_seats = \[0, 1, 0\] is not allowed"),
        ({"pixel_seats": "both"}, "pixel_seats = 'both' is not allowed"),
        ({"pixel_seats": True}, "pixel_seats = True is not allowed"),
        ({"pixel_seats": [0.0, 1.0]}, r"pixel_seats = \[0.0, 1.0\] is not allowed"),
        ({"obs_type": "vector", "pixel_seats": 0}, "pixel_seats is for pixel observations"),
    ],
)
def test_bad_pixel_seats_are_refused_by_name(kwargs, message):
    with pytest.raises(ValueError, match=message):
        VectorFight(2, **{"obs_type": "pixels", **kwargs})


@pytest.mark.parametrize(("kwargs", "message"), BAD)
def test_bad_pixel_options_are_refused_by_name_on_every_face(kwargs, message):
    from vooga_env.envs.sb3 import FightVecEnv

    makers = [
        lambda: vooga_env.parallel_env(**kwargs),
        lambda: vooga_env.env(**kwargs),
        lambda: gymnasium.make("vooga_env/Fight-v0", **kwargs),
        lambda: gymnasium.make_vec(
            "vooga_env/Fight-v0", num_envs=2, vectorization_mode="vector_entry_point", **kwargs
        ),  # fmt: skip
        lambda: VectorFight(2, **kwargs),
        lambda: FightVecEnv(2, **kwargs),
    ]
    for make in makers:
        with pytest.raises(ValueError, match=message):
            make()


def test_vector_observations_never_load_the_rasteriser():
    code = (
        "import sys, numpy as np; from vooga_env.kernel.vector_fight import VectorFight; "
        "import vooga_env; env = vooga_env.parallel_env(); env.reset(seed=0); "
        "f = VectorFight(2); f.reset(seed=0); f.step(np.zeros((2, 2), int)); "
        "print('vooga_env.kernel.raster' in sys.modules)"
    )
    result = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, check=True
    )
    assert result.stdout.strip() == "False"
