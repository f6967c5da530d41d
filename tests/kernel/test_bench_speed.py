"""`python -m bench.speed --quick` runs and reports every comparison (no timing thresholds)."""

from __future__ import annotations

import json
import math
import subprocess
import sys
from pathlib import Path

import pytest

pytest.importorskip("stable_baselines3")

REPO = Path(__file__).resolve().parents[2]


def test_quick_speed_benchmark_prints_tables_and_writes_json(tmp_path):
    out = tmp_path / "speed.json"
    result = subprocess.run(
        [sys.executable, "-m", "bench.speed", "--quick", "--sizes", "1,16", "--json", str(out)],
        cwd=REPO,
        capture_output=True,
        text=True,
        timeout=600,
        check=False,
    )
    assert result.returncode == 0, result.stdout + result.stderr
    report = json.loads(out.read_text())
    assert report["quick"] is True
    names = [row["name"] for row in report["single"]]
    assert names[0].startswith("ParallelEnv.step (default: ")
    assert names[1:] == [
        "AEC env, one cycle (both fighters)",
        "Gymnasium env (vs random)",
        "ParallelEnv.step, backend='engine'",
    ]
    assert {row["n"] for row in report["batched"]} == {1, 16}
    assert {row["threads"] for row in report["batched"]} == {1}  # two only from N = 256
    assert len(report["ppo"]) == 2
    # both backends, then the largest N with both seats and one seat a fight
    assert [row["n"] for row in report["pixels"]] == [1, 1, 16, 16]
    for row in report["single"] + report["batched"] + report["pixels"] + report["ppo"]:
        assert row["ours"] > 0 and row["reference"] > 0 and math.isfinite(row["ratio"])
        assert row["ratio"] == pytest.approx(row["ours"] / row["reference"])  # one round
        assert row["name"] in result.stdout  # the table shows every row
    memory = report["memory"]
    assert 0 < memory["state_bytes_4096"] < 64 * 2**20
    assert memory["peak_rss_bytes"] > memory["state_bytes_4096"]
    assert report["machine"]["python"]


def test_speed_benchmark_rejects_bad_sizes():
    result = subprocess.run(
        [sys.executable, "-m", "bench.speed", "--quick", "--sizes", "0"],
        cwd=REPO,
        capture_output=True,
        text=True,
        timeout=120,
        check=False,
    )
    assert result.returncode == 2
    assert "--sizes" in result.stderr
