"""A simulated two-node Ray cluster in-process: env runners on both nodes sample, the run's
checkpoint loads, and no Ray process is left. Skipped without the `rllib` extra."""

import numpy as np
import pytest

ray = pytest.importorskip("ray")
pytest.importorskip("ray.rllib")

from agents.rllib_config import load_rllib_config  # noqa: E402
from agents.rllib_export import export_checkpoint  # noqa: E402
from agents.train_rllib import CHECKPOINT, train  # noqa: E402
from vooga_env.game.observations import OBSERVATION_SIZE  # noqa: E402
from vooga_env.policies import make_policy  # noqa: E402


@pytest.mark.slow  # 25-40 s on 2 shared cores: two raylets, two env-runner processes
def test_two_node_cluster_samples_on_both_nodes(tmp_path_factory, tmp_path, no_ray_left):
    from ray.cluster_utils import Cluster

    temp_dir = tmp_path_factory.mktemp("cluster")
    node = {"num_cpus": 1, "temp_dir": str(temp_dir), "include_dashboard": False}
    cluster = Cluster(initialize_head=True, head_node_args=node)
    try:
        cluster.add_node(**node)
        ray.init(address=cluster.address, logging_level="ERROR")
        node_ids = {n["NodeID"] for n in ray.nodes() if n["Alive"]}
        assert len(node_ids) == 2
        config = load_rllib_config("rllib_smoke", iterations=1, env_runners=2, envs_per_runner=1)
        state = train(config, tmp_path, echo=False)
    finally:
        ray.shutdown()
        cluster.shutdown()
    assert set(state["nodes"]) == node_ids
    assert all(steps > 0 for steps in state["nodes"].values())
    path = export_checkpoint(tmp_path / CHECKPOINT, "main", tmp_path / "main_from_checkpoint.npz")
    assert make_policy(path).act(np.zeros(OBSERVATION_SIZE)) in range(10)
    no_ray_left(temp_dir)
