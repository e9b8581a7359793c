"""numba kernels for the distance between a robot footprint and the world (private).

The footprint is a disc (``radius > 0`` and no vertices) or a polygon
(vertices in the robot frame, shape (V, 2), implicitly closed, placed at the
robot's pose). Obstacles are the
boundaries of the world's primitives: segments, circles, occupied cells of an
occupancy grid (squares) and moving obstacles. The distance is 0 when the
footprint touches or overlaps a boundary, or when a segment or circle lies
inside a polygon footprint. It is exact up to ``limit``: the search visits the
cells of the uniform grid (and of the occupancy grid) in rings around the
footprint and stops once the rings are farther than the best distance found
or than ``limit``, returning ``min(distance, limit)``.

Compilation on first use is kept to what a world and a robot need:

* ``footprint_clearance`` measures against every kind of obstacle;
  ``edge_clearance`` is the same search for a world of static segments and
  circles only, without the occupancy grid's and the moving obstacles' code
  (about half a second less to compile);
* a disc footprint passes None for the polygon's vertex arrays: numba then
  drops the polygon's branches (``if verts is None``) before typing, so a disc
  robot never compiles the polygon distances (about another half second), and
  a polygon robot compiles the kernels once more, for its own arrays. These
  two specialisations are kept on purpose (issue 17, measured on 2 cores):
  empty (0, 2) arrays for a disc instead, with the choice made at run time,
  saved about 2.7 s of ``warmup()``'s compilation but cost a disc robot's first
  ``Simulation.run`` about 3.8 s more (it compiled the polygon code too) and
  its physics steps 15-20 % more time (the disc's distance no longer inlined
  into the cell loops; 3-4 % with the choice made in the run kernels).

Examples
--------
>>> import numpy as np
>>> segs = np.array([[2.0, -1.0, 2.0, 1.0]])
>>> start = np.array([0, 1], dtype=np.int64)
>>> items = np.array([0], dtype=np.int64)
>>> occ = np.zeros((0, 0), np.uint8)
>>> none3, none4 = np.empty((0, 3)), np.empty((0, 4))
>>> footprint_clearance(0.0, 0.0, 0.0, 0.5, None, None, None, segs, none3, 1.0, -2.0, 2.0,
...                     1, 1, start, items, occ, 0.0, 0.0, 1.0, 0.0, 1.0, none4, none3,
...                     np.inf)
1.5
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

__all__ = ["TOUCH", "edge_clearance", "footprint_clearance"]


TOUCH = 1e-12
"""Clearance (m) at or below which a footprint touches an obstacle: the distance
kernels round, so a footprint edge through an obstacle's vertex may come out a
few 1e-17 m apart instead of 0."""

_INF = math.inf


@njit_helper
def _point_segment(px: float, py: float, ax: float, ay: float, bx: float, by: float) -> float:
    ex = bx - ax
    ey = by - ay
    wx = px - ax
    wy = py - ay
    ee = ex * ex + ey * ey
    t = 0.0
    if ee > 0.0:
        t = min2(max2((wx * ex + wy * ey) / ee, 0.0), 1.0)
    qx = wx - t * ex
    qy = wy - t * ey
    return math.sqrt(qx * qx + qy * qy)


@njit_helper
def _segment_segment(
    ax: float, ay: float, bx: float, by: float, cx: float, cy: float, dx: float, dy: float
) -> float:
    """Distance between segments ab and cd (0 when they share a point, touching included)."""
    # Orientations of a and b about cd, and of c and d about ab.
    d1 = (dx - cx) * (ay - cy) - (dy - cy) * (ax - cx)
    d2 = (dx - cx) * (by - cy) - (dy - cy) * (bx - cx)
    d3 = (bx - ax) * (cy - ay) - (by - ay) * (cx - ax)
    d4 = (bx - ax) * (dy - ay) - (by - ay) * (dx - ax)
    if ((d1 > 0.0 and d2 < 0.0) or (d1 < 0.0 and d2 > 0.0)) and (
        (d3 > 0.0 and d4 < 0.0) or (d3 < 0.0 and d4 > 0.0)
    ):
        return 0.0
    # Otherwise the nearest points include an endpoint (0 when one lies on the other
    # segment: the collinear and touching cases).
    d: float = min2(
        min2(_point_segment(ax, ay, cx, cy, dx, dy), _point_segment(bx, by, cx, cy, dx, dy)),
        min2(_point_segment(cx, cy, ax, ay, bx, by), _point_segment(dx, dy, ax, ay, bx, by)),
    )
    return d


@njit_helper
def _inside_polygon(px: float, py: float, verts: np.ndarray, n: int) -> bool:
    """Even-odd rule point-in-polygon test against the first ``n`` rows of ``verts``."""
    inside = False
    j = n - 1
    for i in range(n):
        xi = verts[i, 0]
        yi = verts[i, 1]
        xj = verts[j, 0]
        yj = verts[j, 1]
        if (yi > py) != (yj > py):
            x_cross = xi + (py - yi) * (xj - xi) / (yj - yi)
            if px < x_cross:
                inside = not inside
        j = i
    return inside


@njit_helper
def _to_segment(
    cx: float,
    cy: float,
    radius: float,
    verts: np.ndarray | None,
    ax: float,
    ay: float,
    bx: float,
    by: float,
) -> float:
    """Footprint-to-segment distance (0 on contact or containment).

    The footprint is the placed polygon ``verts``, or the disc of ``radius``
    about ``(cx, cy)`` when ``verts`` is None (numba then compiles only the
    first branch).
    """
    if verts is None:
        d: float = max2(_point_segment(cx, cy, ax, ay, bx, by) - radius, 0.0)
        return d
    n = verts.shape[0]
    if _inside_polygon(ax, ay, verts, n):
        return 0.0
    best = _INF
    j = n - 1
    for i in range(n):
        d = _segment_segment(verts[j, 0], verts[j, 1], verts[i, 0], verts[i, 1], ax, ay, bx, by)
        if d < best:
            best = d
            if best == 0.0:
                return 0.0
        j = i
    return best


@njit_helper
def _to_circle(
    cx: float, cy: float, radius: float, verts: np.ndarray | None, ox: float, oy: float, r: float
) -> float:
    """Footprint-to-circle-boundary distance (0 when the boundary meets the footprint).

    The footprint as for :func:`_to_segment`.
    """
    if verts is None:
        # Products, not ``** 2``: numba compiles its integer power loop for that (review 51;
        # the same float: the loop's 1.0 * (d * d)).
        dx = cx - ox
        dy = cy - oy
        d = math.sqrt(dx * dx + dy * dy)
        if d + radius < r:
            return r - (d + radius)
        gap: float = max2(d - radius - r, 0.0)
        return gap
    n = verts.shape[0]
    near = _INF
    if _inside_polygon(ox, oy, verts, n):
        near = 0.0
    far = 0.0
    j = n - 1
    for i in range(n):
        near = min2(
            near, _point_segment(ox, oy, verts[j, 0], verts[j, 1], verts[i, 0], verts[i, 1])
        )
        vx = verts[i, 0] - ox
        vy = verts[i, 1] - oy
        far = max2(far, math.sqrt(vx * vx + vy * vy))
        j = i
    if far < r:
        return r - far
    if near > r:
        return near - r
    return 0.0


@njit_helper
def _to_square(
    cx: float,
    cy: float,
    radius: float,
    lverts: np.ndarray | None,
    xa: float,
    ya: float,
    s: float,
) -> float:
    """Footprint-to-square distance; footprint in the square's frame (``lverts``)."""
    xb = xa + s
    yb = ya + s
    if lverts is None:
        qx = cx - min2(max2(cx, xa), xb)
        qy = cy - min2(max2(cy, ya), yb)
        d: float = max2(math.sqrt(qx * qx + qy * qy) - radius, 0.0)
        return d
    n = lverts.shape[0]
    # A vertex of the footprint inside the square, or a square corner inside the footprint.
    for i in range(n):
        if xa <= lverts[i, 0] <= xb and ya <= lverts[i, 1] <= yb:
            return 0.0
    if _inside_polygon(xa, ya, lverts, n):
        return 0.0
    # The square's edges, counter-clockwise from (xa, ya).
    best = _INF
    for e in range(4):
        x0 = xa if e == 0 or e == 3 else xb
        y0 = ya if e < 2 else yb
        x1 = xb if e < 2 else xa
        y1 = ya if e == 0 or e == 3 else yb
        best = min2(best, _to_segment(0.0, 0.0, 0.0, lverts, x0, y0, x1, y1))
    return best


