"""Policies: what plays a fighter, given its own observation.

`base.Policy` is the interface; `scripted` holds the scripted fighters, `models` the frozen
trained ones (SB3 zips, exported MLPs), `batched` the scripted styles on N observations at once,
`random_styles` a batch opponent of random styles (the league's), and `spec.make_policy` turns a
name, a file or a callable into a Policy.
"""

from vooga_env.policies.base import Policy
from vooga_env.policies.scripted import (
    SCRIPTED,
    Aerial,
    Drawn,
    EdgeGrappler,
    EdgeGuard,
    Idle,
    MixUp,
    Punisher,
    RandomFighter,
    Rush,
    Scripted,
    Spacer,
    Turtle,
    Zoner,
)
from vooga_env.policies.spec import CallablePolicy, PredictPolicy, make_policy

__all__ = [
    "SCRIPTED",
    "Aerial",
    "CallablePolicy",
    "Drawn",
    "EdgeGrappler",
    "EdgeGuard",
    "Idle",
    "MixUp",
    "Policy",
    "PredictPolicy",
    "Punisher",
    "RandomFighter",
    "Rush",
    "Scripted",
    "Spacer",
    "Turtle",
    "Zoner",
    "make_policy",
]
