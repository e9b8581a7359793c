"""numba kernels that index a world's edges and circles in a uniform grid (private).

The world's static obstacles are line segments ``(x0, y0, x1, y1)`` (polygon
edges and walls) and circles ``(cx, cy, r)``. :func:`build_cell_lists` files
each of them in every cell of a uniform grid that it touches (conservatively:
a primitive lying on a cell boundary is filed on both sides), as a CSR list:
cell ``k = row * nx + col`` holds ``items[start[k]:start[k + 1]]``; an item
``i < n_segments`` is segment ``i``, otherwise circle ``i - n_segments``. A
circle is filed only in the cells its boundary crosses, since rays and
clearances only ever meet the boundary.

:func:`chebyshev_distance` is the chessboard distance transform of an
occupancy mask, used to skip free space when a ray crosses an occupancy grid.

Examples
--------
>>> import numpy as np
>>> segs = np.array([[0.0, 0.5, 2.0, 0.5]])
>>> start, items = build_cell_lists(segs, np.empty((0, 3)), 0.0, 0.0, 1.0, 2, 2, 100)
>>> start.tolist(), items.tolist()
([0, 1, 2, 2, 2], [0, 0])
>>> chebyshev_distance(np.array([[1, 0, 0, 0]], dtype=np.uint8)).tolist()
[[0, 1, 2, 3]]
"""

from __future__ import annotations

import math

import numpy as np

from navkit._shared.jit import njit_cached

__all__ = ["build_cell_lists", "chebyshev_distance"]

# Relative widening (in cells) of every primitive when it is filed: a primitive
# within this distance of a cell boundary is filed in both cells, so rounding
# can never hide it from a ray or a clearance query.
_PAD = 1e-6


@njit_cached
def _clamp(i: int, hi: int) -> int:
    if i < 0:
        return 0
    if i > hi:
        return hi
    return i


@njit_cached
def _file_segment(
    x0: float,
    y0: float,
    x1: float,
    y1: float,
    gx0: float,
    gy0: float,
    inv_h: float,
    nx: int,
    ny: int,
    item: int,
    counts: np.ndarray,
    start: np.ndarray,
    items: np.ndarray,
    fill: bool,
) -> None:
    """Count (or, with ``fill``, store) segment ``item`` in every cell it touches.

    Row by row: the part of the segment inside the row's slab (widened by
    ``_PAD`` cells) spans a range of columns, all of which are marked.
    """
    # Endpoints in cell units.
    u0 = (x0 - gx0) * inv_h
    v0 = (y0 - gy0) * inv_h
    u1 = (x1 - gx0) * inv_h
    v1 = (y1 - gy0) * inv_h
    row_lo = _clamp(math.floor(min(v0, v1) - _PAD), ny - 1)
    row_hi = _clamp(math.floor(max(v0, v1) + _PAD), ny - 1)
    dv = v1 - v0
    for r in range(row_lo, row_hi + 1):
        lo = r - _PAD
        hi = r + 1 + _PAD
        if dv != 0.0:
            ta = (lo - v0) / dv
            tb = (hi - v0) / dv
            if ta > tb:
                ta, tb = tb, ta
            ta = max(ta, 0.0)
            tb = min(tb, 1.0)
            if ta > tb:
                continue
        else:
            ta = 0.0
            tb = 1.0
        ua = u0 + ta * (u1 - u0)
        ub = u0 + tb * (u1 - u0)
        c_lo = _clamp(math.floor(min(ua, ub) - _PAD), nx - 1)
        c_hi = _clamp(math.floor(max(ua, ub) + _PAD), nx - 1)
        for c in range(c_lo, c_hi + 1):
            k = r * nx + c
            if fill:
                items[start[k] + counts[k]] = item
            counts[k] += 1


@njit_cached
def _file_circle(
    cx: float,
    cy: float,
    radius: float,
    gx0: float,
    gy0: float,
    h: float,
    nx: int,
    ny: int,
    item: int,
    counts: np.ndarray,
    start: np.ndarray,
    items: np.ndarray,
    fill: bool,
) -> None:
    """Count (or store) circle ``item`` in every cell its boundary may cross."""
    inv_h = 1.0 / h
    pad = _PAD * h
    c_lo = _clamp(math.floor((cx - radius - gx0) * inv_h - _PAD), nx - 1)
    c_hi = _clamp(math.floor((cx + radius - gx0) * inv_h + _PAD), nx - 1)
    r_lo = _clamp(math.floor((cy - radius - gy0) * inv_h - _PAD), ny - 1)
    r_hi = _clamp(math.floor((cy + radius - gy0) * inv_h + _PAD), ny - 1)
    for r in range(r_lo, r_hi + 1):
        ya = gy0 + r * h
        yb = ya + h
        for c in range(c_lo, c_hi + 1):
            xa = gx0 + c * h
            xb = xa + h
            # Nearest and farthest points of the cell from the centre.
            nx_ = min(max(cx, xa), xb) - cx
            ny_ = min(max(cy, ya), yb) - cy
            fx = max(abs(xa - cx), abs(xb - cx))
            fy = max(abs(ya - cy), abs(yb - cy))
            near = math.sqrt(nx_ * nx_ + ny_ * ny_)
            far = math.sqrt(fx * fx + fy * fy)
            if near <= radius + pad and far >= radius - pad:
                k = r * nx + c
                if fill:
                    items[start[k] + counts[k]] = item
                counts[k] += 1


