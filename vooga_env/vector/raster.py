"""The pixel observations of N fights, rasterised by numba from the `FightState` arrays.

The twin of `vooga_env.pixels.PixelRenderer` (its module docstring says what is drawn): the same
shapes placed by the same `pixel_formulas` (compiled here), in the same order, with the same
palette, so the compiled backends' images equal the engine backend's bit for bit. A separate
compiled entry from the step kernel (`kernel.py`): it compiles on the first pixel observation
only, so the vector observations never pay for it.
"""

from __future__ import annotations

import numba
import numpy as np

from vooga_env import pixel_formulas
from vooga_env.pixels import (
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
from vooga_env.vector.kernel_parts import compiled
from vooga_env.vector.layout import (
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
from vooga_env.vector.params import FightParams

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
        _render(self.scene, state.floats, state.ints, state.flags, state.counters, index,
                self.background, self.palette, out)  # fmt: skip


@inline
def _fill(out, i, o, palette, entry, top, bottom, left, right):
    """Paint out[i, o]'s pixels (top..bottom, left..right), world columns, with a palette entry."""
    cols, channels = out.shape[3], out.shape[4]
    left, right = P.mirrored(left, right, cols, o)
    for r in range(top, bottom + 1):
        for c in range(left, right + 1):
            for k in range(channels):
                out[i, o, r, c, k] = palette[entry, k]


@inline
def _box(scene, out, x, y, w, h):
    return P.box(x, y, w, h, scene[0], scene[1], out.shape[2], out.shape[3])


@inline
def _body(scene, fl, it, out, i, o, f, palette, shade, stunned):
    """Fighter f's body and eye in observer o's image of fight i; its box in pixels."""
    top, bottom, left, right = _box(scene, out, fl[S_X, f, i], fl[S_Y, f, i], scene[2],
                                    fl[S_HEIGHT, f, i])  # fmt: skip
    entry = stunned if it[S_HITSTUN, f, i] > 0 else shade
    _fill(out, i, o, palette, entry, top, bottom, left, right)
    if top <= bottom and left <= right:
        eye_bottom, eye_column = P.eye(top, bottom, left, right, fl[S_FACING, f, i])
        _fill(out, i, o, palette, EYE, top, eye_bottom, eye_column, eye_column)
    return top, bottom, left, right


@inline
def _shield(fl, fg, out, i, o, f, palette, top, bottom, left, right):
    """Fighter f's shield column, in front of its box, while it blocks."""
    if fg[S_BLOCKING, f, i] and top <= bottom and left <= right:
        column = P.shield(left, right, fl[S_FACING, f, i])
        if 0 <= column < out.shape[3]:
            _fill(out, i, o, palette, SHIELD, top, bottom, column, column)


@inline
def _bar(out, i, o, row, share, palette, entry):
    for c in range(P.bar(share, out.shape[3])):
        for k in range(out.shape[4]):
            out[i, o, row, c, k] = palette[entry, k]


@inline
def _draw(scene, fl, it, fg, ct, out, i, o, palette):
    """Observer o's image of fight i over its background: PixelRenderer._draw."""
    other = 1 - o
    t0, b0, l0, r0 = _body(scene, fl, it, out, i, o, other, palette, OPPONENT, OPPONENT_STUNNED)
    t1, b1, l1, r1 = _body(scene, fl, it, out, i, o, o, palette, SELF, SELF_STUNNED)
    _shield(fl, fg, out, i, o, other, palette, t0, b0, l0, r0)
    _shield(fl, fg, out, i, o, o, palette, t1, b1, l1, r1)
    for f in (other, o):
        if fg[S_HIT_ACTIVE, f, i]:
            top, bottom, left, right = _box(scene, out, fl[S_HIT_X, f, i], fl[S_HIT_Y, f, i],
                                            fl[S_HIT_W, f, i], fl[S_HIT_H, f, i])  # fmt: skip
            _fill(out, i, o, palette, HITBOX, top, bottom, left, right)
    _bar(out, i, o, 0, fl[S_HEALTH, o, i] / scene[3], palette, SELF)
    _bar(out, i, o, 1, fl[S_HEALTH, other, i] / scene[3], palette, OPPONENT)
    _bar(out, i, o, 2, 1.0 - ct[S_STEPS, i] / scene[4], palette, TIME)


@numba.njit(cache=True, nogil=True)
def _render(scene, fl, it, fg, ct, index, background, palette, out):
    rows, cols, channels = out.shape[2], out.shape[3], out.shape[4]
    for i in index:
        for o in range(2):
            for r in range(rows):
                for c in range(cols):
                    for k in range(channels):
                        out[i, o, r, c, k] = background[o, r, c, k]
            _draw(scene, fl, it, fg, ct, out, i, o, palette)
