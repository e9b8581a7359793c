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

from navkit._shared.types import BoolArray, FloatArray

__all__ = ["CELL_EPS", "obstacle_distance", "obstacle_distance_bands"]

#: Distances compared against radii get this slack (in cells) so that radii that
#: are exact multiples of the resolution include the cells at that distance.
CELL_EPS = 1e-9

# Cells per tile of the distances computed from the feature transform: their
# float64 temporaries stay this small (2 x 512 KiB) whatever the grid's size.
_TILE_CELLS = 1 << 16
# Cells of a band of :func:`obstacle_distance_bands` with its halo: SciPy's
# 18 bytes a cell on them, about 36 MiB.
_BAND_CELLS = 1 << 21
# Fewest rows of a band: thinner ones (a wide grid) would cost more Python than
# transform.
_MIN_BAND_ROWS = 64


def obstacle_distance(occupied: BoolArray) -> FloatArray:
    """Distance in cells from each cell centre to the nearest occupied cell centre.

    Exact Euclidean distance transform; ``inf`` everywhere when nothing is occupied.

    Notes
    -----
    Peak memory about 18 bytes a cell and 1 MiB, reached inside SciPy: the
    inverted mask (1), SciPy's feature transform (the nearest occupied cell
    of every cell, two int32 indices: 8) and SciPy's own copies of the mask
    (``np.where(mask, 1, 0)``, int64: 8, made int8: 1); the float64 result
    (8) comes once the int64 copy is gone (measured with tracemalloc, 2048 x
    2048 cells; review 28: this said 17). The distances are computed from the
    feature transform tile by tile, as :func:`scipy.ndimage.distance_transform_edt`
    computes them (``sqrt(dy**2 + dx**2)`` in float64, so bit for bit its
    values), without its float64 temporaries of twice the grid's size (33 bytes
    a cell in all).

    Examples
    --------
    >>> obstacle_distance(np.zeros((1, 2), dtype=bool))
    array([[inf, inf]])
    """
    if not occupied.any():
        return np.full(occupied.shape, np.inf)
    from scipy import ndimage

    rows, cols = occupied.shape
    nearest = np.empty((2, rows, cols), dtype=np.int32)
    ndimage.distance_transform_edt(
        ~occupied, return_distances=False, return_indices=True, indices=nearest
    )
    out = np.empty((rows, cols), dtype=np.float64)
    tile_cols = min(cols, _TILE_CELLS)
    tile_rows = max(1, _TILE_CELLS // tile_cols)
    for r0 in range(0, rows, tile_rows):
        r1 = min(rows, r0 + tile_rows)
        row_index = np.arange(r0, r1, dtype=np.int32)[:, None]
        for c0 in range(0, cols, tile_cols):
            c1 = min(cols, c0 + tile_cols)
            dy = np.subtract(nearest[0, r0:r1, c0:c1], row_index, dtype=np.float64)
            dx = np.subtract(
                nearest[1, r0:r1, c0:c1], np.arange(c0, c1, dtype=np.int32), dtype=np.float64
            )
            np.multiply(dy, dy, out=dy)
            np.multiply(dx, dx, out=dx)
            np.add(dy, dx, out=dy)
            np.sqrt(dy, out=out[r0:r1, c0:c1])
    return out


def obstacle_distance_bands(
    occupied: BoolArray, reach: float
) -> Iterator[tuple[int, int, FloatArray]]:
    """:func:`obstacle_distance` band of rows by band: ``(r0, r1, distances of rows r0:r1)``.

    A band's distances are exact wherever they are at most ``reach`` cells and
    above ``reach`` (perhaps not exact) elsewhere: each band is transformed
    with ``floor(reach)`` rows of its neighbours on either side, which hold
    every occupied cell within ``reach`` of it. Inflation needs no more, and
    the transform's 18 bytes a cell then cover a band and its halo, about
    :data:`_BAND_CELLS` cells or ``6 * floor(reach)`` rows, instead of the
    grid: the caller's peak is its own result and a band (the whole grid at
    once when a band would cover it). The bands cover the rows in order.

    Examples
    --------
    >>> occ = np.array([[True], [False], [False], [False]])
    >>> [(r0, r1, d.ravel().tolist()) for r0, r1, d in obstacle_distance_bands(occ, 1.5)]
    [(0, 4, [0.0, 1.0, 2.0, 3.0])]
    """
    rows, cols = occupied.shape
    halo = int(min(math.floor(reach), rows)) if reach >= 0.0 else 0
    # At least four times the halo's rows a band: a window transforms at most 1.5
    # times its band's cells (the time) and 6 * halo rows (the memory, when that is
    # above _BAND_CELLS); the whole grid at once when a band would cover it anyway.
    band = max(_BAND_CELLS // cols - 2 * halo, 4 * halo, _MIN_BAND_ROWS)
    if band >= rows:
        yield 0, rows, obstacle_distance(occupied)
        return
    for r0 in range(0, rows, band):
        r1 = min(rows, r0 + band)
        w0, w1 = max(0, r0 - halo), min(rows, r1 + halo)
        yield r0, r1, obstacle_distance(occupied[w0:w1])[r0 - w0 : r1 - w0]