@njit_helper
def _edge_grid_distance(
    cx: float,
    cy: float,
    radius: float,
    verts: np.ndarray | None,
    bx0: float,
    by0: float,
    bx1: float,
    by1: float,
    segs: np.ndarray,
    circles: np.ndarray,
    gx0: float,
    gy0: float,
    h: float,
    nx: int,
    ny: int,
    cell_start: np.ndarray,
    cell_items: np.ndarray,
    best: float,
) -> float:
    """Smallest distance below ``best`` to the indexed static primitives."""
    inv_h = 1.0 / h
    # Cells of the footprint's bounding box (may lie outside the grid).
    i0 = math.floor((bx0 - gx0) * inv_h)
    i1 = math.floor((bx1 - gx0) * inv_h)
    j0 = math.floor((by0 - gy0) * inv_h)
    j1 = math.floor((by1 - gy0) * inv_h)
    # Rings farther than this lie wholly outside the grid.
    far = max2(max2(-i1, i0 - (nx - 1)), max2(-j1, j0 - (ny - 1)))
    far = max2(far, 0)
    reach = max2(max2(i1, nx - 1 - i0), max2(j1, ny - 1 - j0))
    n_seg = segs.shape[0]
    ring = far
    while ring <= reach:
        # Any cell of this ring is at least (ring - 1) * h away from the box.
        if (ring - 1) * h >= best:
            break
        lo_i = i0 - ring
        hi_i = i1 + ring
        lo_j = j0 - ring
        hi_j = j1 + ring
        for j in range(max2(lo_j, 0), min2(hi_j, ny - 1) + 1):
            on_edge_row = ring == 0 or (j - lo_j) * (hi_j - j) == 0
            if on_edge_row:
                i_first = max2(lo_i, 0)
                i_step = 1
            else:
                i_first = lo_i
                i_step = hi_i - lo_i if hi_i > lo_i else 1
            i = i_first
            while i <= min2(hi_i, nx - 1):
                if i >= 0:
                    k = j * nx + i
                    for m in range(cell_start[k], cell_start[k + 1]):
                        item = cell_items[m]
                        if item < n_seg:
                            d = _to_segment(
                                cx, cy, radius, verts,
                                segs[item, 0], segs[item, 1], segs[item, 2], segs[item, 3],
                            )  # fmt: skip
                        else:
                            c = item - n_seg
                            d = _to_circle(
                                cx, cy, radius, verts, circles[c, 0], circles[c, 1], circles[c, 2]
                            )
                        if d < best:
                            best = d
                i += i_step
        if best == 0.0:
            return 0.0
        ring += 1
    return best


