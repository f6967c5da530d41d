"""Where a pixel observation's shapes land, written once: the numpy renderer (`pixels.py`) calls
these, the numba rasteriser (`kernel/raster.py`) compiles them, so both pick the same pixels.

Plain Python over floats and ints (px of the arena, pixels of the image), like `formulas.py`.
A pixel is covered by a box when its centre lies in the box, both edges included: that rule is
mirror-symmetric, so the mirrored world covers exactly the mirrored pixels (with dyadic
coordinates the products below are exact). The image's top `HUD_ROWS` rows hold the bars; the
arena fills the rows below them.
"""

from __future__ import annotations

import math

HUD_ROWS = 3  # the observer's health, the opponent's health, the time left


def first_pixel(low: float, length: float, pixels: int) -> int:
    """The first pixel whose centre ((p + 0.5) * length / pixels) is >= `low`."""
    target = 2.0 * low * pixels
    p = math.ceil(low * pixels / length - 0.5)
    while (2 * p + 1) * length < target:
        p += 1
    while (2 * p - 1) * length >= target:
        p -= 1
    return p


def last_pixel(high: float, length: float, pixels: int) -> int:
    """The last pixel whose centre is <= `high`."""
    target = 2.0 * high * pixels
    p = math.floor(high * pixels / length - 0.5)
    while (2 * p + 1) * length > target:
        p -= 1
    while (2 * p + 3) * length <= target:
        p += 1
    return p


def span(low: float, high: float, length: float, pixels: int) -> tuple[int, int]:
    """The pixels (first, last) of the segment [low, high] on an axis `length` px long drawn in
    `pixels` pixels; a segment between two centres gets both (nothing vanishes); first > last:
    off the image."""
    first, last = first_pixel(low, length, pixels), last_pixel(high, length, pixels)
    if first == last + 1:
        first, last = last, first
    return max(first, 0), min(last, pixels - 1)


def box(
    x: float, y: float, w: float, h: float, arena_w: float, arena_h: float, rows: int, cols: int
) -> tuple[int, int, int, int]:
    """(top, bottom, left, right) pixels of the arena box (x, y, w, h) in a `rows` x `cols`
    image, world columns (not yet mirrored), below the HUD rows."""
    top, bottom = span(y, y + h, arena_h, rows - HUD_ROWS)
    left, right = span(x, x + w, arena_w, cols)
    return top + HUD_ROWS, bottom + HUD_ROWS, left, right


def mirrored(left: int, right: int, cols: int, observer: int) -> tuple[int, int]:
    """A column range as `observer` sees it: fighter_1's image is flipped left-right."""
    if observer == 1:
        return cols - 1 - right, cols - 1 - left
    return left, right


def eye(top: int, bottom: int, left: int, right: int, facing: float) -> tuple[int, int]:
    """(last row, column) of the eye: the top third of the body's front column (world frame)."""
    return top + max((bottom - top + 1) // 3, 1) - 1, right if facing > 0 else left


def shield(left: int, right: int, facing: float) -> int:
    """The column of a block's shield: just in front of the body (world frame)."""
    return right + 1 if facing > 0 else left - 1


def bar(share: float, cols: int) -> int:
    """Columns filled by a HUD bar at `share` (0..1) of the image's width."""
    return min(max(math.floor(share * cols + 0.5), 0), cols)
