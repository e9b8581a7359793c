"""The exact Euclidean distance transform of any boolean mask of cells (public face).

Examples
--------
>>> distance_transform(np.array([[True, False, False]]), resolution=0.5)
array([[0. , 0.5, 1. ]])
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike

from navkit._shared.types import FloatArray
from navkit.mapping._grid import _bool_grid
from navkit.mapping._limits import check_cell_count, resolution_float
from navkit.mapping._obstacle_distance import obstacle_distance

__all__ = ["distance_transform"]


def distance_transform(mask: ArrayLike, *, resolution: float) -> FloatArray:
    """Distance (m) from each cell's centre to the centre of the nearest cell of ``mask``.

    The exact Euclidean distance transform that
    :meth:`OccupancyGrid.obstacle_distance` applies to a grid's occupied
    cells, for any set of cells: 0 on a cell of ``mask``,
    ``resolution * sqrt(drow**2 + dcol**2)`` to the nearest one elsewhere,
    ``inf`` everywhere when ``mask`` has no True cell. Obstacles that are not
    a grid's occupied cells (``~grid.free()``: unknown cells too) or the
    distance from inside obstacles to free space (``mask=grid.free()``) take
    this function.

    Parameters
    ----------
    mask : array_like of bool, shape (rows, cols)
        The cells distances are measured to (``True``), cells ``(row, col)``.
    resolution : float
        Side of a cell, m, in [1e-6, 1e6] (keyword-only; 1.0 gives distances
        in cells).

    Returns
    -------
    ndarray of float64, shape (rows, cols)
        New array of distances, m: bit for bit
        ``scipy.ndimage.distance_transform_edt(~mask) * resolution`` when
        ``mask`` has a True cell (with none, SciPy's measures to a cell
        outside the array, above its first row).

    Raises
    ------
    TypeError
        ``mask`` not a boolean array (integers are not taken as a mask);
        ``resolution`` not a real number.
    ValueError
        ``mask`` not a non-empty 2-D array or more than
        ``OccupancyGrid.MAX_CELLS`` cells; ``resolution`` outside [1e-6, 1e6].

    Notes
    -----
    Memory as :meth:`OccupancyGrid.obstacle_distance`'s: the result (8
    bytes a cell) and one band's work of about 2**21 cells (16 MiB) at a
    time, plus a C-contiguous copy of a mask that is not (1 byte a cell).
    ``mask`` is not modified.

    Examples
    --------
    >>> blocked = np.array([[True, True, False, False]])
    >>> distance_transform(blocked, resolution=0.1).round(3)
    array([[0. , 0. , 0.1, 0.2]])
    >>> distance_transform(~blocked, resolution=0.1).round(3)  # from inside to free cells
    array([[0.2, 0.1, 0. , 0. ]])
    >>> distance_transform(np.zeros((1, 2), dtype=bool), resolution=1.0)
    array([[inf, inf]])
    """
    cells = _bool_grid(mask, "mask")
    check_cell_count(float(cells.size), "mask", bytes_per_cell=8, dtype="float64")
    res = resolution_float(resolution)
    out = obstacle_distance(cells)
    # In place: the same float64 products as SciPy's distances * resolution.
    np.multiply(out, res, out=out)
    return out