@njit_helper
def _occupancy_distance(
    cx: float,
    cy: float,
    radius: float,
    verts: np.ndarray | None,
    lverts: np.ndarray | None,
    occ: np.ndarray,
    gox: float,
    goy: float,
    gcos: float,
    gsin: float,
    res: float,
    best: float,
) -> float:
    """Smallest distance below ``best`` to an occupied cell, searching rings of cells.

    ``lverts`` is scratch space of the shape of ``verts`` for the footprint in
    the grid frame (both None for a disc).
    """
    rows = occ.shape[0]
    cols = occ.shape[1]
    # Footprint in the grid frame (metres, origin at the grid's corner).
    rx = cx - gox
    ry = cy - goy
    lcx = gcos * rx + gsin * ry
    lcy = -gsin * rx + gcos * ry
    # Both None or neither; the second test only tells mypy so (numba prunes on the first).
    if verts is None or lverts is None:
        bx0 = lcx - radius
        bx1 = lcx + radius
        by0 = lcy - radius
        by1 = lcy + radius
    else:
        bx0 = by0 = _INF
        bx1 = by1 = -_INF
        for v in range(verts.shape[0]):
            wx = verts[v, 0] - gox
            wy = verts[v, 1] - goy
            lx = gcos * wx + gsin * wy
            ly = -gsin * wx + gcos * wy
            lverts[v, 0] = lx
            lverts[v, 1] = ly
            bx0 = min2(bx0, lx)
            bx1 = max2(bx1, lx)
            by0 = min2(by0, ly)
            by1 = max2(by1, ly)
    inv = 1.0 / res
    i0 = math.floor(bx0 * inv)
    i1 = math.floor(bx1 * inv)
    j0 = math.floor(by0 * inv)
    j1 = math.floor(by1 * inv)
    far = max2(max2(-i1, i0 - (cols - 1)), max2(-j1, j0 - (rows - 1)))
    far = max2(far, 0)
    reach = max2(max2(i1, cols - 1 - i0), max2(j1, rows - 1 - j0))
    ring = far
    while ring <= reach:
        if (ring - 1) * res >= best:
            break
        lo_i = i0 - ring
        hi_i = i1 + ring
        lo_j = j0 - ring
        hi_j = j1 + ring
        for j in range(max2(lo_j, 0), min2(hi_j, rows - 1) + 1):
            on_edge_row = ring == 0 or (j - lo_j) * (hi_j - j) == 0
            if on_edge_row:
                i_first = max2(lo_i, 0)
                i_step = 1
            else:
                i_first = lo_i
                i_step = hi_i - lo_i if hi_i > lo_i else 1
            i = i_first
            while i <= min2(hi_i, cols - 1):
                if i >= 0 and occ[j, i] != 0:
                    d = _to_square(lcx, lcy, radius, lverts, i * res, j * res, res)
                    if d < best:
                        best = d
                i += i_step
        if best == 0.0:
            return 0.0
        ring += 1
    return best


