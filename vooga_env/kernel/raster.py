"""The pixel observations of N fights, rasterised by numba from the `FightState` arrays.

The twin of `vooga_env.game.pixels.PixelRenderer` (its module docstring says what is drawn): the
same shapes placed by the same `pixel_formulas` (compiled here), in the same order, with the same
palette, so the compiled backends' images equal the engine backend's bit for bit. A separate
compiled entry from the step kernel (`compiled.py`): it compiles on the first pixel observation
only, so the vector observations never pay for it.
"""

from __future__ import annotations

import numba
import numpy as np

from vooga_env.game import pixel_formulas
from vooga_env.game.pixels import (
    EYE,
    HITBOX,
    OPPONENT,
    OPPONENT_STUNNED,
    SELF,
    SELF_STUNNED,
    SHIELD,
    TIME,
    PixelSpec,
    background,
)
from vooga_env.kernel.layout import (
    S_BLOCKING,
    S_FACING,
    S_HEALTH,
    S_HEIGHT,
    S_HIT_ACTIVE,
    S_HIT_H,
    S_HIT_W,
    S_HIT_X,
    S_HIT_Y,
    S_HITSTUN,
    S_STEPS,
    S_X,
    S_Y,
)
from vooga_env.kernel.params import FightParams
from vooga_env.kernel.parts import compiled

P = compiled(pixel_formulas)
inline = numba.njit(cache=True, nogil=True, inline="always")
SCENE = ("arena_w", "arena_h", "f_width", "health", "max_cycles")  # the `scene` array's slots


class Rasteriser:
    """One config's static image and numbers; draws a `FightState`'s fights into uint8 arrays."""

    def __init__(self, params: FightParams, spec: PixelSpec) -> None:
        self.spec = spec
        config = params.config
        self.scene = np.array(
            [params.width, params.height, config.fighter.width, config.fighter.health,
             config.max_cycles], dtype=np.float64,
        )  # fmt: skip
        blocks = list(zip(params.block_x, params.block_y, params.block_w, params.block_h))
        self.background = background(spec, blocks, (params.width, params.height))
        self.palette = spec.palette

    def render(self, state, index: np.ndarray, out: np.ndarray) -> None:
        """Both fighters' images of the fights `index` into out[index], (N, 2, H, W, C) uint8."""
        index = np.asarray(index, dtype=np.int64)
        if index.size == out.shape[0]:  # numpy copies the static image faster than a loop
            out[:] = self.background
        else:
            out[index] = self.background
        _render(self.scene, state.floats, state.ints, state.flags, state.counters, index,
                self.palette, out)  # fmt: skip


@inline
def _fill(image, shape, o, palette, entry, top, bottom, left, right):
    """Paint the pixels (top..bottom, left..right), world columns, of observer o's flat image
    (`shape`: rows, cols, channels) with a palette entry."""
    _, cols, channels = shape
    left, right = P.mirrored(left, right, cols, o)
    if channels == 1:  # unit strides: the loop compiles to vector stores
        value = palette[entry, 0]
        for r in range(top, bottom + 1):
            for c in range(r * cols + left, r * cols + right + 1):
                image[c] = value
        return
    for r in range(top, bottom + 1):
        for c in range(left, right + 1):
            for k in range(channels):
                image[(r * cols + c) * channels + k] = palette[entry, k]


@inline
def _box(scene, shape, x, y, w, h):
    return P.box(x, y, w, h, scene[0], scene[1], shape[0], shape[1])


@inline
def _body(scene, fl, it, image, shape, i, o, f, palette, shade, stunned):
    """Fighter f's body and eye in observer o's image of fight i; its box in pixels."""
    top, bottom, left, right = _box(scene, shape, fl[S_X, f, i], fl[S_Y, f, i], scene[2],
                                    fl[S_HEIGHT, f, i])  # fmt: skip
    entry = stunned if it[S_HITSTUN, f, i] > 0 else shade
    _fill(image, shape, o, palette, entry, top, bottom, left, right)
    if top <= bottom and left <= right:
        eye_bottom, eye_column = P.eye(top, bottom, left, right, fl[S_FACING, f, i])
        _fill(image, shape, o, palette, EYE, top, eye_bottom, eye_column, eye_column)
    return top, bottom, left, right


@inline
def _shield(fl, fg, image, shape, i, o, f, palette, top, bottom, left, right):
    """Fighter f's shield column, in front of its box, while it blocks."""
    if fg[S_BLOCKING, f, i] and top <= bottom and left <= right:
        column = P.shield(left, right, fl[S_FACING, f, i])
        if 0 <= column < shape[1]:
            _fill(image, shape, o, palette, SHIELD, top, bottom, column, column)


@inline
def _hitbox(scene, fl, fg, image, shape, i, o, f, palette):
    """Fighter f's attack hitbox, while it is active."""
    if fg[S_HIT_ACTIVE, f, i]:
        top, bottom, left, right = _box(scene, shape, fl[S_HIT_X, f, i], fl[S_HIT_Y, f, i],
                                        fl[S_HIT_W, f, i], fl[S_HIT_H, f, i])  # fmt: skip
        _fill(image, shape, o, palette, HITBOX, top, bottom, left, right)


@inline
def _bar(image, shape, row, share, palette, entry):
    _fill(image, shape, 0, palette, entry, row, row, 0, P.bar(share, shape[1]) - 1)


@inline
def _draw(scene, fl, it, fg, ct, image, shape, i, o, palette):
    """Observer o's image of fight i over its background: PixelRenderer._draw."""
    other = 1 - o
    t0, b0, l0, r0 = _body(scene, fl, it, image, shape, i, o, other, palette, OPPONENT,
                           OPPONENT_STUNNED)  # fmt: skip
    t1, b1, l1, r1 = _body(scene, fl, it, image, shape, i, o, o, palette, SELF, SELF_STUNNED)
    _shield(fl, fg, image, shape, i, o, other, palette, t0, b0, l0, r0)
    _shield(fl, fg, image, shape, i, o, o, palette, t1, b1, l1, r1)
    _hitbox(scene, fl, fg, image, shape, i, o, other, palette)
    _hitbox(scene, fl, fg, image, shape, i, o, o, palette)
    _bar(image, shape, 0, fl[S_HEALTH, o, i] / scene[3], palette, SELF)
    _bar(image, shape, 1, fl[S_HEALTH, other, i] / scene[3], palette, OPPONENT)
    _bar(image, shape, 2, 1.0 - ct[S_STEPS, i] / scene[4], palette, TIME)


@numba.njit(cache=True, nogil=True)
def _render(scene, fl, it, fg, ct, index, palette, out):
    """Paint what `_draw` paints on each image of the fights `index` (over its background),
    each a flat row (one per fight and observer)."""
    shape = (out.shape[2], out.shape[3], out.shape[4])
    images = out.reshape(out.shape[0] * 2, shape[0] * shape[1] * shape[2])
    for i in index:
        for o in range(2):
            _draw(scene, fl, it, fg, ct, images[2 * i + o], shape, i, o, palette)
