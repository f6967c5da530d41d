"""Pixel observations: what a fighter sees of the fight as a small uint8 image, drawn with numpy.

The engine backend draws its `Fight` here; the compiled backends draw their arrays with the numba
twin (`kernel/raster.py`); both place every shape with `pixel_formulas`, in the same order, with
the same palette, so the images are equal bit for bit. An image is ego-centric: the observer is
drawn in the `SELF` shade, the opponent in `OPPONENT`'s, and fighter_1's image is flipped
left-right, so that, as with the vectors, one policy plays either seat.

What is drawn, in order: the sky and the stage's blocks (static: `background`), each fighter's
body (lighter while in hitstun; shorter while crouching) with an eye on its front column (its
facing) and a shield column in front while blocking, the opponent first, then the active attack
hitboxes, then three HUD rows: the observer's health, the opponent's, the time left.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from vooga_env.game import pixel_formulas as P
from vooga_env.game.fight import Fight

OBS_TYPES = ("vector", "pixels", "both")
SIZE_RANGE = (16, 512)  # pixels, each side of the image

# the palette's entries (a shade each for grayscale, a colour for rgb)
SKY, HUD_EMPTY, EYE, STAGE, OPPONENT, OPPONENT_STUNNED, SHIELD, SELF, SELF_STUNNED, HITBOX, TIME = (
    range(11)
)
GRAY = np.array([0, 40, 60, 90, 130, 165, 190, 215, 245, 255, 110], dtype=np.uint8)
RGB = np.array(
    [
        (24, 28, 44),  # sky
        (60, 60, 70),  # an empty bar
        (255, 255, 255),  # eye
        (150, 140, 120),  # stage
        (70, 130, 230),  # opponent
        (170, 205, 255),  # opponent in hitstun
        (160, 230, 255),  # shield
        (220, 70, 70),  # self
        (255, 170, 170),  # self in hitstun
        (255, 220, 60),  # hitbox
        (200, 200, 200),  # time left
    ],
    dtype=np.uint8,
)


@dataclass(frozen=True)
class PixelSpec:
    """The image's size (pixels) and colour: (height, width) grayscale or (height, width, 3)."""

    height: int = 84
    width: int = 84
    rgb: bool = False

    def __post_init__(self) -> None:
        low, high = SIZE_RANGE
        sides = (self.height, self.width)
        if not all(_is_int(side) and low <= side <= high for side in sides):
            raise ValueError(
                f"pixel_size = {sides!r} is not allowed: (height, width), two ints in {low}..{high}"
            )
        if not isinstance(self.rgb, (bool, np.bool_)):
            raise ValueError(
                f"pixel_rgb = {self.rgb!r} is not allowed: True (H, W, 3) or False (H, W) gray"
            )

    @property
    def channels(self) -> int:
        return 3 if self.rgb else 1

    @property
    def shape(self) -> tuple[int, ...]:
        """One observer's image shape, as the observation space gives it."""
        return (self.height, self.width, 3) if self.rgb else (self.height, self.width)

    @property
    def palette(self) -> np.ndarray:
        """(entries, channels) uint8: each palette entry's value per channel."""
        return RGB.copy() if self.rgb else GRAY[:, None].copy()


def _is_int(value: object) -> bool:
    return isinstance(value, (int, np.integer)) and not isinstance(value, (bool, np.bool_))


def pixel_spec(
    obs_type: str = "vector", pixel_size: object = (84, 84), pixel_rgb: object = False
) -> PixelSpec | None:
    """The image that `obs_type` asks for (None for "vector"), or a ValueError naming the bad
    argument, its value and what is allowed."""
    if obs_type not in OBS_TYPES:
        allowed = ", ".join(repr(t) for t in OBS_TYPES)
        raise ValueError(f"obs_type = {obs_type!r} is not allowed: one of {allowed}")
    if not isinstance(pixel_size, (tuple, list)) or len(pixel_size) != 2:
        low, high = SIZE_RANGE
        raise ValueError(
            f"pixel_size = {pixel_size!r} is not allowed: (height, width), two ints in "
            f"{low}..{high}"
        )
    spec = PixelSpec(pixel_size[0], pixel_size[1], pixel_rgb)
    if obs_type == "vector":
        return None
    return PixelSpec(int(spec.height), int(spec.width), bool(spec.rgb))