@njit_helper
def _place_footprint(
    px: float,
    py: float,
    ptheta: float,
    radius: float,
    body_verts: np.ndarray | None,
    verts: np.ndarray | None,
) -> tuple[float, float, float, float]:
    """A polygon footprint at the pose into ``verts``; the footprint's bounding box.

    Returns ``(x0, y0, x1, y1)``.
    """
    # Both None or neither; the second test only tells mypy so (numba prunes on the first).
    if body_verts is None or verts is None:
        return px - radius, py - radius, px + radius, py + radius
    c = math.cos(ptheta)
    s = math.sin(ptheta)
    bx0 = by0 = _INF
    bx1 = by1 = -_INF
    for v in range(body_verts.shape[0]):
        x = px + c * body_verts[v, 0] - s * body_verts[v, 1]
        y = py + s * body_verts[v, 0] + c * body_verts[v, 1]
        verts[v, 0] = x
        verts[v, 1] = y
        bx0 = min2(bx0, x)
        bx1 = max2(bx1, x)
        by0 = min2(by0, y)
        by1 = max2(by1, y)
    return bx0, by0, bx1, by1


@njit_no_refcount
def edge_clearance(
    px: float,
    py: float,
    ptheta: float,
    radius: float,
    body_verts: np.ndarray | None,
    verts: np.ndarray | None,
    segs: np.ndarray,
    circles: np.ndarray,
    gx0: float,
    gy0: float,
    h: float,
    nx: int,
    ny: int,
    cell_start: np.ndarray,
    cell_items: np.ndarray,
    limit: float,
) -> float:
    """:func:`footprint_clearance` in a world of static segments and circles only.

    The same result as :func:`footprint_clearance` given no occupancy grid and
    no moving obstacles, without compiling their distance code.
    """
    bx0, by0, bx1, by1 = _place_footprint(px, py, ptheta, radius, body_verts, verts)
    best = limit
    if best > 0.0 and cell_items.shape[0] > 0:
        best = _edge_grid_distance(
            px, py, radius, verts, bx0, by0, bx1, by1,
            segs, circles, gx0, gy0, h, nx, ny, cell_start, cell_items, best,
        )  # fmt: skip
    return best


@njit_no_refcount
def footprint_clearance(
    px: float,
    py: float,
    ptheta: float,
    radius: float,
    body_verts: np.ndarray | None,
    verts: np.ndarray | None,
    scratch: np.ndarray | None,
    segs: np.ndarray,
    circles: np.ndarray,
    gx0: float,
    gy0: float,
    h: float,
    nx: int,
    ny: int,
    cell_start: np.ndarray,
    cell_items: np.ndarray,
    occ: np.ndarray,
    gox: float,
    goy: float,
    gcos: float,
    gsin: float,
    res: float,
    dyn_segs: np.ndarray,
    dyn_circles: np.ndarray,
    limit: float,
) -> float:
    """``min(limit, distance)`` from the footprint at a pose to the nearest obstacle boundary.

    The footprint is the disc of ``radius`` about ``(px, py)`` when
    ``body_verts`` is None, otherwise the polygon ``body_verts`` (robot
    frame, shape (V, 2)) placed at the pose ``(px, py, ptheta)``. 0 means
    contact. ``verts`` and ``scratch`` are float64 work arrays of the shape of
    ``body_verts`` (the footprint in the world and in the grid frame), None
    with it.
    """
    bx0, by0, bx1, by1 = _place_footprint(px, py, ptheta, radius, body_verts, verts)
    best = limit
    for m in range(dyn_segs.shape[0]):
        d = _to_segment(
            px, py, radius, verts, dyn_segs[m, 0], dyn_segs[m, 1], dyn_segs[m, 2], dyn_segs[m, 3]
        )
        best = min2(best, d)
    for m in range(dyn_circles.shape[0]):
        d = _to_circle(
            px, py, radius, verts, dyn_circles[m, 0], dyn_circles[m, 1], dyn_circles[m, 2]
        )
        best = min2(best, d)
    if best > 0.0 and cell_items.shape[0] > 0:
        best = _edge_grid_distance(
            px, py, radius, verts, bx0, by0, bx1, by1,
            segs, circles, gx0, gy0, h, nx, ny, cell_start, cell_items, best,
        )  # fmt: skip
    if best > 0.0 and occ.shape[0] > 0:
        best = _occupancy_distance(
            px, py, radius, verts, scratch, occ, gox, goy, gcos, gsin, res, best
        )
    return best
