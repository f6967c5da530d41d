"""The batched engine: N fights as arrays, the single env's rules and results (see engine.py)."""

from vooga_env.vector.engine import VectorFight, numba_available
from vooga_env.vector.params import UnsupportedConfig

__all__ = ["UnsupportedConfig", "VectorFight", "numba_available"]
