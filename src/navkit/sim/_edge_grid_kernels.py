"""Index a world's edges and circles in a uniform grid; chessboard distances (private).

The world's static obstacles are line segments ``(x0, y0, x1, y1)`` (polygon
edges and walls) and circles ``(cx, cy, r)``. :func:`build_cell_lists` files
each of them in every cell of a uniform grid that it touches (conservatively:
a primitive lying on a cell boundary is filed on both sides), as a CSR list:
cell ``k = row * nx + col`` holds ``items[start[k]:start[k + 1]]``, in
increasing order; an item ``i < n_segments`` is segment ``i``, otherwise circle
``i - n_segments``. A circle is filed only in the cells its boundary crosses,
since rays and clearances only ever meet the boundary.

:func:`chebyshev_distance` is the chessboard distance transform of an
occupancy mask, used to skip free space when a ray crosses an occupancy grid.

Both run once per :class:`~navkit.sim.World` and are vectorised NumPy (and
SciPy) rather than numba kernels: they would cost a second of compilation on
first use and gain nothing measurable in a call made once.

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

import numpy as np

from navkit._shared.types import FloatArray, IntArray

__all__ = ["build_cell_lists", "chebyshev_distance"]

# Relative widening (in cells) of every primitive when it is filed: a primitive
# within this distance of a cell boundary is filed in both cells, so rounding
# can never hide it from a ray or a clearance query.
_PAD = 1e-6


def _cell(x: FloatArray, hi: int) -> IntArray:
    """``floor(x)`` clamped to ``[0, hi]``."""
    return np.clip(np.floor(x).astype(np.int64), 0, hi)


def _expand(lo: IntArray, hi: IntArray) -> tuple[IntArray, IntArray]:
    """Every integer of each range ``[lo[i], hi[i]]``: ``(i, value)``, in order."""
    n = np.maximum(hi - lo + 1, 0)
    owner = np.repeat(np.arange(lo.shape[0]), n)
    first = np.cumsum(n) - n
    return owner, lo[owner] + (np.arange(owner.shape[0]) - first[owner])


def _segment_rows(
    segs: FloatArray, gx0: float, gy0: float, h: float, nx: int, ny: int
) -> tuple[IntArray, IntArray, IntArray, IntArray]:
    """Row by row, the columns each segment touches: ``(segment, row, col_lo, col_hi)``.

    The part of the segment inside the row's slab (widened by ``_PAD`` cells)
    spans a range of columns, all of which are marked.
    """
    inv_h = 1.0 / h
    # Endpoints in cell units.
    u0 = (segs[:, 0] - gx0) * inv_h
    v0 = (segs[:, 1] - gy0) * inv_h
    u1 = (segs[:, 2] - gx0) * inv_h
    v1 = (segs[:, 3] - gy0) * inv_h
    row_lo = _cell(np.minimum(v0, v1) - _PAD, ny - 1)
    row_hi = _cell(np.maximum(v0, v1) + _PAD, ny - 1)
    seg, row = _expand(row_lo, row_hi)
    u0, v0, u1, dv = u0[seg], v0[seg], u1[seg], (v1 - v0)[seg]
    lo = row - _PAD
    hi = (row + 1) + _PAD
    slanted = dv != 0.0
    with np.errstate(divide="ignore", invalid="ignore"):
        ta = (lo - v0) / dv
        tb = (hi - v0) / dv
    ta, tb = np.where(ta > tb, tb, ta), np.where(ta > tb, ta, tb)
    ta = np.where(slanted, np.maximum(ta, 0.0), 0.0)
    tb = np.where(slanted, np.minimum(tb, 1.0), 1.0)
    keep = ta <= tb
    ua = u0 + ta * (u1 - u0)
    ub = u0 + tb * (u1 - u0)
    col_lo = _cell(np.minimum(ua, ub) - _PAD, nx - 1)
    col_hi = _cell(np.maximum(ua, ub) + _PAD, nx - 1)
    return seg[keep], row[keep], col_lo[keep], col_hi[keep]


def _circle_cells(
    circles: FloatArray, gx0: float, gy0: float, h: float, nx: int, ny: int
) -> tuple[IntArray, IntArray]:
    """``(circle, cell)`` for every cell each circle's boundary may cross, in order."""
    inv_h = 1.0 / h
    pad = _PAD * h
    cx, cy, radius = circles[:, 0], circles[:, 1], circles[:, 2]
    c_lo = _cell((cx - radius - gx0) * inv_h - _PAD, nx - 1)
    c_hi = _cell((cx + radius - gx0) * inv_h + _PAD, nx - 1)
    r_lo = _cell((cy - radius - gy0) * inv_h - _PAD, ny - 1)
    r_hi = _cell((cy + radius - gy0) * inv_h + _PAD, ny - 1)
    circle_of_row, r = _expand(r_lo, r_hi)
    row_of_cell, c = _expand(c_lo[circle_of_row], c_hi[circle_of_row])
    circle = circle_of_row[row_of_cell]
    r = r[row_of_cell]
    cx, cy, radius = cx[circle], cy[circle], radius[circle]
    ya = gy0 + r * h
    yb = ya + h
    xa = gx0 + c * h
    xb = xa + h
    # Nearest and farthest points of the cell from the centre.
    near_x = np.minimum(np.maximum(cx, xa), xb) - cx
    near_y = np.minimum(np.maximum(cy, ya), yb) - cy
    far_x = np.maximum(np.abs(xa - cx), np.abs(xb - cx))
    far_y = np.maximum(np.abs(ya - cy), np.abs(yb - cy))
    near = np.sqrt(near_x * near_x + near_y * near_y)
    far = np.sqrt(far_x * far_x + far_y * far_y)
    crossed = (near <= radius + pad) & (far >= radius - pad)
    return circle[crossed], (r * nx + c)[crossed]


