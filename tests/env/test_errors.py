"""Bad input gets a clear error naming the field, the value and what is allowed."""

import gymnasium
import numpy as np
import pytest

import vooga_env
from vooga_env.game.config import ConfigError, load_config


def test_unknown_config_key_names_file_and_key(tmp_path):
    path = tmp_path / "typo.toml"
    path.write_text("[physics]\ngravty = 0.003\n")
    with pytest.raises(ConfigError, match=r"typo\.toml.*'physics\.gravty'.*gravity"):
        load_config(path)


def test_wrong_type_names_key_and_value(tmp_path):
    path = tmp_path / "bad.toml"
    path.write_text('[fighter]\nmass = "heavy"\n')
    with pytest.raises(ConfigError, match=r"bad\.toml.*fighter\.mass.*'heavy'"):
        load_config(path)


@pytest.mark.parametrize(
    ("overrides", "key"),
    [
        ({"arena": {"spawns": [40.0, 520.0]}}, r"arena\.spawns\[0\]"),
        ({"arena": {"blocks": [{"x": 0, "y": 300, "width": 800, "height": 40}]}}, r"arena\.blocks"),
        ({"arena": {"blocks": [{"x": 100, "y": 300, "width": 900, "height": 40}]}}, r"blocks\[0\]"),
        ({"fighter": {"height": 400.0}}, "too tall"),
        ({"max_cycles": 0}, "max_cycles"),
        ({"collisions": {"enemy": "hug"}}, r"collisions\.enemy.*push"),
        ({"fighter": {"crouch_height": 90.0}}, "crouch_height"),
    ],
)
def test_impossible_configs_are_refused(overrides, key):
    with pytest.raises(ConfigError, match=key):
        vooga_env.parallel_env(**overrides)


def test_unknown_config_name_lists_the_known_ones():
    with pytest.raises(ConfigError, match="default.*water"):
        load_config("nope")


@pytest.mark.parametrize(
    ("action", "error", "match"),
    [
        (10, ValueError, "fighter_0.*0..9.*10"),
        (-1, ValueError, "-1"),
        (1.5, TypeError, "1.5"),
        ("kick", TypeError, "kick"),
        (True, TypeError, "True"),
    ],
)
def test_wrong_actions(action, error, match):
    env = vooga_env.parallel_env()
    env.reset(seed=0)
    with pytest.raises(error, match=match):
        env.step({"fighter_0": action, "fighter_1": 0})


def test_numpy_actions_are_accepted():
    env = vooga_env.parallel_env()
    env.reset(seed=0)
    env.step({"fighter_0": np.int32(3), "fighter_1": np.array(2)})


def test_missing_and_unknown_agents():
    env = vooga_env.parallel_env()
    env.reset(seed=0)
    with pytest.raises(KeyError, match="fighter_1"):
        env.step({"fighter_0": 0})
    with pytest.raises(KeyError, match="fighter_9"):
        env.step({"fighter_0": 0, "fighter_1": 0, "fighter_9": 0})


@pytest.mark.parametrize("seed", [-1, 1.5, "7"])
def test_bad_seed(seed):
    with pytest.raises(ValueError, match="seed"):
        vooga_env.parallel_env().reset(seed=seed)


def test_step_after_the_end_needs_a_reset():
    env = vooga_env.parallel_env(max_cycles=2)
    env.reset(seed=0)
    env.step({"fighter_0": 0, "fighter_1": 0})
    env.step({"fighter_0": 0, "fighter_1": 0})
    with pytest.raises(RuntimeError, match="reset"):
        env.step({"fighter_0": 0, "fighter_1": 0})


def test_unknown_opponent_lists_the_known_ones():
    with pytest.raises(ValueError, match="rush.*turtle"):
        gymnasium.make("vooga_env/Fight-v0", opponent="ninja")


def test_bad_render_mode():
    with pytest.raises(ValueError, match="render_mode.*'ansi'"):
        vooga_env.parallel_env(render_mode="ansi")
