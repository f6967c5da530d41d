"""`make test` runs the suite on every core with pytest-xdist (`--dist loadgroup`). Each module
is one group, so the fixtures a module shares (a trained model, an installed wheel) are built on
one worker only; the RLlib tests are one group, since their Ray cluster is package-wide."""

from pathlib import Path

import pytest

RLLIB = Path(__file__).parent / "agents" / "rllib"


@pytest.hookimpl(tryfirst=True)  # before xdist's own hook reads the groups
def pytest_collection_modifyitems(items: list[pytest.Item]) -> None:
    for item in items:
        group = "rllib" if RLLIB in item.path.parents else item.nodeid.split("::")[0]
        item.add_marker(pytest.mark.xdist_group(group))
