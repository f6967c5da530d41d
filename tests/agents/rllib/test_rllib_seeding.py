"""`--seed` repeats an RLlib run: the same seed, the same samples, the same trained fighter.
docs/rllib.md says what RLlib itself does not guarantee. Skipped without the `rllib` extra."""

import json
from types import SimpleNamespace

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

ray = pytest.importorskip("ray")
pytest.importorskip("ray.rllib")

from ray.rllib.env.env_context import EnvContext  # noqa: E402

from agents.rllib_config import LeagueConfig, load_rllib_config  # noqa: E402
from agents.rllib_env import FightMultiAgentEnv, fight_seed  # noqa: E402
from agents.rllib_league import DRAW, MAIN, League, LeagueCallbacks  # noqa: E402
from agents.train_rllib import PROGRESS_FILE, train  # noqa: E402
from vooga_env.envs.parallel import AGENTS  # noqa: E402

TIMINGS = ("seconds", "env_steps_per_s", "env_step_ms", "inference_ms", "connectors_ms")


def progress(folder):
    lines = (folder / PROGRESS_FILE).read_text().splitlines()
    return [{k: v for k, v in json.loads(line).items() if k not in TIMINGS} for line in lines]


def test_the_same_seed_repeats_a_run(ray_cluster, tmp_path):
    """Two fresh runs, the driver sampling: the same games and bit-identical weights."""
    config = load_rllib_config("rllib_smoke", iterations=1, seed=7)
    for name in ("a", "b"):
        train(config, tmp_path / name, echo=False)
    assert progress(tmp_path / "a") == progress(tmp_path / "b")
    a, b = np.load(tmp_path / "a" / "main.npz"), np.load(tmp_path / "b" / "main.npz")
    assert a.files == b.files
    assert all(np.array_equal(a[key], b[key]) for key in a.files)


def episode(key=None):
    """What the mapping reads of an RLlib episode."""
    return SimpleNamespace(id_="4f1d", custom_data={} if key is None else {DRAW: key})


@given(seed=st.integers(0, 2**32 - 1), key=st.tuples(*[st.integers(0, 10**6)] * 3))
def test_an_episodes_draw_depends_on_the_seed_and_its_key_only(seed, key):
    mapping = League(LeagueConfig(scripted=("idle", "rush", "zoner"))).mapping(seed)
    modules = [mapping(agent, episode(key)) for agent in AGENTS]
    assert sorted(modules, key=lambda m: m != MAIN)[0] == MAIN  # one seat is main's
    assert modules == [mapping(agent, episode(key)) for agent in AGENTS]


def test_draws_cover_both_seats_and_the_whole_pool():
    mapping = League(LeagueConfig(scripted=("idle", "rush", "zoner"))).mapping(0)
    draws = [[mapping(agent, episode((0, 0, n))) for agent in AGENTS] for n in range(200)]
    assert {modules.index(MAIN) for modules in draws} == {0, 1}
    assert {m for modules in draws for m in modules} == {MAIN, "idle", "rush", "zoner"}


def test_episodes_are_keyed_by_runner_vector_index_and_number():
    callbacks, runner = LeagueCallbacks(), SimpleNamespace(worker_index=3)
    episodes = [episode() for _ in range(3)]
    for index, each in zip((0, 1, 0), episodes):
        callbacks.on_episode_created(episode=each, env_runner=runner, env_index=index)
    assert [e.custom_data[DRAW] for e in episodes] == [(3, 0, 0), (3, 1, 0), (3, 0, 1)]


@given(run_seed=st.integers(0, 2**31))
def test_every_runner_and_vector_index_gets_a_stream_of_its_own(run_seed):
    """RLlib resets env i of runner w with run_seed + w + i: the sums repeat, the streams not."""
    seeds = {fight_seed(run_seed, w, run_seed + w + i) for w in range(4) for i in range(4)}
    assert len(seeds) == 16


def test_runners_given_the_same_reset_seed_fight_apart():
    """The default fight jitters the spawns: another runner, another fight; the same, the same."""
    one, two = (
        FightMultiAgentEnv(
            EnvContext({"fight": "default", "backend": "engine", "seed": 5}, worker_index=w)
        )
        for w in (1, 2)
    )
    first, again, other = one.reset(seed=11)[0], one.reset(seed=11)[0], two.reset(seed=11)[0]
    assert all(np.array_equal(first[a], again[a]) for a in AGENTS)
    assert not all(np.array_equal(first[a], other[a]) for a in AGENTS)
