"""A simulated two-node Ray cluster in-process (`conftest.ray_cluster`): env runners on both
nodes sample, the run's checkpoint loads, and no Ray process is left (the fixture's teardown).
Skipped without the `rllib` extra."""

import numpy as np
import pytest

ray = pytest.importorskip("ray")
pytest.importorskip("ray.rllib")

from agents.rllib_config import load_rllib_config  # noqa: E402
from agents.train_rllib import train  # noqa: E402
from vooga_env.game.observations import OBSERVATION_SIZE  # noqa: E402
from vooga_env.policies import make_policy  # noqa: E402
from vooga_env.policies.models import load_mlp  # noqa: E402


def test_env_runners_on_both_nodes_sample_and_the_checkpoint_loads(ray_cluster, smoke_run):
    first, second = smoke_run.first, smoke_run.second
    assert set(first["nodes"]) == ray_cluster.node_ids
    assert all(steps > 0 for steps in first["nodes"].values())
    assert second["iteration"] == 2  # restored from the cluster's checkpoint, then trained on
    assert make_policy(smoke_run.first_fighter).act(np.zeros(OBSERVATION_SIZE)) in range(10)


@pytest.mark.slow  # ~25 s on 2 shared cores: two more env-runner processes
def test_a_two_node_run_repeats_with_the_same_seed(ray_cluster, smoke_run, tmp_path):
    """The remote env runners' samples and the opponent draws repeat too (docs/rllib.md says
    what RLlib does not guarantee: a runner past `sample_timeout_s`, a restarted runner)."""
    config = load_rllib_config("rllib_smoke", iterations=1, env_runners=2, envs_per_runner=1)
    again = train(config, tmp_path, echo=False)
    assert again["league"] == smoke_run.first["league"]
    assert again["nodes"] == smoke_run.first["nodes"]
    expected, got = load_mlp(smoke_run.first_fighter), load_mlp(tmp_path / "main.npz")
    observations = np.random.default_rng(0).uniform(-2, 2, (64, OBSERVATION_SIZE))
    assert np.array_equal(expected.logits(observations), got.logits(observations))
