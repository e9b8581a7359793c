"""numba kernel placing moving obstacles at a time (private).

Each moving obstacle ``m`` follows the polyline ``path_xy[first[m]:first[m] +
count[m]]`` reached at ``times[...]`` (strictly increasing), interpolated
linearly. Before its first time it waits at the first point; after its last it
stops (``after == STOP``), starts over (``LOOP``) or keeps the last segment's
velocity (``EXTEND``). Its shape is a set of segments and circles given
relative to its reference point, translated (never rotated) to its position.
``point_in_moving`` (for other kernels only) tells whether a point lies inside
one of the placed obstacles (all solid).

Examples
--------
>>> import numpy as np
>>> out_segs, out_circles = np.empty((0, 4)), np.empty((1, 3))
>>> place_moving(
...     2.5, np.array([[0.0, 0.0], [1.0, 0.0]]), np.array([0.0, 1.0]),
...     np.array([0]), np.array([2]), np.array([EXTEND]),
...     np.empty((0, 4)), np.empty(0, dtype=np.int64), out_segs,
...     np.array([[0.0, 0.0, 0.3]]), np.array([0]), out_circles)
>>> out_circles.tolist()
[[2.5, 0.0, 0.3]]
"""

from __future__ import annotations

import math

import numpy as np

from navkit._shared.jit import njit_helper, njit_no_refcount

__all__ = ["EXTEND", "LOOP", "STOP", "place_moving", "point_in_moving"]


STOP = 0
LOOP = 1
EXTEND = 2


@njit_helper
def _position(
    t: float, path_xy: np.ndarray, times: np.ndarray, first: int, count: int, after: int
) -> tuple[float, float]:
    last = first + count - 1
    if count == 1 or t <= times[first]:
        return path_xy[first, 0], path_xy[first, 1]
    t0 = times[first]
    t1 = times[last]
    if t >= t1:
        if after == STOP:
            return path_xy[last, 0], path_xy[last, 1]
        if after == LOOP:
            t = t0 + (t - t0) % (t1 - t0)
        else:
            a = last - 1
            f = (t - times[a]) / (times[last] - times[a])
            x = path_xy[a, 0] + f * (path_xy[last, 0] - path_xy[a, 0])
            y = path_xy[a, 1] + f * (path_xy[last, 1] - path_xy[a, 1])
            return x, y
    # Binary search for the segment [times[a], times[a + 1]] holding t.
    lo = first
    hi = last
    while hi - lo > 1:
        mid = (lo + hi) // 2
        if times[mid] <= t:
            lo = mid
        else:
            hi = mid
    f = (t - times[lo]) / (times[hi] - times[lo])
    x = path_xy[lo, 0] + f * (path_xy[hi, 0] - path_xy[lo, 0])
    y = path_xy[lo, 1] + f * (path_xy[hi, 1] - path_xy[lo, 1])
    return x, y


@njit_no_refcount
def place_moving(
    t: float,
    path_xy: np.ndarray,
    times: np.ndarray,
    first: np.ndarray,
    count: np.ndarray,
    after: np.ndarray,
    base_segs: np.ndarray,
    seg_owner: np.ndarray,
    out_segs: np.ndarray,
    base_circles: np.ndarray,
    circle_owner: np.ndarray,
    out_circles: np.ndarray,
) -> None:
    """Write every moving obstacle's segments and circles at time ``t``."""
    n_seg = base_segs.shape[0]
    n_circ = base_circles.shape[0]
    i_seg = 0
    i_circ = 0
    for m in range(first.shape[0]):
        x, y = _position(t, path_xy, times, first[m], count[m], after[m])
        while i_seg < n_seg and seg_owner[i_seg] == m:
            out_segs[i_seg, 0] = base_segs[i_seg, 0] + x
            out_segs[i_seg, 1] = base_segs[i_seg, 1] + y
            out_segs[i_seg, 2] = base_segs[i_seg, 2] + x
            out_segs[i_seg, 3] = base_segs[i_seg, 3] + y
            i_seg += 1
        while i_circ < n_circ and circle_owner[i_circ] == m:
            out_circles[i_circ, 0] = base_circles[i_circ, 0] + x
            out_circles[i_circ, 1] = base_circles[i_circ, 1] + y
            out_circles[i_circ, 2] = base_circles[i_circ, 2]
            i_circ += 1


@njit_helper
def point_in_moving(
    px: float, py: float, segs: np.ndarray, seg_owner: np.ndarray, circles: np.ndarray
) -> bool:
    """Whether ``(px, py)`` lies inside a placed moving obstacle (``place_moving``'s output).

    Inside a disc: nearer its centre than its radius. A polygon obstacle's
    edges are consecutive rows of ``segs`` with the same owner (even-odd rule
    over them, a point on the horizontal through a vertex counted above it).
    """
    for m in range(circles.shape[0]):
        if math.hypot(px - circles[m, 0], py - circles[m, 1]) < circles[m, 2]:
            return True
    inside = False
    for m in range(segs.shape[0]):
        if m > 0 and seg_owner[m] != seg_owner[m - 1]:
            if inside:
                return True
            inside = False
        ay = segs[m, 1]
        by = segs[m, 3]
        if (ay > py) != (by > py):
            ax = segs[m, 0]
            x_cross = ax + (py - ay) * (segs[m, 2] - ax) / (by - ay)
            if px < x_cross:
                inside = not inside
    return inside
