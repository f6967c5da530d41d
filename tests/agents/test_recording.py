"""GIF (and MP4 when its plugin is installed) recordings of rendered frames."""

from __future__ import annotations

import importlib.util

import numpy as np
import pytest
from PIL import Image

from vooga_env.tools.match import run_match
from vooga_env.tools.recording import save_animation


@pytest.fixture(scope="module")
def frames():
    result = run_match("rush", "idle", episodes=1, seed=0, max_cycles=40, record_frames=1)
    return result.episodes[0].frames


def test_gif_is_written_and_loads(frames, tmp_path):
    path = save_animation(frames, tmp_path / "sub" / "game.gif", fps=25)
    with Image.open(path) as image:
        assert image.format == "GIF" and image.size == (800, 480)
        assert image.n_frames > len(frames) // 2  # Pillow merges identical neighbours
        assert image.info["duration"] == 40
        image.seek(image.n_frames - 1)
        last = np.asarray(image.convert("RGB"))
    assert np.mean(np.all(last == frames[-1], axis=2)) > 0.95


def test_gif_scaled_down(frames, tmp_path):
    path = save_animation(frames[:5], tmp_path / "small.gif", scale=2)
    with Image.open(path) as image:
        assert image.size == (400, 240)


def test_bad_requests(frames, tmp_path):
    with pytest.raises(ValueError, match=".gif or .mp4"):
        save_animation(frames, tmp_path / "game.avi")
    with pytest.raises(ValueError, match="no frames"):
        save_animation([], tmp_path / "game.gif")
    with pytest.raises(ValueError, match="one size"):
        save_animation([frames[0], frames[0][:10]], tmp_path / "game.gif")


def test_mp4_written_or_the_plugin_named(frames, tmp_path):
    path = tmp_path / "game.mp4"
    if importlib.util.find_spec("imageio_ffmpeg") is None:
        with pytest.raises(ImportError, match="imageio-ffmpeg"):
            save_animation(frames[:5], path)
        assert not path.exists()
    else:
        save_animation(frames[:5], path)
        assert path.stat().st_size > 0
