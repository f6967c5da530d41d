"""The single env still plays the recorded reference games bit for bit (see reference.py)."""

from __future__ import annotations

import numpy as np
import pytest

from tests.kernel.reference import SCENARIOS, load, record, summary


def assert_identical(got: dict, expected: dict) -> None:
    assert got.keys() == expected.keys()
    for key, value in expected.items():
        assert got[key].dtype == value.dtype, key
        assert got[key].shape == value.shape, key
        # bytes, not values: -0.0 and 0.0 differ, and so would a float that moved by one ulp
        if got[key].tobytes() != value.tobytes():
            diff = np.argwhere(got[key] != value)
            raise AssertionError(f"{key} differs first at index {diff[0] if len(diff) else '?'}")


@pytest.mark.parametrize("scenario", SCENARIOS, ids=lambda scenario: scenario.name)
def test_single_env_replays_the_reference_bit_for_bit(scenario):
    expected = load(scenario)
    got = record(scenario, len(expected["actions"]), actions=expected["actions"])
    assert_identical(got, expected)


def test_the_references_hold_every_event():
    total = {}
    for scenario in SCENARIOS:
        for key, count in summary(load(scenario)).items():
            total[key] = total.get(key, 0) + count
    assert all(count > 0 for count in total.values()), total
