"""numba kernel: distance from many points to a polyline (private).

Used for the cross-track error of a run against its reference path.

Examples
--------
>>> import numpy as np
>>> out = np.empty(2)
>>> point_polyline_distances(np.array([[0.5, 1.0], [3.0, 0.0]]),
...                          np.array([[0.0, 0.0], [2.0, 0.0]]), out)
>>> out.tolist()
[1.0, 1.0]
"""

from __future__ import annotations

import math

import numpy as np

from navkit._shared.jit import njit_no_refcount

__all__ = ["point_polyline_distances"]


@njit_no_refcount
def point_polyline_distances(points: np.ndarray, path: np.ndarray, out: np.ndarray) -> None:
    """``out[i]``: distance from ``points[i]`` to the polyline ``path`` (K >= 1 vertices)."""
    k = path.shape[0]
    for i in range(points.shape[0]):
        px = points[i, 0]
        py = points[i, 1]
        best = math.hypot(px - path[0, 0], py - path[0, 1])
        for j in range(k - 1):
            ax = path[j, 0]
            ay = path[j, 1]
            ex = path[j + 1, 0] - ax
            ey = path[j + 1, 1] - ay
            wx = px - ax
            wy = py - ay
            ee = ex * ex + ey * ey
            t = 0.0
            if ee > 0.0:
                t = min(max((wx * ex + wy * ey) / ee, 0.0), 1.0)
            d = math.hypot(wx - t * ex, wy - t * ey)
            if d < best:
                best = d
        out[i] = best
