"""`bench.recurrent_cost` prices an LSTM learner beside the league's MLP (no timing thresholds)."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import pytest

pytest.importorskip("stable_baselines3")
pytest.importorskip("sb3_contrib")

from bench import recurrent_cost  # noqa: E402
from tests.agents.test_bad_input import usage_error  # noqa: E402

REPO = Path(__file__).resolve().parents[2]


def bench(*args: str) -> subprocess.CompletedProcess:
    return subprocess.run(
        [sys.executable, "-m", "bench.recurrent_cost", *args],
        cwd=REPO,
        capture_output=True,
        text=True,
        timeout=600,
        check=False,
    )


def test_quick_run_reports_both_learners_with_the_replaced_settings():
    result = bench("--quick", "--json", "--n-epochs", "2", "--batch-size", "512")
    assert result.returncode == 0, result.stdout + result.stderr
    report = json.loads(result.stdout)
    (measured,) = report["rows"]
    assert measured["name"] == "learn() vs rush, 64 fights, 2 epochs"
    assert measured["batch_size"] == 512
    assert measured["ours"] > 0 and measured["reference"] > 0
    assert measured["ratio"] == pytest.approx(measured["ours"] / measured["reference"])
    assert report["machine"]["sb3_contrib"]


@pytest.mark.parametrize("flag", ["--n-epochs", "--rounds", "--steps", "--batch-size"])
def test_a_count_below_one_is_refused_by_its_flag(flag, capsys):
    error = usage_error(recurrent_cost.main, [flag, "0"], capsys)  # in this process: no torch again
    assert flag in error and "0" in error


def test_a_minibatch_of_one_is_refused_with_ppos_bound(capsys):
    error = usage_error(recurrent_cost.main, ["--batch-size", "1"], capsys)
    assert "batch_size = 1 is not allowed: must be >= 2" in error
