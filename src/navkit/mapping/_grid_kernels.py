"""numba kernels for world-to-cell conversion of many points (private).

Plain functions on arrays and scalars compiled with ``cache=True``;
:class:`navkit.mapping.OccupancyGrid` validates input before calling them. Grid
cells are ``(row, col)``; continuous grid coordinates put integers at cell
centres (cell ``(r, c)`` covers ``[r - ½, r + ½) × [c - ½, c + ½)``).

Examples
--------
>>> import numpy as np
>>> out = np.empty((1, 2), dtype=np.int64)
>>> world_to_cell_kernel(np.array([[0.7, 0.2]]), 0.0, 0.0, 0.0, 0.5, out)
>>> out
array([[0, 1]])
>>> cont = np.empty((1, 2))
>>> world_to_continuous_kernel(np.array([[0.7, 0.2]]), 0.0, 0.0, 0.0, 0.5, cont)
>>> cont.round(12)
array([[-0.1,  0.9]])
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

__all__ = ["world_to_cell_kernel", "world_to_continuous_kernel"]


@njit(cache=True)
def world_to_cell_kernel(
    points: np.ndarray,
    origin_x: float,
    origin_y: float,
    origin_yaw: float,
    resolution: float,
    out: np.ndarray,
) -> None:
    """Fill ``out`` (N, 2) int64 with the ``(row, col)`` cell of each ``(x, y)`` point.

    The cell is ``floor`` of the point's coordinates in the grid frame divided by
    the resolution, so indices outside the grid are returned as they are.
    """
    inv_res = 1.0 / resolution
    c = math.cos(origin_yaw)
    s = math.sin(origin_yaw)
    for i in range(points.shape[0]):
        dx = points[i, 0] - origin_x
        dy = points[i, 1] - origin_y
        out[i, 0] = math.floor((-s * dx + c * dy) * inv_res)
        out[i, 1] = math.floor((c * dx + s * dy) * inv_res)


@njit(cache=True)
def world_to_continuous_kernel(
    points: np.ndarray,
    origin_x: float,
    origin_y: float,
    origin_yaw: float,
    resolution: float,
    out: np.ndarray,
) -> None:
    """Fill ``out`` (N, 2) float64 with continuous ``(row, col)`` coordinates of points.

    Integers are cell centres: a point at the lower-left corner of cell (0, 0) is
    at ``(-0.5, -0.5)``.
    """
    inv_res = 1.0 / resolution
    c = math.cos(origin_yaw)
    s = math.sin(origin_yaw)
    for i in range(points.shape[0]):
        dx = points[i, 0] - origin_x
        dy = points[i, 1] - origin_y
        out[i, 0] = (-s * dx + c * dy) * inv_res - 0.5
        out[i, 1] = (c * dx + s * dy) * inv_res - 0.5
