"""The "engine" and "compiled" backends of FightParallelEnv: the same fight, bit for bit."""

import subprocess
import sys

import numpy as np
import pytest

import vooga_env
from vooga_env.game.rewards import HitAndRingOutReward
from vooga_env.policies import make_policy

pytest.importorskip("numba")

MIXES = (("rush", "turtle"), ("zoner", "edge_guard"), ("random", "rush"), ("random", "random"))


def play_side_by_side(config, steps, seed, **overrides):
    """Both backends, the same seeds and actions; every output compared as it comes.

    Returns how often each event happened, so a caller can check the game covered them.
    """
    engine = vooga_env.parallel_env(config=config, backend="engine", **overrides)
    compiled = vooga_env.parallel_env(config=config, backend="compiled", **overrides)
    assert (engine.backend, compiled.backend) == ("engine", "compiled")
    rng = np.random.default_rng(seed)
    seen = dict.fromkeys(("hits_landed", "hits_blocked", "rung_out", "knocked_out"), 0)
    seen.update(truncated=0, episodes=0)
    episode_seed = seed
    mix = 0
    for step in range(steps):
        if step == 0 or not engine.agents:
            # every third episode reseeds; the others continue each env's own stream
            reseed = episode_seed if seen["episodes"] % 3 == 0 else None
            episode_seed += 1
            results = [env.reset(seed=reseed) for env in (engine, compiled)]
            assert_same(*results)
            policies = [make_policy(name, int(rng.integers(1000))) for name in MIXES[mix]]
            mix = (mix + 1) % len(MIXES)
            observations = results[0][0]
            seen["episodes"] += 1
        actions = {
            agent: policy.act(observations[agent])
            for agent, policy in zip(engine.possible_agents, policies)
        }
        results = [env.step(actions) for env in (engine, compiled)]
        assert_same(*results)
        assert engine.fighter_status() == compiled.fighter_status()
        assert engine.state().tobytes() == compiled.state().tobytes()
        observations, _, _, truncations, infos = results[0]
        for info in infos.values():
            for key in ("hits_landed", "hits_blocked", "rung_out", "knocked_out"):
                seen[key] += int(info[key])
        seen["truncated"] += int(truncations["fighter_0"])
    return seen


def assert_same(first, second):
    """Equal dicts of arrays (bit for bit) or of plain values (same type and value)."""
    for part_one, part_two in zip(first, second, strict=True):
        assert part_one.keys() == part_two.keys()
        for key, one in part_one.items():
            two = part_two[key]
            if isinstance(one, np.ndarray):
                assert one.dtype == two.dtype and one.tobytes() == two.tobytes(), key
            elif isinstance(one, dict):
                assert one == two, key
                assert [type(v) for v in one.values()] == [type(v) for v in two.values()], key
            else:
                assert type(one) is type(two) and one == two, key


def test_backends_agree_over_3000_steps_of_hits_blocks_ring_outs_kos_and_time_outs():
    seen = play_side_by_side("default", 3000, seed=11, max_cycles=150, fighter={"health": 30.0})
    assert seen["episodes"] > 20
    assert all(seen[key] > 0 for key in seen), seen


@pytest.mark.parametrize("config", ["water", "platforms", "small"])
def test_backends_agree_on_every_shipped_stage(config):
    seen = play_side_by_side(config, 800, seed=3, max_cycles=120, stocks=2)
    assert seen["hits_landed"] > 0 and seen["episodes"] > 3


def test_auto_picks_the_compiled_backend_when_it_can():
    assert vooga_env.parallel_env().backend == "compiled"
    assert vooga_env.env().unwrapped.backend == "compiled"


@pytest.mark.parametrize(
    "kwargs, reason",
    [
        (dict(render_mode="rgb_array"), "render_mode"),
        (dict(reward_fn=lambda fight, events: (0.0, 0.0)), "reward_fn"),
        (dict(collisions={"enemy": "momentum"}), "collisions.enemy"),
    ],
)
def test_what_the_compiled_backend_cannot_run_falls_back_or_says_why(kwargs, reason):
    assert vooga_env.parallel_env(**kwargs).backend == "engine"
    with pytest.raises(ValueError, match=reason):
        vooga_env.parallel_env(backend="compiled", **kwargs)


def test_the_default_reward_function_runs_compiled_only_with_the_configs_weights():
    config = vooga_env.load_config("default")
    same = HitAndRingOutReward(config.rewards)
    assert vooga_env.parallel_env(reward_fn=same).backend == "compiled"
    other = HitAndRingOutReward(vooga_env.load_config("default", rewards={"ko": 1.0}).rewards)
    assert vooga_env.parallel_env(reward_fn=other).backend == "engine"


def test_an_unknown_backend_names_the_allowed_ones():
    with pytest.raises(ValueError, match="backend = 'gpu'.*auto, engine, compiled"):
        vooga_env.parallel_env(backend="gpu")


def test_the_compiled_backend_says_how_to_reach_the_engine_sprites():
    with pytest.raises(AttributeError, match="backend='engine'"):
        getattr(vooga_env.parallel_env(backend="compiled"), "fight")  # noqa: B009


def test_without_numba_auto_runs_the_engine_and_compiled_says_what_to_install():
    code = """
import sys
sys.modules["numba"] = None  # as if it were not installed
import vooga_env
assert vooga_env.parallel_env().backend == "engine"
try:
    vooga_env.parallel_env(backend="compiled")
except ValueError as error:
    assert "numba is not installed" in str(error), error
else:
    raise AssertionError("backend='compiled' ran without numba")
"""
    subprocess.run([sys.executable, "-c", code], check=True)


def test_the_single_agent_env_takes_the_backend_and_plays_the_same_game():
    import gymnasium

    games = []
    for backend in ("engine", "compiled"):
        env = gymnasium.make("vooga_env/Fight-v0", opponent="rush", seat="random", backend=backend)
        assert env.unwrapped.fight_env.backend == backend
        observation, _ = env.reset(seed=4)
        trace = [observation.tobytes()]
        for step in range(300):
            observation, reward, terminated, truncated, info = env.step(step % 10)
            trace.append((observation.tobytes(), reward, terminated, truncated, info))
            if terminated or truncated:
                trace.append(env.reset()[0].tobytes())
        games.append(trace)
    assert games[0] == games[1]
