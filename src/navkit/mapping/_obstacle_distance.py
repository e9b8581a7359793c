"""Distance from every cell to the nearest occupied cell, the basis of inflation (private).

Examples
--------
>>> import numpy as np
>>> obstacle_distance(np.array([[True, False, False]]))
array([[0., 1., 2.]])
"""

from __future__ import annotations

import math
from collections.abc import Iterator

import numpy as np

from navkit._shared.float32 import intended_resolution
from navkit._shared.types import BoolArray, FloatArray
from navkit.mapping._edt_kernels import band_distances

__all__ = [
    "CELL_EPS",
    "Band",
    "obstacle_distance",
    "obstacle_distance_bands",
    "reach_cells",
]

#: Cells of a band of :func:`obstacle_distance_bands`: ``(rows, cols)`` slices.
Band = tuple[slice, slice]

#: Distances compared against radii get this slack (in cells) so that radii that
#: are exact multiples of the resolution include the cells at that distance.
CELL_EPS = 1e-9


def reach_cells(radius: float, resolution: float) -> float:
    """How far, in cells, a ``radius`` (m) reaches: cells at most this far lie within it.

    ``radius / resolution`` with :data:`CELL_EPS` of slack, or, for a float32
    resolution above the decimal it stands for (:func:`intended_resolution`),
    ``radius`` in cells of that decimal: the cells a radius reaches on a map
    read from a ROS message are those it reaches on the same map read from its
    YAML.

    Examples
    --------
    >>> reach_cells(0.15, 0.05) >= 3.0  # 0.15 / 0.05 is 2.9999999999999996
    True
    >>> 0.15 / float(np.float32(0.05)) < 3.0 <= reach_cells(0.15, float(np.float32(0.05)))
    True
    >>> reach_cells(0.1499, 0.05) < 3.0
    True
    """
    return radius / min(resolution, intended_resolution(resolution)) + CELL_EPS


# Cells of a band of :func:`obstacle_distance_bands`: its int64 column distances
# and float64 result, 16 bytes a cell, 32 MiB.
_BAND_CELLS = 1 << 21


def obstacle_distance(occupied: BoolArray) -> FloatArray:
    """Distance in cells from each cell centre to the nearest occupied cell centre.

    Exact Euclidean distance transform; ``inf`` everywhere when nothing is occupied.

    Notes
    -----
    The bands of :func:`obstacle_distance_bands` put together, computed in
    place: peak memory the float64 result (8 bytes a cell) and a band's int64
    column distances. Bit for bit the distances of
    :func:`scipy.ndimage.distance_transform_edt` (``sqrt(dy**2 + dx**2)`` in
    float64 of the nearest occupied cell's offsets; see
    :mod:`navkit.mapping._edt_kernels`), which took 18 bytes a cell inside
    SciPy (review 45).

    Examples
    --------
    >>> obstacle_distance(np.zeros((1, 2), dtype=bool))
    array([[inf, inf]])
    """
    out = np.empty(occupied.shape, dtype=np.float64)
    if _by_columns(*occupied.shape):
        for where, dist in obstacle_distance_bands(occupied):
            out[where] = dist
            del dist  # before the next band is made: one band's distances at a time
    else:
        # Each band computed in place in the result: no band-sized copy.
        for _ in _row_bands(np.ascontiguousarray(occupied, dtype=np.bool_), out):
            pass
    return out


def _by_columns(rows: int, cols: int) -> bool:
    """Whether a grid goes by bands of columns: a band of ``sqrt(rows)`` rows is too many cells."""
    return cols > rows and math.isqrt(rows) * cols > _BAND_CELLS


