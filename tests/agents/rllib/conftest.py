"""Shared by the RLlib tests: one simulated two-node Ray cluster for the whole folder (its files
in a short folder of its own, no Ray process left when it stops), and the smoke run on it."""

import os
import shutil
import tempfile
import time
from collections.abc import Iterator
from contextlib import contextmanager
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import pytest


def ray_processes(temp_dir: Path) -> list[int]:
    """Ids of live processes whose command line names `temp_dir` (Ray's own, for this test)."""
    found = []
    for entry in Path("/proc").iterdir():
        if entry.name.isdigit():
            try:
                command = (entry / "cmdline").read_bytes()
            except OSError:
                continue
            if str(temp_dir).encode() in command and int(entry.name) != os.getpid():
                found.append(int(entry.name))
    return found


def assert_no_ray_left(temp_dir: Path) -> None:
    """Ray stops its processes asynchronously: give them a few seconds, then none may be left."""
    deadline = time.monotonic() + 15
    while ray_processes(temp_dir) and time.monotonic() < deadline:
        time.sleep(0.2)
    assert ray_processes(temp_dir) == []


@contextmanager
def short_temp_dir() -> Iterator[Path]:
    """A new folder right under /tmp, removed afterwards: Ray's socket paths under it must fit
    AF_UNIX's 107 bytes, which pytest's own tmp folders pass under pytest-xdist (`popen-gw0/`)."""
    folder = Path(tempfile.mkdtemp(prefix="ray", dir="/tmp"))
    try:
        yield folder
    finally:
        shutil.rmtree(folder, ignore_errors=True)


@pytest.fixture
def ray_temp_dir() -> Iterator[Path]:
    """`short_temp_dir`, for a test that starts a Ray of its own."""
    with short_temp_dir() as folder:
        yield folder


@dataclass(frozen=True)
class RayCluster:
    temp_dir: Path
    node_ids: frozenset[str]


@pytest.fixture(scope="package")
def ray_cluster():
    """Two Ray nodes of one CPU each in this process (`ray.cluster_utils.Cluster`), shared by
    every test here: starting Ray is most of what a test on it costs."""
    ray = pytest.importorskip("ray")
    from ray.cluster_utils import Cluster

    with short_temp_dir() as temp_dir, pytest.MonkeyPatch.context() as patch:
        (temp_dir / "ray").mkdir()
        node = {"num_cpus": 1, "temp_dir": str(temp_dir / "ray"), "include_dashboard": False}
        patch.setenv("RAY_TMPDIR", str(temp_dir))  # where Cluster writes its address file
        cluster = Cluster()
        try:
            cluster.add_node(**node, no_monitor=True)  # the head; no autoscaler to run
            cluster.add_node(**node)
            ray.init(address=cluster.address, logging_level="ERROR")
            assert ray_processes(temp_dir), "Ray's processes name their temp dir: the check fails"
            alive = frozenset(n["NodeID"] for n in ray.nodes() if n["Alive"])
            assert len(alive) == 2
            yield RayCluster(temp_dir, alive)
        finally:
            ray.shutdown()
            cluster.shutdown()
        assert_no_ray_left(temp_dir)


@dataclass(frozen=True)
class SmokeRun:
    folder: Path
    first: dict[str, Any]  # iteration 1: an env runner on each node
    second: dict[str, Any]  # iteration 2, resumed in the driver (0 env runners)
    first_fighter: Path  # main.npz after iteration 1


@pytest.fixture(scope="package")
def smoke_run(ray_cluster, tmp_path_factory):
    """Iteration 1 with an env runner on each node, then `--resume` for iteration 2 with the
    driver sampling: the checkpoint the cluster wrote must load into another layout."""
    from agents.rllib_config import load_rllib_config
    from agents.train_rllib import train

    folder = tmp_path_factory.mktemp("smoke")
    on_both = load_rllib_config("rllib_smoke", iterations=1, env_runners=2, envs_per_runner=1)
    first = train(on_both, folder, echo=False)
    first_fighter = shutil.copy(folder / "main.npz", folder.parent / "main_iteration_1.npz")
    second = train(load_rllib_config("rllib_smoke", iterations=2), folder, resume=True, echo=False)
    return SmokeRun(folder, first, second, Path(first_fighter))


@pytest.fixture
def no_ray_left():
    """`assert_no_ray_left`, for tests that start their own Ray."""
    return assert_no_ray_left
