"""Env tests render headless."""

import os

os.environ.setdefault("SDL_VIDEODRIVER", "dummy")
os.environ.setdefault("SDL_AUDIODRIVER", "dummy")

import pytest  # noqa: E402


@pytest.fixture(params=["engine", "compiled"])
def backend(request):
    """Each backend of FightParallelEnv in turn (the compiled one needs numba)."""
    if request.param == "compiled":
        pytest.importorskip("numba")
    return request.param
