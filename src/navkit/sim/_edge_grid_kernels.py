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

from collections.abc import Iterator

import numpy as np

from navkit._shared.types import FloatArray, IntArray

__all__ = ["build_cell_lists", "chebyshev_distance"]

# Relative widening (in cells) of every primitive when it is filed: a primitive
# within this distance of a cell boundary is filed in both cells, so rounding
# can never hide it from a ray or a clearance query.
_PAD = 1e-6
#: Most segments, row spans, entries or candidate cells of a block of
#: :func:`build_cell_lists` (its temporaries: about 10 MiB).
_BLOCK = 1 << 16
#: Most circles of a block (each has up to ``ny`` rows of candidate cells).
_CIRCLE_BLOCK = 1 << 8
#: Most entries whose blocks the first pass keeps for the second (64 MiB).
_KEPT = 1 << 22


def _cell(x: FloatArray, hi: int) -> IntArray:
    """``floor(x)`` clamped to ``[0, hi]``."""
    return np.clip(np.floor(x).astype(np.int64), 0, hi)


def _expand(lo: IntArray, hi: IntArray) -> tuple[IntArray, IntArray]:
    """Every integer of each range ``[lo[i], hi[i]]``: ``(i, value)``, in order."""
    n = np.maximum(hi - lo + 1, 0)
    owner = np.repeat(np.arange(lo.shape[0]), n)
    first = np.cumsum(n) - n
    return owner, lo[owner] + (np.arange(owner.shape[0]) - first[owner])


def _blocks(weights: IntArray, limit: int) -> Iterator[slice]:
    """Consecutive slices of ``weights`` each summing to at most ``limit`` (or one item)."""
    ends = np.cumsum(weights)
    i, done = 0, 0
    while i < ends.shape[0]:
        j = max(i + 1, int(np.searchsorted(ends, done + limit, side="right")))
        yield slice(i, j)
        done = int(ends[j - 1])
        i = j


def _segment_row_range(
    segs: FloatArray, gy0: float, h: float, ny: int
) -> tuple[IntArray, IntArray]:
    """The first and last rows each segment touches (widened by ``_PAD`` cells)."""
    inv_h = 1.0 / h
    v0 = (segs[:, 1] - gy0) * inv_h
    v1 = (segs[:, 3] - gy0) * inv_h
    return _cell(np.minimum(v0, v1) - _PAD, ny - 1), _cell(np.maximum(v0, v1) + _PAD, ny - 1)


def _segment_rows(
    segs: FloatArray,
    row_lo: IntArray,
    row_hi: IntArray,
    gx0: float,
    gy0: float,
    h: float,
    nx: int,
) -> tuple[IntArray, IntArray, IntArray, IntArray]:
    """Row by row, the columns each segment touches: ``(segment, row, col_lo, col_hi)``.

    The part of the segment inside the row's slab (widened by ``_PAD`` cells)
    spans a range of columns, all of which are marked. ``row_lo`` and
    ``row_hi`` are :func:`_segment_row_range`'s.
    """
    inv_h = 1.0 / h
    # Endpoints in cell units.
    u0 = (segs[:, 0] - gx0) * inv_h
    v0 = (segs[:, 1] - gy0) * inv_h
    u1 = (segs[:, 2] - gx0) * inv_h
    v1 = (segs[:, 3] - gy0) * inv_h
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


def _segment_entries(
    segs: FloatArray, gx0: float, gy0: float, h: float, nx: int, ny: int
) -> Iterator[tuple[IntArray, IntArray]]:
    """``(cell, segment)`` of every entry of the segments, in blocks, in segment order.

    Segments, their row spans and the spans' cells are taken at most
    :data:`_BLOCK` at a time, so the temporaries stay about 10 MiB
    whatever the number of entries (a segment crosses at most ``ny`` rows and a
    row span at most ``nx`` cells).
    """
    for first in range(0, segs.shape[0], _BLOCK):
        part = segs[first : first + _BLOCK]
        row_lo, row_hi = _segment_row_range(part, gy0, h, ny)
        for rows in _blocks(row_hi - row_lo + 1, _BLOCK):
            seg, row, col_lo, col_hi = _segment_rows(
                part[rows], row_lo[rows], row_hi[rows], gx0, gy0, h, nx
            )
            seg += first + rows.start
            for spans in _blocks(col_hi - col_lo + 1, _BLOCK):
                owner, col = _expand(col_lo[spans], col_hi[spans])
                yield row[spans][owner] * nx + col, seg[spans][owner]


