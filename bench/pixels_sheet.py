"""A contact sheet of what a pixel agent sees: frames of a scripted match, both seats' images.

    python -m bench.pixels_sheet [--out docs/pixels_contact_sheet.png] [--left rush --right turtle]

Each cell is one step: fighter_0's image, then fighter_1's (flipped: each sees itself on the
left of the picture it started in), 84x84 grayscale as `obs_type="pixels"` gives them, scaled up
by `--scale` with no smoothing; the last row is the same frames in rgb (`pixel_rgb=True`). Frames
are picked to show each drawn state at least once: a hitbox, a shield, hitstun, a crouch.
"""

from __future__ import annotations

import argparse
import os
from pathlib import Path

import numpy as np

import vooga_env
from vooga_env.game import pixels as px
from vooga_env.policies import make_policy
from vooga_env.tools.files import atomic_write

GAP = 4  # pixels between images, in the sheet's own (scaled) pixels


def play(left: str, right: str, steps: int, seed: int) -> list[dict]:
    """The frames of one match: both seats' gray and rgb images and the drawn states in each."""
    gray = vooga_env.parallel_env(backend="engine", obs_type="both")
    rgb = vooga_env.parallel_env(backend="engine", obs_type="pixels", pixel_rgb=True)
    policies = [make_policy(left, seed), make_policy(right, seed + 1)]
    observations, _ = gray.reset(seed=seed)
    rgb.reset(seed=seed)
    frames = []
    for _ in range(steps):
        if not gray.agents:
            break
        actions = {
            agent: policy.act(observations[agent]["vector"])
            for agent, policy in zip(gray.possible_agents, policies)
        }
        observations, *_ = gray.step(actions)
        colour, *_ = rgb.step(actions)
        images = [observations[agent]["pixels"] for agent in gray.possible_agents]
        frames.append(
            {
                "gray": images,
                "rgb": [colour[agent] for agent in rgb.possible_agents],
                "shades": set(np.unique(images[0][3:]).tolist()),
                "crouching": any(f.crouching for f in gray.fight.fighters),
            }
        )
    return frames


def pick(frames: list[dict], count: int) -> list[int]:
    """`count` frame indices: the first showing each drawn state, the rest spread evenly."""
    wanted = [px.GRAY[e] for e in (px.HITBOX, px.SHIELD, px.SELF_STUNNED, px.OPPONENT_STUNNED)]
    chosen = [
        next((i for i, f in enumerate(frames) if shade in f["shades"]), None) for shade in wanted
    ]
    chosen.append(next((i for i, f in enumerate(frames) if f["crouching"]), None))
    chosen = [i for i in dict.fromkeys(chosen) if i is not None]
    spread = np.linspace(0, len(frames) - 1, count).round().astype(int).tolist()
    for i in spread:
        if len(chosen) >= count:
            break
        if i not in chosen:
            chosen.append(i)
    return sorted(chosen[:count])


def sheet(frames: list[dict], chosen: list[int], columns: int, scale: int) -> np.ndarray:
    """The picked frames as an (H, W, 3) uint8 grid: gray rows, then one rgb row."""
    cells = [_pair([np.repeat(image[..., None], 3, -1) for image in frames[i]["gray"]])
             for i in chosen]  # fmt: skip
    rows = [cells[k : k + columns] for k in range(0, len(cells), columns)]
    colour = [_pair(frames[i]["rgb"]) for i in chosen]
    rows.append(colour[:columns])
    width = max(sum(cell.shape[1] for cell in row) for row in rows)
    lines = [
        _pad(np.concatenate(row, 1), right=width - sum(c.shape[1] for c in row)) for row in rows
    ]
    grid = np.concatenate(lines, 0)
    return np.repeat(np.repeat(grid, scale, 0), scale, 1)


def _pair(images: list[np.ndarray]) -> np.ndarray:
    """Both seats' images side by side, a black gap after them."""
    pair = np.concatenate([_pad(image) for image in images], 1)
    return np.pad(pair, ((0, 0), (0, GAP), (0, 0)))


def _pad(image: np.ndarray, right: int = 0) -> np.ndarray:
    """An image with a white gap below it and to its right."""
    return np.pad(image, ((0, GAP), (0, GAP + right), (0, 0)), constant_values=255)


def save_png(path: Path, image: np.ndarray) -> Path:
    os.environ.setdefault("SDL_VIDEODRIVER", "dummy")
    os.environ.setdefault("PYGAME_HIDE_SUPPORT_PROMPT", "1")
    import pygame

    surface = pygame.surfarray.make_surface(image.transpose(1, 0, 2))

    def write(temporary: str) -> None:
        with open(temporary, "wb") as file:
            pygame.image.save(surface, file, "sheet.png")

    return atomic_write(path, write)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", type=Path, default=Path("docs/pixels_contact_sheet.png"))
    parser.add_argument("--left", default="rush")
    parser.add_argument("--right", default="turtle")
    parser.add_argument("--steps", type=int, default=300)
    parser.add_argument("--frames", type=int, default=12)
    parser.add_argument("--columns", type=int, default=4)
    parser.add_argument("--scale", type=int, default=3)
    parser.add_argument("--seed", type=int, default=0)
    args = parser.parse_args(argv)
    frames = play(args.left, args.right, args.steps, args.seed)
    chosen = pick(frames, args.frames)
    path = save_png(args.out, sheet(frames, chosen, args.columns, args.scale))
    print(f"frames {chosen} of {len(frames)}; wrote {path}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
