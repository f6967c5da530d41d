"""Shared by the RLlib tests: a local Ray whose files live under the test's tmp folder, and a
check that no Ray process outlives its test."""

import os
import time
from pathlib import Path

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


@pytest.fixture(scope="module")
def local_ray(tmp_path_factory):
    """One local Ray (2 CPUs) for this module's tests; its files under the test's tmp folder."""
    ray = pytest.importorskip("ray")
    temp_dir = tmp_path_factory.mktemp("ray")
    ray.init(num_cpus=2, include_dashboard=False, _temp_dir=str(temp_dir), logging_level="ERROR")
    assert ray_processes(temp_dir), "Ray's processes name their temp dir: the check below can fail"
    yield temp_dir
    ray.shutdown()
    assert_no_ray_left(temp_dir)


@pytest.fixture
def no_ray_left():
    """`assert_no_ray_left`, for tests that start their own Ray."""
    return assert_no_ray_left
