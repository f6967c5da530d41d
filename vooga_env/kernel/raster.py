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
# No reference counting (`_nrt=False`): the helpers take the arrays as arguments, and counting
# each argument in and out of each inlined helper was two thirds of the drawing time (nothing
# here allocates; the arrays outlive the call).
inline = numba.njit(cache=True, nogil=True, inline="always", _nrt=False)
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
        self.shape = (spec.height, spec.width, spec.channels)

    def render(self, state, index: np.ndarray, out: np.ndarray, seats=None) -> None:
        """The images of the fights `index` into `out`: both fighters', out[i] (2, H, W, C), or
        with `seats` (one per fight of the batch) fighter seats[i]'s alone, out[i] (H, W, C)."""
        index = np.asarray(index, dtype=np.int64)
        seats = _NO_SEATS if seats is None else np.asarray(seats, dtype=np.int64)
        _render(self.scene, state.floats, state.ints, state.flags, state.counters, index, seats,
                self.palette, self.background.reshape(2, -1), self.shape,
                out.reshape(out.shape[0], -1))  # fmt: skip


_NO_SEATS = np.empty(0, dtype=np.int64)


@inline
def _fill(image, shape, o, palette, entry, top, bottom, left, right):
    """Paint the pixels (top..bottom, left..right), world columns, of observer o's flat image
    (`shape`: rows, cols, channels) with a palette entry."""
    _, cols, channels = shape
    left, right = P.mirrored(left, right, cols, o)
    if channels == 1:  # a row is one slice store
        value = palette[entry, 0]
        for r in range(top, bottom + 1):
            image[r * cols + left : r * cols + right + 1] = value
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


@inline
def _paint(scene, fl, it, fg, ct, image, shape, i, o, palette, background):
    """Observer o's image of fight i, a flat row: its background, then `_draw`'s shapes, while
    the row is in cache (copying the whole batch's backgrounds first read every image back from
    memory to draw on it)."""
    source = background[o]
    for k in range(image.size):
        image[k] = source[k]
    _draw(scene, fl, it, fg, ct, image, shape, i, o, palette)


@numba.njit(cache=True, nogil=True, _nrt=False)
def _render(scene, fl, it, fg, ct, index, seats, palette, background, shape, out):
    """Paint the images of the fights `index` into `out`'s flat rows: two a fight (2i + o), or
    one (row i, observer seats[i]) when `seats` is given."""
    images = out if seats.size else out.reshape(out.shape[0] * 2, out.shape[1] // 2)
    for i in index:
        if seats.size:
            _paint(scene, fl, it, fg, ct, images[i], shape, i, seats[i], palette, background)
        else:
            for o in range(2):
                _paint(scene, fl, it, fg, ct, images[2 * i + o], shape, i, o, palette, background)
