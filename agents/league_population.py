"""Several leagues at once, one process (and core) each, and the best of their final models
shipped.

What a league makes swings with its seed: the same config beat every scripted fighter >= 90%
on some seeds and never beat turtle on others (docs/league.md), and this machine has a core for
each of two leagues. League i trains in OUT/league_i with seed + i, as agents.league trains one;
at the end each final model plays fresh games against every scripted fighter and every league's
exploiters, and the one with the best worst score (games won against a scripted fighter, not
lost against an exploiter) becomes OUT/final.zip (agents.league_select).

The leagues' final models all beat the scripted fighters on most seeds, and then the comparison
cannot tell them apart; yet one of two was often beaten by every fresh exploiter within a minute
while the other held for five (docs/league.md). With `screen_steps`, a fresh exploiter first trains
against each final model (a screen, OUT/league_i/exploiters/screen.zip), and every final model
meets every screen in the comparison: the one its own screen beats is not shipped over one that
held (a screen that only draws has not beaten it).
"""

from __future__ import annotations

import json
import multiprocessing
import sys
from collections.abc import Callable, Sequence
from multiprocessing.connection import wait
from pathlib import Path
from typing import Any

import numpy as np

from . import common
from .checkpoints import STATE_FILE
from .league_exploiter import ExploiterJob, ExploiterWorker
from .league_select import league_opponents, ship_best

SCREEN = "screen"  # a league's screen: OUT/league_i/exploiters/screen.zip


class LeagueFailed(RuntimeError):
    """A league's process ended with an error (printed by that process)."""


def league_folder(folder: Path, index: int) -> Path:
    return folder / f"league_{index}"


def run_leagues(train: Callable[..., Any], runs: Sequence[tuple], total: int, progress: bool):
    """Call `train(*run)` for each run, each in its own process, and wait for all of them.

    `run[1]` is the run's folder. Ctrl-C reaches the processes as SIGTERM, once each, which
    they take as Ctrl-C (checkpointed, resumable); the KeyboardInterrupt goes on from here. A
    process that fails is a LeagueFailed naming its folder, once all have ended. With
    `progress`, a bar of the steps the leagues have checkpointed, of `total`.
    """
    context = multiprocessing.get_context("spawn")  # no copy of torch's threads
    processes = [context.Process(target=_interruptible, args=(train, *run)) for run in runs]
    common.start_without_ctrl_c(processes)
    folders = [Path(run[1]) for run in runs]
    try:
        _wait(processes, folders, total if progress else 0)
    except KeyboardInterrupt:
        for process in processes:
            process.terminate()
        for process in processes:
            process.join()
        raise
    failed = [
        f"{folder} (exit code {process.exitcode})"
        for process, folder in zip(processes, folders, strict=True)
        if process.exitcode != 0
    ]
    if failed:
        raise LeagueFailed(
            f"the league process of {', '.join(failed)} failed (its error is printed above); "
            "--resume continues every league from its last checkpoint"
        )


def _interruptible(train: Callable[..., Any], *args: Any) -> None:
    """A league's process: SIGTERM is its Ctrl-C, and Ctrl-C ends it with exit code 130."""
    common.stop_on_signals()
    try:
        train(*args)
    except KeyboardInterrupt:
        sys.exit(130)


def _wait(processes: list[Any], folders: list[Path], total: int) -> None:
    bar = None
    if total:
        from tqdm import tqdm

        bar = tqdm(total=total, desc="leagues", unit="step", unit_scale=True, file=sys.stderr)
    try:
        alive = list(processes)
        while alive:
            wait([process.sentinel for process in alive], timeout=10.0)
            alive = [process for process in alive if process.is_alive()]
            if bar is not None:
                bar.n = sum(_steps(folder) for folder in folders)
                bar.refresh()
    finally:
        if bar is not None:
            bar.close()
    for process in processes:
        process.join()


def _steps(folder: Path) -> int:
    """The steps of the league's last checkpoint (0 before its first)."""
    try:
        return int(json.loads((folder / STATE_FILE).read_text())["num_timesteps"])
    except (FileNotFoundError, json.JSONDecodeError, KeyError):
        return 0


def screen_leagues(
    folder: Path, count: int, steps: int, fight: str, fights: int, seed: int
) -> None:
    """Train a fresh exploiter (`steps` steps, `fights` fights) against each of the `count`
    leagues' final models playing its argmax, one process a league, each saved as the league's
    screen; seeded from `seed` alone."""
    seeds = np.random.default_rng([seed, 2]).integers(2**31, size=(count, 2))
    workers = []
    try:
        for index, (target_seed, exploiter_seed) in enumerate(seeds):
            league = league_folder(folder, index)
            (league / "exploiters").mkdir(exist_ok=True)
            job = ExploiterJob(
                target=str(league / "final.zip"),
                argmax=True,
                target_seed=int(target_seed),
                seed=int(exploiter_seed),
                steps=steps,
                fight=fight,
                fights=fights,
                out=str(league / "exploiters" / f"{SCREEN}.zip"),
            )
            workers.append(ExploiterWorker())
            workers[-1].submit(job)
        for worker in workers:
            worker.collect()
    finally:
        for worker in workers:
            worker.close()


def ship_best_league(
    folder: Path,
    count: int,
    scripted: list[str],
    argmax: bool,
    games: int,
    seed: int,
    fight: Any,
    screened: bool = False,
) -> Path:
    """Copy the best of the `count` leagues' final models to `folder/final.zip`: the one whose
    worst score over `games` games against the scripted fighters (won) and every league's
    exploiters (not lost; named league_i/exploiter_N, and league_i/screen when `screened`) is
    best; `folder/selection.json` says why."""
    opponents = league_opponents(folder, scripted, [])
    candidates = {}
    for index in range(count):
        league = league_folder(folder, index)
        exploiters = json.loads((league / STATE_FILE).read_text())["exploiters"]
        exploiters += [SCREEN] if screened else []
        opponents.update(league_opponents(league, [], exploiters, argmax, f"{league.name}/"))
        candidates[league.name] = league / "final.zip"
    learned = set(opponents) - set(scripted)  # the exploiters and the screens
    return ship_best(folder, candidates, opponents, games, seed, fight, learned)
