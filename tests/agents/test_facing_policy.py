"""A network that plays facing its opponent (`frame = "opponent"`): SB3's FacingPolicy, its numpy
copy, and the configs that ask for it."""

from __future__ import annotations

import numpy as np
import pytest
import torch

pytest.importorskip("stable_baselines3")

from stable_baselines3 import PPO  # noqa: E402

from agents.league import load_league_config, train_league  # noqa: E402
from agents.train_config import load_train_config  # noqa: E402
from vooga_env.envs.sb3 import FightVecEnv  # noqa: E402
from vooga_env.game.config import ConfigError  # noqa: E402
from vooga_env.game.facing import MIRROR_INDEX, MIRROR_SIGN, OPPONENT_X, TURNED_ACTIONS  # noqa: E402
from vooga_env.policies.facing_policy import FacingPolicy  # noqa: E402
from vooga_env.policies.models import FrozenPolicy, load_model  # noqa: E402


@pytest.fixture(scope="module")
def saved(tmp_path_factory):
    """A FacingPolicy model trained a few rollouts against rush, saved and loaded back."""
    model = PPO(
        FacingPolicy,
        FightVecEnv(8, "default", opponent="rush", seat="alternate"),
        n_steps=32,
        batch_size=128,
        n_epochs=2,
        seed=0,
        device="cpu",
    )
    model.learn(512)
    path = tmp_path_factory.mktemp("facing") / "model.zip"
    model.save(path)
    return load_model(path)


@pytest.fixture(scope="module")
def observations():
    """Observations on both sides of the opponent, and their mirror images."""
    rows = np.random.default_rng(0).uniform(-1.5, 1.5, (400, 41)).astype(np.float32)
    rows[rows[:, OPPONENT_X] == 0, OPPONENT_X] = 0.5
    return rows, rows[:, MIRROR_INDEX] * MIRROR_SIGN


def test_a_facing_model_plays_a_fight_and_its_mirror_image_alike(saved, observations):
    assert isinstance(saved.policy, FacingPolicy)
    plain, mirror = observations
    assert np.any(plain[:, OPPONENT_X] < 0) and np.any(plain[:, OPPONENT_X] > 0)
    with torch.no_grad():
        probs = [
            saved.policy.get_distribution(torch.as_tensor(rows)).distribution.probs.numpy()
            for rows in (plain, mirror)
        ]
        values = [saved.policy.predict_values(torch.as_tensor(rows)) for rows in (plain, mirror)]
    np.testing.assert_allclose(probs[1], probs[0][:, TURNED_ACTIONS], atol=1e-6)
    np.testing.assert_allclose(values[1], values[0], atol=1e-6)
    actions, _ = saved.predict(mirror, deterministic=True)
    assert np.array_equal(actions, TURNED_ACTIONS[saved.predict(plain, deterministic=True)[0]])


def test_its_numpy_copy_keeps_the_frame_and_picks_the_same_actions(saved, observations):
    frozen = FrozenPolicy(saved)
    assert frozen.frame == "opponent"
    plain, mirror = observations
    for rows in (plain, mirror):
        with torch.no_grad():
            logits = saved.policy.get_distribution(torch.as_tensor(rows)).distribution.logits
        own = frozen.logits(rows)
        own -= np.log(np.exp(own).sum(axis=1, keepdims=True))
        np.testing.assert_allclose(own, logits.numpy(), atol=1e-5)
        assert np.array_equal(frozen.act_batch(rows), saved.predict(rows, deterministic=True)[0])
        assert frozen.act(rows[0]) == frozen.act_batch(rows[:1])[0]


def test_a_seat_model_is_copied_as_one():
    model = PPO(
        "MlpPolicy",
        FightVecEnv(2, "default", opponent="idle"),
        n_steps=8,
        batch_size=16,
        device="cpu",
    )
    assert FrozenPolicy(model).frame == "seat"


def test_the_league_trains_a_facing_learner_when_its_config_asks(tmp_path):
    config = load_league_config("smoke", total_timesteps=1024)
    assert config.ppo.frame == "opponent"
    final = load_model(train_league(config, tmp_path, progress=False))
    assert isinstance(final.policy, FacingPolicy)
    snapshot = load_model(tmp_path / "snapshots" / "snapshot_1024.zip")
    assert FrozenPolicy(snapshot, "snapshot").frame == "opponent"  # the pool plays it facing too


@pytest.mark.parametrize(
    ("text", "message"),
    [
        ('[ppo]\nframe = "sideways"\n', "frame = 'sideways' is not allowed: one of seat, opponent"),
        (
            'obs_type = "pixels"\n[ppo]\nframe = "opponent"\n',
            "ppo.frame = 'opponent' is not allowed: 'seat' with obs_type = 'pixels'",
        ),
    ],
)
def test_a_bad_frame_is_refused_by_name(tmp_path, text, message):
    path = tmp_path / "bad.toml"
    path.write_text(text)
    with pytest.raises(ConfigError, match=message):
        load_train_config(path)


def test_the_rows_asked_take_the_argmax_and_the_others_sample(saved, observations):
    plain, _ = observations
    obs = torch.as_tensor(plain)
    rows = torch.arange(len(plain)) % 2 == 0
    saved.policy.argmax_rows = rows
    try:
        with torch.no_grad():
            actions, _, log_probs = saved.policy(obs)
            distribution = saved.policy.get_distribution(obs)
    finally:
        saved.policy.argmax_rows = None
    mode = distribution.mode()
    assert torch.equal(actions[rows], mode[rows])
    assert not torch.equal(actions[~rows], mode[~rows])  # a barely trained network samples
    torch.testing.assert_close(log_probs, distribution.log_prob(actions))