def _band_rows(rows: int, cols: int) -> int:
    """Rows of a band: about :data:`_BAND_CELLS` cells, and at least ``sqrt(rows)``.

    Each band keeps a checkpoint of ``cols`` int64 (the nearest occupied row
    below it): bands of a few rows of a wide grid would cost up to 8 bytes a
    cell in checkpoints, ``sqrt(rows)`` rows a band keep them to
    ``8 * cols * sqrt(rows)`` bytes.
    """
    return max(1, _BAND_CELLS // max(cols, 1), math.isqrt(rows))


def obstacle_distance_bands(occupied: BoolArray) -> Iterator[tuple[Band, FloatArray]]:
    """:func:`obstacle_distance` band by band: ``(where, distances of the cells [where])``.

    ``where`` is a pair of slices, a band of rows ``(r0:r1, 0:cols)`` (or of
    columns ``(0:rows, c0:c1)`` for a grid much wider than tall); the bands
    cover the grid once, each band's distances a new array, exact
    (:func:`obstacle_distance`'s, bit for bit) whatever a caller's radius:
    each band is transformed from the nearest occupied cells above and below
    its columns (:mod:`navkit.mapping._edt_kernels`), not from a halo of
    neighbouring rows.

    Notes
    -----
    Peak memory besides the caller's: a band of about :data:`_BAND_CELLS`
    cells at 16 bytes a cell (its int64 column distances and float64 result;
    two bands' results, 24 bytes a cell, for a caller that keeps a band's
    distances while it asks for the next: ``del dist`` ends its loop)
    and the checkpoints of :func:`_band_rows`, under 64 MiB for any grid of
    at most 2**28 cells. A grid whose band of ``sqrt(rows)`` rows would exceed
    :data:`_BAND_CELLS` is wider than tall: it is transformed as its
    transpose (a copy, 1 byte a cell), whose bands are columns. ``occupied``
    is read as C-contiguous bool (a copy only when it is not).

    Examples
    --------
    >>> occ = np.array([[True], [False], [False], [False]])
    >>> [(where, d.ravel().tolist()) for where, d in obstacle_distance_bands(occ)]
    [((slice(0, 4, None), slice(0, 1, None)), [0.0, 1.0, 2.0, 3.0])]
    """
    if _by_columns(*occupied.shape):
        # Distances are symmetric bit for bit (dy*dy + dx*dx adds the same two
        # squares): the transpose's bands of rows are this grid's bands of columns.
        for (c, r), dist in _row_bands(np.ascontiguousarray(occupied.T, dtype=np.bool_)):
            yield (r, c), dist.T
            del dist  # see _row_bands
        return
    yield from _row_bands(np.ascontiguousarray(occupied, dtype=np.bool_))


def _row_bands(
    occupied: BoolArray, into: FloatArray | None = None
) -> Iterator[tuple[Band, FloatArray]]:
    """:func:`obstacle_distance_bands` by bands of rows, ``occupied`` C-contiguous bool.

    With ``into`` (C-contiguous float64 of ``occupied``'s shape) the bands are
    its rows, written in place; otherwise new arrays.
    """
    rows, cols = occupied.shape
    band = _band_rows(rows, cols)
    every_col = slice(0, cols)
    if not occupied.any():
        for r0 in range(0, rows, band):
            r1 = min(rows, r0 + band)
            if into is None:
                yield (slice(r0, r1), every_col), np.full((r1 - r0, cols), np.inf)
            else:
                into[r0:r1] = np.inf
                yield (slice(r0, r1), every_col), into[r0:r1]
        return
    below = np.empty((-(-rows // band), cols), dtype=np.int64)
    above = np.full(cols, -1, dtype=np.int64)
    g = np.empty((min(band, rows), cols), dtype=np.int64)
    s = np.empty(cols, dtype=np.int64)
    t = np.empty(cols, dtype=np.int64)
    for b, r0 in enumerate(range(0, rows, band)):
        r1 = min(rows, r0 + band)
        out = np.empty((r1 - r0, cols), dtype=np.float64) if into is None else into[r0:r1]
        band_distances(occupied, band, b, above, below, rows + cols, g[: r1 - r0], s, t, out)
        yield (slice(r0, r1), every_col), out
        # Not kept while the next band's array is made: with a caller that lets go of
        # it too, one band's distances at a time (16 bytes a cell, not 24; review 45).
        del out
