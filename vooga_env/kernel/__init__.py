"""The fight compiled with numba: `VectorFight` (N fights as arrays, the single env's rules and
results), the compiled single fight behind `backend="compiled"`, and the stages they run."""

from vooga_env.kernel.params import UnsupportedConfig
from vooga_env.kernel.vector_fight import VectorFight, numba_available

__all__ = ["UnsupportedConfig", "VectorFight", "numba_available"]
