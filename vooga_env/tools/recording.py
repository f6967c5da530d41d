"""Saving frames (HxWx3 uint8 arrays, e.g. `env.render()` in rgb_array mode) as a GIF or an MP4.

GIF needs Pillow (`pip install 'vooga-env[render]'`); MP4 needs imageio with its ffmpeg plugin
(`pip install imageio imageio-ffmpeg`). `check_writer(path)` says before a long run whether the
file can be written.
"""

from __future__ import annotations

import importlib.util
from collections.abc import Sequence
from pathlib import Path

import numpy as np

FORMATS = (".gif", ".mp4")
NEEDS = {
    ".gif": (("PIL",), "saving a GIF needs Pillow: pip install 'vooga-env[render]'"),
    ".mp4": (
        ("imageio", "imageio_ffmpeg"),
        "saving an MP4 needs imageio and its ffmpeg plugin: pip install imageio imageio-ffmpeg",
    ),
}


def check_writer(path: str | Path) -> None:
    """Raise ValueError for a file type we cannot write, ImportError when its library is missing."""
    suffix = Path(path).suffix.lower()
    if suffix not in FORMATS:
        raise ValueError(f"cannot record to {path}: use a {' or '.join(FORMATS)} file name")
    modules, message = NEEDS[suffix]
    if any(importlib.util.find_spec(module) is None for module in modules):
        raise ImportError(message)


def save_animation(
    frames: Sequence[np.ndarray], path: str | Path, fps: float = 25.0, scale: int = 1
) -> Path:
    """Write `frames` to `path` (.gif or .mp4) at `fps` frames per second; returns the path.

    `scale`: keep every `scale`-th pixel in each direction (2 halves the width and height).
    """
    path = Path(path)
    check_writer(path)
    if not frames:
        raise ValueError("no frames to record")
    if fps <= 0 or scale < 1:
        raise ValueError(f"need fps > 0 and scale >= 1, got fps={fps!r}, scale={scale!r}")
    shapes = {np.shape(frame) for frame in frames}
    if len(shapes) != 1 or len(next(iter(shapes))) != 3 or next(iter(shapes))[2] != 3:
        raise ValueError(f"frames must all be HxWx3 arrays of one size, got shapes {shapes}")
    images = [np.ascontiguousarray(np.asarray(f, dtype=np.uint8)[::scale, ::scale]) for f in frames]
    path.parent.mkdir(parents=True, exist_ok=True)
    if path.suffix.lower() == ".gif":
        _save_gif(images, path, fps)
    else:
        _save_mp4(images, path, fps)
    return path


def _save_gif(images: list[np.ndarray], path: Path, fps: float) -> None:
    from PIL import Image

    # One palette for the whole animation, from a few frames spread over it: quantising each
    # frame against it is several times faster than an adaptive palette per frame.
    sample = images[:: max(1, len(images) // 8)][:8]
    palette = Image.fromarray(np.concatenate(sample)).quantize(
        colors=255, method=Image.Quantize.MEDIANCUT
    )
    pictures = [
        Image.fromarray(image).quantize(palette=palette, dither=Image.Dither.NONE)
        for image in images
    ]
    pictures[0].save(
        path,
        save_all=True,
        append_images=pictures[1:],
        duration=round(1000.0 / fps),
        loop=0,
    )


def _save_mp4(images: list[np.ndarray], path: Path, fps: float) -> None:
    import imageio.v2 as imageio

    # H.264 wants even sizes; pad the last row / column if needed.
    height, width = images[0].shape[:2]
    pad = ((0, height % 2), (0, width % 2), (0, 0))
    with imageio.get_writer(path, fps=fps, codec="libx264", macro_block_size=1) as writer:
        for image in images:
            writer.append_data(np.pad(image, pad, mode="edge") if any(p[1] for p in pad) else image)