def background(
    spec: PixelSpec, blocks: list[tuple[float, float, float, float]], arena: tuple[float, float]
) -> np.ndarray:
    """Each observer's static image, (2, H, W, C): sky, the blocks, the empty HUD bars."""
    image = np.empty((spec.height, spec.width, spec.channels), dtype=np.uint8)
    palette = spec.palette
    image[:] = palette[SKY]
    image[: P.HUD_ROWS] = palette[HUD_EMPTY]
    for x, y, w, h in blocks:
        _fill(image, palette, STAGE, P.box(x, y, w, h, arena[0], arena[1], *image.shape[:2]), 0)
    return np.stack([image, image[:, ::-1]])


class PixelRenderer:
    """Draws one `Fight` as each fighter sees it, with numpy (the engine backend's renderer)."""

    def __init__(self, fight: Fight, spec: PixelSpec) -> None:
        self.fight = fight
        self.spec = spec
        self.palette = spec.palette
        arena = fight.config.arena
        self.arena = (arena.width, arena.height)
        blocks = [(b.x, b.y, b.width, b.height) for b in arena.blocks]
        self.background = background(spec, blocks, self.arena)

    def render(self) -> np.ndarray:
        """Both fighters' images, (2, H, W, C) uint8, fighter_0's first."""
        out = self.background.copy()
        for observer in (0, 1):
            self._draw(out[observer], observer)
        return out

    def _draw(self, image: np.ndarray, observer: int) -> None:
        fight, palette = self.fight, self.palette
        me, other = fight.fighters[observer], fight.fighters[1 - observer]
        boxes = [self._body(image, other, OPPONENT, OPPONENT_STUNNED, observer),
                 self._body(image, me, SELF, SELF_STUNNED, observer)]  # fmt: skip
        for fighter, (top, bottom, left, right) in zip((other, me), boxes):
            if fighter.blocking and top <= bottom and left <= right:
                column = P.shield(left, right, fighter.facing)
                if 0 <= column < self.spec.width:
                    _fill(image, palette, SHIELD, (top, bottom, column, column), observer)
        for fighter in (other, me):
            hitbox = fighter.hitbox
            if hitbox.active:
                rect = self._box(hitbox.x, hitbox.y, hitbox.width, hitbox.height)
                _fill(image, palette, HITBOX, rect, observer)
        config = fight.config
        shares = (
            me.health / config.fighter.health,
            other.health / config.fighter.health,
            1.0 - fight.steps / config.max_cycles,
        )
        for row, (share, entry) in enumerate(zip(shares, (SELF, OPPONENT, TIME))):
            image[row, : P.bar(share, self.spec.width)] = palette[entry]

    def _body(self, image, fighter, shade: int, stunned: int, observer: int) -> tuple[int, ...]:
        """Paint the fighter's body and eye; its box in pixels."""
        palette = self.palette
        rect = self._box(fighter.x, fighter.y, fighter.width, fighter.height)
        _fill(image, palette, stunned if fighter.hitstun > 0 else shade, rect, observer)
        top, bottom, left, right = rect
        if top <= bottom and left <= right:
            eye_bottom, eye_column = P.eye(top, bottom, left, right, fighter.facing)
            _fill(image, palette, EYE, (top, eye_bottom, eye_column, eye_column), observer)
        return rect

    def _box(self, x: float, y: float, w: float, h: float) -> tuple[int, int, int, int]:
        return P.box(x, y, w, h, self.arena[0], self.arena[1], self.spec.height, self.spec.width)


def _fill(image: np.ndarray, palette: np.ndarray, entry: int, rect, observer: int) -> None:
    """Paint the pixels (top, bottom, left, right) (inclusive, world columns) of `observer`'s
    image with a palette entry; an empty range paints nothing."""
    top, bottom, left, right = rect
    left, right = P.mirrored(left, right, image.shape[1], observer)
    if top <= bottom and left <= right:
        image[top : bottom + 1, left : right + 1] = palette[entry]


def compose(obs_type: str, vector: np.ndarray, images: np.ndarray | None, spec: PixelSpec | None):
    """The observation `obs_type` names from the vectors (..., 41) and the images (..., H, W, C):
    the vectors, the images in `spec.shape`, or a dict of both."""
    if obs_type == "vector":
        return vector
    pixels = images.reshape(images.shape[:-3] + spec.shape)
    if obs_type == "pixels":
        return pixels
    return {"vector": vector, "pixels": pixels}
