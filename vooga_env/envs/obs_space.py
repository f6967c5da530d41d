"""The observation space each `obs_type` gives one fighter: the vector, the image, or both."""

from __future__ import annotations

import numpy as np
from gymnasium import spaces

from vooga_env.game.observations import HIGH, LOW, OBSERVATION_SIZE
from vooga_env.game.pixels import PixelSpec


def observation_space(
    obs_type: str, spec: PixelSpec | None, channel_axis: bool = False
) -> spaces.Space:
    """`Box(-2, 2, (41,), float32)`, `Box(0, 255, spec.shape, uint8)`, or a `Dict` of both
    ("vector", "pixels"); `spec` is None for "vector" (see `pixels.pixel_spec`). `channel_axis`:
    grayscale as (H, W, 1), the image shape SB3's CnnPolicy and VecFrameStack take."""
    vector = spaces.Box(LOW, HIGH, (OBSERVATION_SIZE,), np.float32)
    if spec is None:
        return vector
    shape = (spec.height, spec.width, spec.channels) if channel_axis else spec.shape
    pixels = spaces.Box(0, 255, shape, np.uint8)
    if obs_type == "pixels":
        return pixels
    return spaces.Dict({"vector": vector, "pixels": pixels})