def _circle_entries(
    circles: FloatArray, gx0: float, gy0: float, h: float, nx: int, ny: int
) -> Iterator[tuple[IntArray, IntArray]]:
    """``(cell, circle)`` for every cell each circle's boundary may cross, in blocks, in order.

    The candidate cells (each circle's bounding box) are taken at most
    :data:`_BLOCK` at a time, a row of a box at least: one circle across the
    world has up to ``nx * ny`` of them.
    """
    inv_h = 1.0 / h
    pad = _PAD * h
    for first in range(0, circles.shape[0], _CIRCLE_BLOCK):
        part = circles[first : first + _CIRCLE_BLOCK]
        cx, cy, radius = part[:, 0], part[:, 1], part[:, 2]
        c_lo = _cell((cx - radius - gx0) * inv_h - _PAD, nx - 1)
        c_hi = _cell((cx + radius - gx0) * inv_h + _PAD, nx - 1)
        r_lo = _cell((cy - radius - gy0) * inv_h - _PAD, ny - 1)
        r_hi = _cell((cy + radius - gy0) * inv_h + _PAD, ny - 1)
        circle_of_row, rows_r = _expand(r_lo, r_hi)
        for rows in _blocks((c_hi - c_lo + 1)[circle_of_row], _BLOCK):
            of_row = circle_of_row[rows]
            row_of_cell, c = _expand(c_lo[of_row], c_hi[of_row])
            circle = of_row[row_of_cell]
            r = rows_r[rows][row_of_cell]
            ccx, ccy, rad = cx[circle], cy[circle], radius[circle]
            ya = gy0 + r * h
            yb = ya + h
            xa = gx0 + c * h
            xb = xa + h
            # Nearest and farthest points of the cell from the centre.
            near_x = np.minimum(np.maximum(ccx, xa), xb) - ccx
            near_y = np.minimum(np.maximum(ccy, ya), yb) - ccy
            far_x = np.maximum(np.abs(xa - ccx), np.abs(xb - ccx))
            far_y = np.maximum(np.abs(ya - ccy), np.abs(yb - ccy))
            near = np.sqrt(near_x * near_x + near_y * near_y)
            far = np.sqrt(far_x * far_x + far_y * far_y)
            crossed = (near <= rad + pad) & (far >= rad - pad)
            yield (r * nx + c)[crossed], circle[crossed] + first


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

    Two passes over the entries, made a block at a time: the first counts
    each cell's entries, the second files each block's entries in place
    (sorted by cell within the block, stably, after the earlier blocks'). The
    peak is the result (8 bytes an entry, ``start``) and a block's temporaries;
    sorting every entry at once took about 80 bytes an entry (8 GB at the
    world's limit of 10**8 entries). Worlds of a few blocks keep the first
    pass's blocks instead of making them again.

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
    n_segs = segs.shape[0]

    def entries() -> Iterator[tuple[IntArray, IntArray]]:
        yield from _segment_entries(segs, gx0, gy0, h, nx, ny)
        for cells, circle in _circle_entries(circles, gx0, gy0, h, nx, ny):
            yield cells, circle + n_segs

    start = np.zeros(n_cells + 1, dtype=np.int64)
    counts = start[1:]
    kept: list[tuple[IntArray, IntArray]] | None = []
    held = 0
    for cells, items in entries():
        np.add.at(counts, cells, 1)
        if kept is not None:
            held += cells.shape[0]
            if held <= _KEPT:
                kept.append((cells, items))
            else:
                kept = None  # made again in the second pass
    total = int(counts.sum())
    if total > max_items:
        start[:] = 0
        start[-1] = total
        return start, np.empty(0, dtype=np.int64)
    np.cumsum(counts, out=counts)
    out = np.empty(total, dtype=np.int64)
    fill = start[:-1].copy()
    for cells, items in entries() if kept is None else kept:
        order = np.argsort(cells, kind="stable")
        by_cell = cells[order]
        group = np.flatnonzero(np.diff(by_cell, prepend=-1))  # each cell's first entry
        size = np.diff(group, append=by_cell.shape[0])
        rank = np.arange(by_cell.shape[0]) - np.repeat(group, size)
        out[fill[by_cell] + rank] = items[order]
        fill[by_cell[group]] += size
    return start, out


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