@njit_cached
def _file_all(
    segs: np.ndarray,
    circles: np.ndarray,
    gx0: float,
    gy0: float,
    h: float,
    nx: int,
    ny: int,
    counts: np.ndarray,
    start: np.ndarray,
    items: np.ndarray,
    fill: bool,
) -> None:
    inv_h = 1.0 / h
    n_seg = segs.shape[0]
    for i in range(n_seg):
        _file_segment(
            segs[i, 0], segs[i, 1], segs[i, 2], segs[i, 3],
            gx0, gy0, inv_h, nx, ny, i, counts, start, items, fill,
        )  # fmt: skip
    for j in range(circles.shape[0]):
        _file_circle(
            circles[j, 0], circles[j, 1], circles[j, 2],
            gx0, gy0, h, nx, ny, n_seg + j, counts, start, items, fill,
        )  # fmt: skip


@njit_cached
def build_cell_lists(
    segs: np.ndarray,
    circles: np.ndarray,
    gx0: float,
    gy0: float,
    h: float,
    nx: int,
    ny: int,
    max_items: int,
) -> tuple[np.ndarray, np.ndarray]:
    """CSR cell lists ``(start (nx*ny + 1,), items (M,))`` of segments and circles.

    When the lists would hold more than ``max_items`` entries nothing is
    filed: ``items`` is empty and ``start[-1]`` is the number that was needed.

    Parameters
    ----------
    segs : float64 (S, 4)
        Segments ``x0, y0, x1, y1``.
    circles : float64 (C, 3)
        Circles ``cx, cy, r``.
    gx0, gy0 : float
        World position of the grid's lower-left corner.
    h : float
        Cell size.
    nx, ny : int
        Columns and rows.
    """
    n_cells = nx * ny
    counts = np.zeros(n_cells, dtype=np.int64)
    dummy = np.zeros(1, dtype=np.int64)
    _file_all(segs, circles, gx0, gy0, h, nx, ny, counts, dummy, dummy, False)
    start = np.zeros(n_cells + 1, dtype=np.int64)
    for k in range(n_cells):
        start[k + 1] = start[k] + counts[k]
    if start[n_cells] > max_items:
        return start, np.empty(0, dtype=np.int64)
    items = np.empty(start[n_cells], dtype=np.int64)
    counts[:] = 0
    _file_all(segs, circles, gx0, gy0, h, nx, ny, counts, start, items, True)
    return start, items


@njit_cached
def chebyshev_distance(occ: np.ndarray) -> np.ndarray:
    """Chessboard distance (in cells) from every cell to the nearest occupied one.

    Two raster passes with unit weights over the 8-neighbourhood give the exact
    chessboard distance. Cells of a grid with no occupied cell get
    ``rows + cols`` (larger than any distance inside the grid). Returns int32
    ``(rows, cols)``; occupied cells (``occ != 0``) are 0.
    """
    rows, cols = occ.shape
    big = rows + cols
    d = np.empty((rows, cols), dtype=np.int32)
    for r in range(rows):
        for c in range(cols):
            if occ[r, c] != 0:
                d[r, c] = 0
                continue
            best = big
            if r > 0:
                best = min(best, d[r - 1, c] + 1)
                if c > 0:
                    best = min(best, d[r - 1, c - 1] + 1)
                if c + 1 < cols:
                    best = min(best, d[r - 1, c + 1] + 1)
            if c > 0:
                best = min(best, d[r, c - 1] + 1)
            d[r, c] = best
    for r in range(rows - 1, -1, -1):
        for c in range(cols - 1, -1, -1):
            best = d[r, c]
            if best == 0:
                continue
            if r + 1 < rows:
                best = min(best, d[r + 1, c] + 1)
                if c > 0:
                    best = min(best, d[r + 1, c - 1] + 1)
                if c + 1 < cols:
                    best = min(best, d[r + 1, c + 1] + 1)
            if c + 1 < cols:
                best = min(best, d[r, c + 1] + 1)
            d[r, c] = best
    return d
