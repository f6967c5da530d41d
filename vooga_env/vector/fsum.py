"""`fsum_columns`: `math.fsum` of each column of an array, bit for bit, with array operations.

The engine sums a sprite's position, increment and reaction shifts with `math.fsum`, which is
correctly rounded (so independent of the order of the terms) and returns +0.0 for a zero sum. A
column with at most two non-zero terms is their plain float sum (one correctly rounded addition);
the others go through CPython's own algorithm (Shewchuk's partials, then the half-even fix-up),
emulated here column-wise with masks: a zero partial stands for one CPython drops, which changes
nothing, since adding a zero partial leaves the running sum as it was.
"""

from __future__ import annotations

import numpy as np


def fsum_columns(terms: np.ndarray) -> np.ndarray:
    """`math.fsum(terms[:, j])` for every column j of the (K, M) float64 array `terms`."""
    nonzero = terms != 0.0
    count = nonzero.sum(axis=0)
    # zeros add nothing to a non-zero sum; + 0.0 turns a -0.0 result into fsum's +0.0
    result = terms.sum(axis=0) + 0.0
    hard = np.flatnonzero(count > 2)
    if hard.size:
        subset = terms[:, hard]
        # the non-zero terms first (fsum's result does not depend on their order)
        order = np.argsort(subset == 0.0, axis=0, kind="stable")
        subset = np.take_along_axis(subset, order, axis=0)[: int(count[hard].max())]
        result[hard] = _fsum_exact(subset)
    return result


def _fsum_exact(terms: np.ndarray) -> np.ndarray:
    """CPython's fsum of each column (finite values), with masks instead of branches."""
    rows, width = terms.shape
    partials = np.zeros((rows, width))
    for k in range(rows):
        x = terms[k].copy()
        live = x != 0.0
        for j in range(k):
            y = partials[j]
            active = live & (y != 0.0)
            swap = np.abs(x) < np.abs(y)
            big = np.where(swap, y, x)
            small = np.where(swap, x, y)
            hi = big + small
            lo = small - (hi - big)
            partials[j] = np.where(active, lo, y)
            x = np.where(active, hi, x)
        partials[k] = np.where(live, x, 0.0)
    # sum_exact from the top partial down, stopping at the first inexact addition
    hi = np.zeros(width)
    lo = np.zeros(width)
    started = np.zeros(width, dtype=bool)
    stopped = np.zeros(width, dtype=bool)
    below = np.zeros(width)  # the first non-zero partial under the one that stopped the sum
    found = np.zeros(width, dtype=bool)
    for j in range(rows - 1, -1, -1):
        y = partials[j]
        present = y != 0.0
        take_below = present & stopped & ~found
        below = np.where(take_below, y, below)
        found |= take_below
        adding = present & started & ~stopped
        total = hi + y
        error = y - (total - hi)
        hi = np.where(adding, total, np.where(present & ~started, y, hi))
        stops = adding & (error != 0.0)
        lo = np.where(stops, error, lo)
        stopped |= stops
        started |= present
    # half-even rounding across partials
    fix = found & (((lo < 0.0) & (below < 0.0)) | ((lo > 0.0) & (below > 0.0)))
    doubled = lo * 2.0
    moved = hi + doubled
    fix &= (moved - hi) == doubled
    return np.where(fix, moved, hi) + 0.0
