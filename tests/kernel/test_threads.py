"""The batched engine leaves a trainer's thread settings alone, even when it steps on threads."""

import subprocess
import sys

import pytest

pytest.importorskip("torch")

# A fresh process: numba's thread pool starts once per process, and whatever another test
# started already would hide the effect.
SCRIPT = """
import numpy as np, torch
torch.set_num_threads(1)
from vooga_env.kernel import VectorFight
for threads in (1, 2):
    fights = VectorFight(64, threads=threads)
    fights.reset(seed=0)
    for _ in range(3):
        fights.step(np.zeros((64, 2), dtype=np.int64))
import numba
print(torch.get_num_threads(), numba.threading_layer())
"""


def test_stepping_on_two_threads_leaves_torch_on_one():
    result = subprocess.run(
        [sys.executable, "-c", SCRIPT], capture_output=True, text=True, timeout=300, check=True
    )
    torch_threads, layer = result.stdout.split()
    assert torch_threads == "1"
    assert layer == "workqueue"
