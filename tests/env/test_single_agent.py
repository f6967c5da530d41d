"""The Gymnasium face: registered ids, opponents of every kind, seats."""

import gymnasium
import numpy as np
import pytest

import vooga_env
from vooga_env.game.actions import Action


@pytest.mark.parametrize(("env_id", "config"), sorted(vooga_env.GYM_IDS.items()))
def test_registered_ids_use_their_config(env_id, config):
    env = gymnasium.make(env_id)
    assert env.unwrapped.config.name == config


class Charger:
    def predict(self, observation, state=None, episode_start=None, deterministic=True):
        return np.array(Action.RIGHT), state


@pytest.mark.parametrize("opponent", ["idle", lambda obs: Action.RIGHT, Charger()])
def test_any_kind_of_opponent(opponent):
    env = gymnasium.make("vooga_env/Fight-v0", opponent=opponent)
    env.reset(seed=0)
    _, _, _, _, info = env.step(Action.IDLE)
    expected = Action.IDLE if opponent == "idle" else Action.RIGHT
    assert info["opponent_action"] == expected


def test_the_same_seed_gives_the_same_episode_including_the_opponent():
    def episode():
        env = gymnasium.make("vooga_env/Fight-v0", opponent="random", seat="random")
        obs, info = env.reset(seed=11)
        trace = [obs.tobytes(), info["seat"]]
        for _ in range(200):
            obs, reward, terminated, truncated, info = env.step(Action.PUNCH)
            trace += [obs.tobytes(), reward, info["opponent_action"]]
            if terminated or truncated:
                break
        return trace

    assert episode() == episode()


def test_random_seat_uses_both_sides():
    env = gymnasium.make("vooga_env/Fight-v0", seat="random")
    seats = {env.reset(seed=seed)[1]["seat"] for seed in range(20)}
    assert seats == {0, 1}


def test_bad_seat():
    with pytest.raises(ValueError, match="seat.*2"):
        gymnasium.make("vooga_env/Fight-v0", seat=2)
