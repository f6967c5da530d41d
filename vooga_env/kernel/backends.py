"""`make_simulation`: the engine or the compiled backend for one fight, by name or by what can
run it."""

from __future__ import annotations

from vooga_env.game.config import FightConfig
from vooga_env.game.rewards import RewardFn
from vooga_env.game.simulation import EngineSimulation, Simulation
from vooga_env.kernel.params import UnsupportedConfig, check_supported
from vooga_env.kernel.single import CompiledSimulation
from vooga_env.kernel.vector_fight import numba_available

BACKENDS = ("auto", "engine", "compiled")


def make_simulation(
    config: FightConfig,
    backend: str = "auto",
    reward_fn: RewardFn | None = None,
    render_mode: str | None = None,
) -> Simulation:
    """The simulation `backend` names; "auto": compiled when it can run this env, else engine."""
    if backend not in BACKENDS:
        raise ValueError(f"backend = {backend!r} is not allowed: one of {', '.join(BACKENDS)}")
    if reward_fn is not None and not callable(reward_fn):
        raise TypeError(
            f"reward_fn = {reward_fn!r} is not allowed: a callable (fight, events) -> "
            "(reward_0, reward_1), or None for the config's HitAndRingOutReward"
        )
    if backend == "engine":
        return EngineSimulation(config, reward_fn)
    reason = None
    if render_mode is not None:
        reason = f"render_mode = {render_mode!r}: the viewer draws the engine's fight"
    elif not numba_available():
        reason = "numba is not installed: pip install numba"
    else:
        try:
            check_supported(config, reward_fn)
        except UnsupportedConfig as error:
            reason = str(error)
    if reason is None:
        return CompiledSimulation(config)
    if backend == "compiled":
        raise ValueError(f"backend = 'compiled' cannot run this env: {reason}; use 'engine'")
    return EngineSimulation(config, reward_fn)
