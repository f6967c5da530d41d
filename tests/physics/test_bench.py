"""`python -m bench.physics --quick` runs and reports sane numbers (no timing thresholds)."""

from __future__ import annotations

import json
import math
import subprocess
import sys
from pathlib import Path

REPO = Path(__file__).resolve().parents[2]


def test_quick_benchmark_prints_a_table_and_writes_json(tmp_path):
    out = tmp_path / "physics.json"
    result = subprocess.run(
        [sys.executable, "-m", "bench.physics", "--quick", "--json", str(out)],
        cwd=REPO,
        capture_output=True,
        text=True,
        timeout=300,
        check=False,
    )
    assert result.returncode == 0, result.stdout + result.stderr

    lines = result.stdout.splitlines()
    assert lines[0].split()[:3] == ["n", "steps/s", "checks/s"]
    table = {int(line.split()[0]): line.split() for line in lines[2:] if line.split()[0].isdigit()}
    assert sorted(table) == [10, 100, 1000]

    report = json.loads(out.read_text())
    assert report["quick"] is True
    rows = {row["n"]: row for row in report["rows"]}
    assert sorted(rows) == [10, 100, 1000]
    for n, row in rows.items():
        assert row["all_pairs"] == n * (n - 1) // 2
        assert 0 <= row["candidate_pairs"] <= row["all_pairs"]
        assert row["ratio"] == row["candidate_pairs"] / row["all_pairs"]
        assert row["steps"] > 0
        for rate in (row["steps_per_s"], row["checks_per_s"]):
            assert rate > 0.0 and math.isfinite(rate)
        assert int(table[n][3]) == row["candidate_pairs"]  # the table shows the same numbers
        assert int(table[n][4]) == row["all_pairs"]
    # the broad phase is what keeps 1000 sprites tractable
    assert rows[1000]["candidate_pairs"] < 0.01 * rows[1000]["all_pairs"]


def test_benchmark_rejects_bad_sizes():
    result = subprocess.run(
        [sys.executable, "-m", "bench.physics", "--quick", "--sizes", "1"],
        cwd=REPO,
        capture_output=True,
        text=True,
        timeout=60,
        check=False,
    )
    assert result.returncode == 2
    assert "--sizes" in result.stderr