def build_cell_lists(
    segs: FloatArray,
    circles: FloatArray,
    gx0: float,
    gy0: float,
    h: float,
    nx: int,
    ny: int,
    max_items: int,
) -> tuple[IntArray, IntArray]:
    """CSR cell lists ``(start (nx*ny + 1,), items (M,))`` of segments and circles.

    When the lists would hold more than ``max_items`` entries nothing is
    filed: ``items`` is empty and ``start[-1]`` is the number that was needed
    (the other entries of ``start`` are then 0).

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
    max_items : int
        Most entries to file.

    Returns
    -------
    start : int64 (nx*ny + 1,)
        Cell ``k``'s items are ``items[start[k]:start[k + 1]]``.
    items : int64 (M,)
        Segment indices, then ``S + circle index``.
    """
    n_cells = nx * ny
    seg, row, col_lo, col_hi = _segment_rows(segs, gx0, gy0, h, nx, ny)
    n_seg_items = int(np.sum(col_hi - col_lo + 1))
    circle, circle_cell = _circle_cells(circles, gx0, gy0, h, nx, ny)
    total = n_seg_items + circle.shape[0]
    start = np.zeros(n_cells + 1, dtype=np.int64)
    if total > max_items:
        start[-1] = total
        return start, np.empty(0, dtype=np.int64)
    owner, col = _expand(col_lo, col_hi)
    cells = np.concatenate([row[owner] * nx + col, circle_cell])
    items = np.concatenate([seg[owner], circle + segs.shape[0]])
    np.cumsum(np.bincount(cells, minlength=n_cells), out=start[1:])
    # Stable: the items of a cell keep their (increasing) order.
    return start, items[np.argsort(cells, kind="stable")]


def chebyshev_distance(occ: np.ndarray) -> np.ndarray:
    """Chessboard distance (in cells) from every cell to the nearest occupied one.

    Cells of a grid with no occupied cell get ``rows + cols`` (larger than any
    distance inside the grid). Returns int32 ``(rows, cols)``; occupied cells
    (``occ != 0``) are 0.
    """
    from scipy.ndimage import distance_transform_cdt

    rows, cols = occ.shape
    free = occ == 0
    if free.all():
        return np.full((rows, cols), rows + cols, dtype=np.int32)
    d = distance_transform_cdt(free, metric="chessboard")
    return np.asarray(d, dtype=np.int32)
