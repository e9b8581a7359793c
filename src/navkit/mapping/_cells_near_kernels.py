"""numba kernel of :meth:`navkit.mapping.OccupancyGrid.cells_near` (private).

A cell ``(r, c)`` is near a point's cell ``(pr, pc)`` when
``sqrt(dr**2 + dc**2) <= reach`` in float64, with ``dr = r - pr`` and
``dc = c - pc`` and ``reach`` in cells: the arithmetic of the distance
transform behind :meth:`~navkit.mapping.OccupancyGrid.inflate`
(:func:`navkit.mapping._obstacle_distance.obstacle_distance`), so that the
cells near a set of points are the cells that inflating those points' cells
would mark. Rounding is monotone, so the cells of one row near one point
form an interval; the kernel adds each interval's two ends to a row buffer
and reads the row back in column order (a running sum), so the cells come
out row-major with no duplicates and no sort, and a wide disc costs no more
per row than a narrow one.

Examples
--------
>>> import numpy as np
>>> points = np.array([[1, 1]])
>>> edges = np.zeros(4, dtype=np.int64)
>>> out = np.empty((5, 2), dtype=np.int64)
>>> cells_near_kernel(points, 3, 3, 1.0 + 1e-9, 1, edges, out, True)
5
>>> out.tolist()
[[0, 1], [1, 0], [1, 1], [1, 2], [2, 1]]
"""

from __future__ import annotations

import math

import numpy as np

from navkit._shared.jit import njit_cached_released, njit_helper

__all__ = ["cells_near_kernel"]


@njit_helper
def _reached(d: int, c: int, reach: float) -> bool:
    """Whether offset ``(d, c)`` cells lies within ``reach``, as the distance transform rounds."""
    fd = float(d)
    fc = float(c)
    return math.sqrt(fd * fd + fc * fc) <= reach


@njit_helper
def _half_width(d: int, reach: float) -> int:
    """Largest ``c >= 0`` with ``_reached(d, c, reach)``; ``_reached(d, 0, reach)`` must hold.

    The square root of ``(reach - d)(reach + d)`` is the answer in exact
    arithmetic; rounding can move the float rule's edge away from it (by
    many cells where ``d**2`` exceeds 2**53, a reach of about 1e12 cells),
    so the edge is found by galloping from that estimate and bisecting.
    """
    est = (reach - d) * (reach + d)
    c = math.floor(math.sqrt(est)) if est > 0.0 else 0
    step = 1
    if _reached(d, c, reach):
        lo = c
        while _reached(d, lo + step, reach):
            lo += step
            step *= 2
        hi = lo + step
    else:
        hi = c
        while hi - step > 0 and not _reached(d, hi - step, reach):
            hi -= step
            step *= 2
        lo = hi - step if hi - step > 0 else 0
    # _reached(d, lo) holds and _reached(d, hi) does not.
    while hi - lo > 1:
        mid = lo + (hi - lo) // 2
        if _reached(d, mid, reach):
            lo = mid
        else:
            hi = mid
    return lo


@njit_cached_released
def cells_near_kernel(
    points: np.ndarray,
    rows: int,
    cols: int,
    reach: float,
    k: int,
    edges: np.ndarray,
    out: np.ndarray,
    write: bool,
) -> int:
    """Count (and with ``write``, list in ``out``) the grid cells near any of ``points``.

    ``points`` (P, 2) int64: distinct cells ``(row, col)`` sorted by row, each
    within ``k`` cells of the grid (they may lie outside it). ``reach`` (cells)
    is the radius with the inflation's slack; ``k = floor(reach)``, the
    farthest row offset reached (exact: ``sqrt(d * d)`` rounds to ``d`` for
    every integer below 2**53). ``edges`` (cols + 1,) int64 zeros, left zero.
    ``out`` (K, 2) int64 receives the cells row-major when ``write``.
    Work: each point's rows inside the grid, plus, in each row, the columns
    between the first and last cell found there.
    """
    n = points.shape[0]
    count = 0
    lo = 0  # points[lo:hi] reach row r: |points[i, 0] - r| <= k
    hi = 0
    r = 0
    while r < rows and lo < n:
        while lo < n and points[lo, 0] + k < r:
            lo += 1
        if lo == n:
            break
        if points[lo, 0] - k > r:
            r = points[lo, 0] - k  # no point reaches the rows before this one
            continue
        if hi < lo:
            hi = lo
        while hi < n and points[hi, 0] - k <= r:
            hi += 1
        first = cols
        last = -1
        for i in range(lo, hi):
            pc = points[i, 1]
            if pc + k < 0 or pc - k >= cols:
                continue
            d = r - points[i, 0]
            w = _half_width(d if d >= 0 else -d, reach)
            # Selects, not the min/max builtins: numba compiles those as overloads
            # of their own on first use.
            a = pc - w if pc - w > 0 else 0
            b = pc + w if pc + w < cols - 1 else cols - 1
            if a > b:
                continue
            # The interval as +1 at its start and -1 past its end: O(1) however
            # wide the disc (a radius covering the map costs a row, not a disc).
            edges[a] += 1
            edges[b + 1] -= 1
            first = a if a < first else first
            last = b if b > last else last
        # The row's cells, in column order: where the running sum of edges is
        # positive. The sum is cleared as it is read.
        covering = 0
        for c in range(first, last + 2):
            covering += edges[c]
            edges[c] = 0
            if covering > 0 and c <= last:
                if write:
                    out[count, 0] = r
                    out[count, 1] = c
                count += 1
        r += 1
    return count
