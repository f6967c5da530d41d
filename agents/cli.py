"""The console commands that need an extra: without it they say which one to install, in one
line, instead of a traceback from an import deep inside (`pip install vooga-env` alone brings
the engine, the env faces and the scripted fighters, not the RL stack or pygame)."""

from __future__ import annotations

import importlib
import importlib.util
import sys

# the module a command imports first -> the extra that brings it
PROVIDED_BY = {"stable_baselines3": "train", "torch": "train", "ray": "rllib", "pygame": "render"}


def _installed(module: str) -> bool:
    """Found without importing it (`import ray` alone takes seconds, before `--help`)."""
    try:
        return importlib.util.find_spec(module) is not None
    except ImportError:  # an import hook that refuses it
        return False


def _main(command: str, needs: tuple[str, ...]) -> int:
    for module in needs:
        if not _installed(module):
            extra = PROVIDED_BY[module]
            sys.exit(
                f"vooga-{command.replace('_', '-')}: no module named {module!r}; it comes with the "
                f"{extra!r} extra: pip install 'vooga-env[{extra}]'"
            )
    return importlib.import_module(f".{command}", __package__).main()


def train() -> int:
    return _main("train", ("stable_baselines3",))


def league() -> int:
    return _main("league", ("stable_baselines3",))


def exploit() -> int:
    return _main("exploit", ("stable_baselines3",))


def play() -> int:
    return _main("play", ("pygame",))


def train_rllib() -> int:
    return _main("train_rllib", ("ray", "torch"))
