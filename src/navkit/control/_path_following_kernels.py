"""numba kernels behind the path trackers' polyline geometry (private).

Plain functions on scalars and float64 arrays, compiled with ``cache=True`` and
allocating nothing; :mod:`navkit.control._path_following` validates input and
calls them. A path is given by its vertices ``pts`` (K, 2), without consecutive
duplicates, and their arc lengths ``cum`` (K,), ``cum[0] = 0``; segment ``i``
runs from ``pts[i]`` to ``pts[i + 1]``.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from navkit._shared.jit import bind_numba_names, njit_helper, njit_no_refcount

# numba's min and max builtins, without an overload compiled per argument types
# (navkit._shared.selects: intrinsics, so bound when numba loads; issue 17).
min2: Any = None
max2: Any = None
bind_numba_names(
    globals(), "navkit._shared.selects", python={"min2": min, "max2": max}, min2="min2", max2="max2"
)


@njit_helper
def segment_of(cum: np.ndarray, s: float) -> int:
    """Index of the segment holding arc length ``s``: the last ``i`` with ``cum[i] <= s``.

    Clamped to ``[0, K - 2]`` (0 for a one-point path), so ``s`` at the end of the
    path belongs to the last segment.
    """
    k: int = cum.shape[0]
    if k < 2:
        return 0
    lo = 0
    hi = k - 2
    if s >= cum[hi]:
        return hi
    # Invariant: cum[lo] <= s < cum[hi] (or s < cum[0], then lo stays 0).
    while hi - lo > 1:
        mid = (lo + hi) // 2
        if cum[mid] <= s:
            lo = mid
        else:
            hi = mid
    return lo


@njit_no_refcount
def point_at(pts: np.ndarray, cum: np.ndarray, s: float) -> tuple[float, float]:
    """The point at arc length ``s``, clamped to ``[0, length]``."""
    k = pts.shape[0]
    if k < 2 or s <= 0.0:
        return pts[0, 0], pts[0, 1]
    if s >= cum[k - 1]:
        return pts[k - 1, 0], pts[k - 1, 1]
    i = segment_of(cum, s)
    t = (s - cum[i]) / (cum[i + 1] - cum[i])
    return (
        pts[i, 0] + t * (pts[i + 1, 0] - pts[i, 0]),
        pts[i, 1] + t * (pts[i + 1, 1] - pts[i, 1]),
    )


@njit_no_refcount
def offset_at(
    pts: np.ndarray, cum: np.ndarray, s: float, px: float, py: float
) -> tuple[float, float, float, float]:
    """The point at arc length ``s`` (clamped) minus ``(px, py)``, and the point:
    ``(dx, dy, x, y)``.

    The offset is subtracted first, ``(a - p) + t (b - a)`` on the segment from
    ``a`` to ``b``, rather than ``point_at(s) - p``: the point carries the
    rounding of its world coordinates (1e-9 m at UTM northings of 4.6e6 m), the
    offset only its own, so a problem translated anywhere gives the same offsets
    to about 1e-16 of their length. The point is :func:`point_at`'s, bit for bit.
    """
    k = pts.shape[0]
    if k < 2 or s <= 0.0:
        return pts[0, 0] - px, pts[0, 1] - py, pts[0, 0], pts[0, 1]
    if s >= cum[k - 1]:
        return pts[k - 1, 0] - px, pts[k - 1, 1] - py, pts[k - 1, 0], pts[k - 1, 1]
    i = segment_of(cum, s)
    t = (s - cum[i]) / (cum[i + 1] - cum[i])
    ex = pts[i + 1, 0] - pts[i, 0]
    ey = pts[i + 1, 1] - pts[i, 1]
    return (
        (pts[i, 0] - px) + t * ex,
        (pts[i, 1] - py) + t * ey,
        pts[i, 0] + t * ex,
        pts[i, 1] + t * ey,
    )


@njit_no_refcount
def project(
    px: float,
    py: float,
    pts: np.ndarray,
    cum: np.ndarray,
    s_from: float,
    s_to: float,
    s_free: float,
    detour: float,
) -> tuple[float, float]:
    """Closest point to ``(px, py)`` on the part ``[s_from, s_to]`` of the path.

    Returns ``(s, distance)``; on ties the smallest ``s`` wins. ``s_from <= s_to``
    and both inside ``[0, length]``. The search walks the path from ``s_from``
    and stops at the first vertex from arc length ``s_free`` on (or the point
    at ``s_free`` itself) more than ``detour`` farther from ``(px, py)`` than
    the closest point found so far (``detour = inf``: the whole window). As the
    distance is convex along a segment, that is the first such point of the
    path walked continuously: splitting a segment into collinear pieces
    changes nothing.
    """
    k = pts.shape[0]
    if k < 2:
        return 0.0, math.hypot(px - pts[0, 0], py - pts[0, 1])
    i0 = segment_of(cum, s_from)
    i1 = segment_of(cum, s_to)
    best_s = s_from
    best_d2 = math.inf
    for i in range(i0, i1 + 1):
        ax = pts[i, 0]
        ay = pts[i, 1]
        ex = pts[i + 1, 0] - ax
        ey = pts[i + 1, 1] - ay
        # The segment's length from its ends: arc lengths of a long path can
        # round a tiny segment to zero length.
        seg = math.hypot(ex, ey)
        lo = max2(0.0, s_from - cum[i])
        hi = max2(lo, min2(seg, s_to - cum[i]))
        if seg > 0.0:
            # Distance along the segment of the foot of the perpendicular, clamped.
            u = ((px - ax) * ex + (py - ay) * ey) / seg
            u = min2(max2(u, lo), hi)
            f = min2(u / seg, 1.0)
        else:
            u = lo
            f = 0.0
        # Subtracted first (the offset's rounding, not the world coordinates').
        qx = (ax - px) + ex * f
        qy = (ay - py) + ey * f
        d2 = qx * qx + qy * qy
        free = s_free - cum[i]
        if lo < free < hi:
            # The detour test starts at s_free, inside this segment: the part before
            # it counts first, then the point at s_free is tested as a vertex is.
            # Tested at the segment's end only, a path split into collinear pieces (a
            # vertex just past s_free) stopped where the whole one went on to a nearer
            # later pass: other commands (review 38).
            g = min2(free / seg, 1.0)
            wx = (ax - px) + ex * g
            wy = (ay - py) + ey * g
            # The part's closest point: the segment's own, or else the point at s_free.
            near2 = d2 if u <= free else wx * wx + wy * wy
            if near2 < best_d2:
                best_d2 = near2
                best_s = min2(max2(cum[i] + min2(u, free), s_from), s_to)
            if math.hypot(wx, wy) > math.sqrt(best_d2) + detour:
                break
        if d2 < best_d2:
            best_d2 = d2
            best_s = min2(max2(cum[i] + u, s_from), s_to)
        # The distance to a segment's points is convex along it, so the path can only
        # leave the robot and come back through a vertex: past one that is a detour
        # away, a nearer point is a later pass (the end of a short loop, a crossing).
        vx = pts[i + 1, 0] - px
        vy = pts[i + 1, 1] - py
        if cum[i + 1] >= s_free and math.hypot(vx, vy) > math.sqrt(best_d2) + detour:
            break
    return best_s, math.sqrt(best_d2)


@njit_no_refcount
def project_offset(
    px: float,
    py: float,
    pts: np.ndarray,
    cum: np.ndarray,
    s_from: float,
    s_to: float,
    s_free: float,
    detour: float,
) -> tuple[float, float, float]:
    """:func:`project`'s ``s`` and :func:`offset_at` for it: ``(s, dx, dy)``.

    In one call, without the second call's dispatch (0.4 µs).
    """
    s, _ = project(px, py, pts, cum, s_from, s_to, s_free, detour)
    dx, dy, _, _ = offset_at(pts, cum, s, px, py)
    return s, dx, dy


@njit_no_refcount
def circle_exit(
    px: float, py: float, pts: np.ndarray, cum: np.ndarray, s_from: float, radius: float
) -> float:
    """First arc length ``s >= s_from`` whose point is at least ``radius`` from ``(px, py)``.

    This is pure pursuit's lookahead point with interpolation (Nav2's
    ``getLookAheadPoint``): walking the path from ``s_from``, the first vertex
    at least ``radius`` away is found and the circle's crossing is interpolated
    on the segment leading to it. Returns ``s_from`` when that point already is
    ``radius`` away, and -1 when no point is.
    """
    k = pts.shape[0]
    if k < 2:
        # Products, not ``** 2``: numba compiles its integer power loop for that (review 51;
        # the same float: the loop's 1.0 * (d * d)).
        dx = pts[0, 0] - px
        dy = pts[0, 1] - py
        return 0.0 if dx * dx + dy * dy >= radius * radius else -1.0
    r2 = radius * radius
    # Offsets from the robot throughout (a - p, b - p), each subtracted first: the
    # same result wherever the problem is translated (see offset_at).
    fx, fy, _, _ = offset_at(pts, cum, s_from, px, py)
    s_a: float = s_from
    if fx * fx + fy * fy >= r2:
        return s_from
    for j in range(segment_of(cum, s_from) + 1, k):
        if cum[j] <= s_a:
            continue
        gx: float = pts[j, 0] - px
        gy: float = pts[j, 1] - py
        if gx * gx + gy * gy >= r2:
            # |a + t (b - a) - p| = radius with |a - p| < radius <= |b - p|: the
            # larger root of the quadratic lies in (0, 1].
            dx = gx - fx
            dy = gy - fy
            qa = dx * dx + dy * dy
            if qa == 0.0:
                return float(cum[j])
            qb = 2.0 * (fx * dx + fy * dy)
            qc = fx * fx + fy * fy - r2
            disc = max2(qb * qb - 4.0 * qa * qc, 0.0)
            t = (-qb + math.sqrt(disc)) / (2.0 * qa)
            clamped: float = min2(max2(t, 0.0), 1.0)
            end: float = cum[j]
            return s_a + clamped * (end - s_a)
        fx = gx
        fy = gy
        s_a = cum[j]
    return -1.0
