"""numba kernels for simulated 2-D LiDAR: exact ray casting and range noise (private).

A scan finds, for every beam from one origin, the distance to the first
obstacle it meets, exactly (closed-form ray–segment and ray–circle
intersections, exact cell traversal of an occupancy grid) and only among the
primitives near the beam:

* static segments and circles are looked up in a uniform grid
  (:mod:`navkit.sim._edge_grid_kernels`) walked cell by cell along the beam
  (Amanatides–Woo), stopping at the first cell whose exit lies beyond the
  nearest hit found so far;
* an occupancy grid is walked cell by cell from the sensor (Amanatides–Woo),
  jumping across the free square around a cell when its chessboard distance
  to the nearest blocked cell is large; the range is the distance at which
  the beam first touches a blocked cell, its closed square as a box of the
  polygon world (a corner it passes, a face it runs along, a face the origin
  is on), whichever way the beam's angle is written (a direction within
  rounding of a grid axis is that axis);
* moving obstacles (few) are tested by brute force.

A beam from inside a solid obstacle (a solid polygon or circle, a moving
obstacle) reads 0, as one from inside a blocked cell of the occupancy grid
does: ``cast_edge_rays`` tells whether the origin is inside one before it
casts. For the static solids it counts, by the even-odd rule, the edges of
the union of the solid polygons (a CSR list of its own, filed in the cells of
the same uniform grid) that a horizontal ray from the origin crosses, walking
the origin's row of cells toward the nearer side of the grid, and tests the
solid circles filed in those cells.

A scan is one or two passes over the beams: ``cast_edge_rays`` for segments
and circles, static and moving, then ``cast_occupancy_rays`` for an
occupancy grid, starting from the ranges of the first pass: a world compiles
only the passes of the kinds it has on first use.

``apply_range_noise`` turns exact ranges into REP 117 readings with relative
and absolute Gaussian noise by distance band and dropouts.

Every kernel takes all its inputs as arguments and allocates nothing.

Examples
--------
>>> import numpy as np
>>> square = np.array([[2.0, -5.0, 2.0, 5.0]])
>>> none3, none4 = np.empty((0, 3)), np.empty((0, 4))
>>> start = np.array([0, 1], dtype=np.int64)
>>> items = np.array([0], dtype=np.int64)
>>> angles = np.array([0.0, np.pi / 3, np.pi])
>>> out, dirs = np.empty(3), np.empty((3, 2))
>>> no_items, no_owner = np.empty(0, dtype=np.int64), np.empty(0, dtype=np.int64)
>>> cast_edge_rays(out, dirs, 0.0, 0.0, 0.0, angles, 10.0, True,
...                square, none3, 1.0, -6.0, 12.0, 1, 1, start, items,
...                none4, none3, start, no_items, none4, no_owner, none3)
>>> out.round(12).tolist()
[2.0, 4.0, inf]
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from navkit._shared.jit import bind_numba_names, njit_helper, njit_no_refcount, njit_released
from navkit.sim._moving_kernels import point_in_moving

# numba's min and max builtins, without an overload compiled per argument types
# (navkit._shared.selects: intrinsics, so bound when numba loads; issue 17).
min2: Any = None
max2: Any = None
bind_numba_names(
    globals(), "navkit._shared.selects", python={"min2": min, "max2": max}, min2="min2", max2="max2"
)

__all__ = ["apply_range_noise", "cast_edge_rays", "cast_occupancy_rays"]


_INF = math.inf
#: Chessboard distance (cells) from which the occupancy walk jumps across the
#: free square around a cell instead of stepping cell by cell: a jump costs
#: about as much as eight steps.
_JUMP = 8
#: Distance (m) from a beam's line within which a segment's end counts as on it.
#: Rounding of the beam's direction and of the products that measure the
#: distance is about 1e-16 of the end's distance from the origin, far below
#: this for every distance a world allows (1e6 m); a segment within it of the
#: whole line is met at its nearer end.
_ON_LINE = 1e-9
#: Relative size below which a direction's component across a grid axis is
#: rounding and is taken as 0: the beam runs along the axis. The sine of a
#: multiple of pi is up to |angle| * 2**-53 instead of 0 (1.2e-16 at pi), and
#: rotating into a map's frame adds a few 1e-16.
_AXIS = 2.0**-46
#: Relative difference within which the ray's crossings of a column line and a
#: row line are one corner: rounding of the direction and of the summed steps
#: puts the two crossings of a corner the ray passes through a few 1e-16 apart
#: (up to ~1e-12 after 10^4 steps), far below a step between lines.
_TIE = 2.0**-36
_APART = 1.0 - _TIE
#: Relative distance (of the coordinates' size) within which a ray's start point
#: lies on a grid line: a few hundred roundings.
_NEAR = 2.0**-44


@njit_helper
def _ray_segment(
    ox: float,
    oy: float,
    dx: float,
    dy: float,
    ax: float,
    ay: float,
    bx: float,
    by: float,
    best: float,
) -> float:
    """Smaller of ``best`` and the ray parameter t >= 0 where the ray meets segment ab.

    ``(dx, dy)`` is a unit vector. The hit is found from the signed distances of
    a and b to the ray's line, each computed from that end alone, rather than by
    solving for the crossing point: two edges sharing a vertex then agree on the
    vertex's side, so a beam aimed at a polygon's vertex cannot slip between
    them (as rounding of the edge parameter let it), and a beam running along a
    wall, its direction a rounding off the wall's, meets the wall's nearer end
    (cancellation put the crossing point anywhere, often at the origin).
    """
    wx = ax - ox
    wy = ay - oy
    qx = bx - ox
    qy = by - oy
    # Signed distances of a and b to the ray's line, m.
    sa = wx * dy - wy * dx
    sb = qx * dy - qy * dx
    if (sa > _ON_LINE and sb > _ON_LINE) or (sa < -_ON_LINE and sb < -_ON_LINE):
        return best  # both ends on one side of the ray's line
    ta = wx * dx + wy * dy
    tb = qx * dx + qy * dy
    if abs(sa) <= _ON_LINE and abs(sb) <= _ON_LINE:
        # Along the ray's line: a hit at the nearer end in front of the origin.
        if ta < 0.0 and tb < 0.0:
            return best
        t: float = max2(min2(ta, tb), 0.0)
    else:
        # Where the segment crosses the line: sa / (sa - sb) of the way from a to b.
        t = ta + (tb - ta) * (sa / (sa - sb))
        if t <= _ON_LINE:
            if t < -_ON_LINE:
                return best
            t = 0.0  # the origin on the segment, to rounding
    return t if t < best else best


@njit_helper
def _ray_circle(
    ox: float, oy: float, dx: float, dy: float, cx: float, cy: float, r: float, best: float
) -> float:
    """Smaller of ``best`` and the first t >= 0 where the ray meets the circle's boundary."""
    wx = ox - cx
    wy = oy - cy
    b = wx * dx + wy * dy
    c = wx * wx + wy * wy - r * r
    disc = b * b - c
    if disc < 0.0:
        return best
    sq = math.sqrt(disc)
    t = -b - sq
    if t < 0.0:
        t = -b + sq
        if t < 0.0:
            return best
    return t if t < best else best


@njit_helper
def _cast_edge_grid(
    ox: float,
    oy: float,
    dx: float,
    dy: float,
    best: float,
    segs: np.ndarray,
    circles: np.ndarray,
    gx0: float,
    gy0: float,
    h: float,
    nx: int,
    ny: int,
    cell_start: np.ndarray,
    cell_items: np.ndarray,
) -> float:
    """Nearest static segment/circle hit below ``best`` along the ray, by grid walk."""
    gx1 = gx0 + nx * h
    gy1 = gy0 + ny * h
    # Clip the ray [0, best] to the grid's box (slabs).
    t0 = 0.0
    t1 = best
    if dx != 0.0:
        ta = (gx0 - ox) / dx
        tb = (gx1 - ox) / dx
        if ta > tb:
            ta, tb = tb, ta
        t0 = max2(t0, ta)
        t1 = min2(t1, tb)
    elif ox < gx0 or ox > gx1:
        return best
    if dy != 0.0:
        ta = (gy0 - oy) / dy
        tb = (gy1 - oy) / dy
        if ta > tb:
            ta, tb = tb, ta
        t0 = max2(t0, ta)
        t1 = min2(t1, tb)
    elif oy < gy0 or oy > gy1:
        return best
    if t0 > t1:
        return best
    inv_h = 1.0 / h
    px = ox + t0 * dx
    py = oy + t0 * dy
    i = min2(max2(math.floor((px - gx0) * inv_h), 0), nx - 1)
    j = min2(max2(math.floor((py - gy0) * inv_h), 0), ny - 1)
    si = 1 if dx > 0.0 else -1
    sj = 1 if dy > 0.0 else -1
    n_seg = segs.shape[0]
    while True:
        k = j * nx + i
        for m in range(cell_start[k], cell_start[k + 1]):
            item = cell_items[m]
            if item < n_seg:
                best = _ray_segment(
                    ox, oy, dx, dy, segs[item, 0], segs[item, 1], segs[item, 2], segs[item, 3],
                    best,
                )  # fmt: skip
            else:
                c = item - n_seg
                best = _ray_circle(
                    ox, oy, dx, dy, circles[c, 0], circles[c, 1], circles[c, 2], best
                )
        # Where the ray leaves this cell.
        tx = (gx0 + (i + (1 if si > 0 else 0)) * h - ox) / dx if dx != 0.0 else _INF
        ty = (gy0 + (j + (1 if sj > 0 else 0)) * h - oy) / dy if dy != 0.0 else _INF
        t_exit = min2(tx, ty)
        if best <= t_exit or t_exit >= t1:
            return best
        if tx <= ty:
            i += si
            if i < 0 or i >= nx:
                return best
        if ty <= tx:
            j += sj
            if j < 0 or j >= ny:
                return best


@njit_helper
def _cast_occupancy(
    ox: float,
    oy: float,
    dx: float,
    dy: float,
    best: float,
    cheb: np.ndarray,
    gox: float,
    goy: float,
    gcos: float,
    gsin: float,
    res: float,
) -> float:
    """Distance below ``best`` at which the ray first touches a blocked cell.

    ``cheb`` is the chessboard distance of every cell to the nearest blocked
    one (0 on blocked cells). Works in the grid frame in cell units. The walk
    steps through cell ``(row, col)`` as ``[col, col + 1) x [row, row + 1)``,
    but a blocked cell counts as its closed square, as a box of the polygon
    world does: the ray stops where it first touches one, at a corner it
    passes (to rounding), along a face it runs on, or at once from a point on
    its boundary. A direction within rounding of a grid axis is
    that axis (``sin(pi)`` is 1.2e-16, not 0), so a beam along a grid line
    reads the same whichever way its angle is written.
    """
    rows = cheb.shape[0]
    cols = cheb.shape[1]
    inv = 1.0 / res
    # Origin and direction in the grid frame (direction in cells per metre).
    rx = ox - gox
    ry = oy - goy
    su = (gcos * rx + gsin * ry) * inv
    sv = (-gsin * rx + gcos * ry) * inv
    eu = (gcos * dx + gsin * dy) * inv
    ev = (-gsin * dx + gcos * dy) * inv
    if abs(ev) <= _AXIS * abs(eu):
        ev = 0.0
    elif abs(eu) <= _AXIS * abs(ev):
        eu = 0.0
    # A start point within rounding of the map's edge is on it, as one within
    # rounding of an inner grid line is on that line: a sensor on the edge of a
    # rotated map lands a few 1e-16 inside or outside, and outside it read
    # nothing along the edge (or from the face of a blocked cell there).
    edge_tol = _NEAR * (abs(su) + abs(sv))
    if -edge_tol <= su < 0.0:
        su = 0.0
    elif cols < su <= cols + edge_tol:
        su = float(cols)
    if -edge_tol <= sv < 0.0:
        sv = 0.0
    elif rows < sv <= rows + edge_tol:
        sv = float(rows)
    t0 = 0.0
    t1 = best
    if eu != 0.0:
        ta = -su / eu
        tb = (cols - su) / eu
        if ta > tb:
            ta, tb = tb, ta
        t0 = ta if ta > t0 else t0  # not max(): -0.0 must not replace 0.0
        t1 = min2(t1, tb)
    elif su < 0.0 or su > cols:
        return best
    if ev != 0.0:
        ta = -sv / ev
        tb = (rows - sv) / ev
        if ta > tb:
            ta, tb = tb, ta
        t0 = ta if ta > t0 else t0
        t1 = min2(t1, tb)
    elif sv < 0.0 or sv > rows:
        return best
    # A ray through a corner of the map enters and leaves it at once: rounding
    # may put its exit a hair before its entry, and it still touches that cell.
    if t0 >= best or t0 - t1 > _TIE * t0:
        return best
    u0 = su + t0 * eu
    v0 = sv + t0 * ev
    c = min2(max2(math.floor(u0), 0), cols - 1)
    r = min2(max2(math.floor(v0), 0), rows - 1)
    # The start point touches every cell whose closed square holds it: one, or
    # two or four on a grid line or corner (an origin on a blocked cell's face,
    # a ray entering the map through a corner), to rounding of its coordinates.
    near_u = _NEAR * (abs(su) + abs(t0 * eu))
    near_v = _NEAR * (abs(sv) + abs(t0 * ev))
    r_lo = r - 1 if r >= 1 and abs(v0 - r) <= near_v else r
    r_hi = r + 1 if r + 1 < rows and abs(v0 - (r + 1)) <= near_v else r
    c_lo = c - 1 if c >= 1 and abs(u0 - c) <= near_u else c
    c_hi = c + 1 if c + 1 < cols and abs(u0 - (c + 1)) <= near_u else c
    for rr in range(r_lo, r_hi + 1):
        for cc in range(c_lo, c_hi + 1):
            if cheb[rr, cc] == 0:
                return t0
    # A ray along a grid line touches the cells on both sides of it: side_r
    # (side_c) is the row (column) beside the one it steps along (-1: none).
    side_r = -1
    if ev == 0.0:
        side_r = r_lo if r_lo != r else (r_hi if r_hi != r else -1)
    side_c = -1
    if eu == 0.0:
        side_c = c_lo if c_lo != c else (c_hi if c_hi != c else -1)
    sc = 1 if eu > 0.0 else -1
    sr = 1 if ev > 0.0 else -1
    # Reciprocals: the walk is bound by latency, and a product is quicker than
    # a quotient (one extra rounding, ~1e-16 relative).
    inv_eu = 1.0 / eu if eu != 0.0 else 0.0
    inv_ev = 1.0 / ev if ev != 0.0 else 0.0
    dtc = abs(inv_eu) if eu != 0.0 else _INF
    dtr = abs(inv_ev) if ev != 0.0 else _INF
    # Exit edge of a cell (or square) along each axis, relative to its first index.
    off_c = 1 if sc > 0 else 0
    off_r = 1 if sr > 0 else 0
    # Where the beam crosses the next column and row line.
    tc = (c + off_c - su) * inv_eu if eu != 0.0 else _INF
    tr = (r + off_r - sv) * inv_ev if ev != 0.0 else _INF
    t_in: float = t0
    if side_r >= 0 or side_c >= 0:
        # Along a grid line (rare): step the cells on both sides of it together.
        while True:
            if side_r >= 0:
                if cheb[r, c] == 0 or cheb[side_r, c] == 0:
                    return t_in if t_in < best else best
                t_in = tc
                tc += dtc
                c += sc
            else:
                if cheb[r, c] == 0 or cheb[r, side_c] == 0:
                    return t_in if t_in < best else best
                t_in = tr
                tr += dtr
                r += sr
            if t_in >= t1 or c < 0 or c >= cols or r < 0 or r >= rows:
                return best
    while True:
        d = cheb[r, c]
        if d == 0:
            return t_in if t_in < best else best
        if d >= _JUMP:
            # Every cell within chessboard distance d - 1 is free: go to the square's
            # last cell along the ray; the steps below cross its boundary and see
            # what the ray touches there (a corner).
            half = np.int64(d) - 1
            xc = (c + sc * half + off_c - su) * inv_eu if eu != 0.0 else _INF
            xr = (r + sr * half + off_r - sv) * inv_ev if ev != 0.0 else _INF
            exit_t = min2(xc, xr)
            if exit_t - t1 > _TIE * exit_t:
                return best  # the ray ends or leaves the map inside the free square
            # One step before the exit the ray is well inside the square: its cell
            # there, unlike the exit point's, is no rounding away from a corner.
            back = exit_t - min2(dtc, dtr)
            # Within the square and the map (a ray along its top or right edge
            # walks the last row or column, as from the start).
            r = min2(min2(max2(max2(math.floor(sv + back * ev), r - half), 0), r + half), rows - 1)
            c = min2(min2(max2(max2(math.floor(su + back * eu), c - half), 0), c + half), cols - 1)
            tc = (c + off_c - su) * inv_eu if eu != 0.0 else _INF
            tr = (r + off_r - sv) * inv_ev if ev != 0.0 else _INF
            continue
        if tc < tr * _APART:
            # Never earlier than the last crossing: a line the start point lies
            # on can round to a crossing a hair behind it.
            t_in = tc if tc > t_in else t_in
            tc += dtc
            c += sc
        elif tr < tc * _APART:
            t_in = tr if tr > t_in else t_in
            tr += dtr
            r += sr
        else:
            # Through a corner (to rounding): the two cells beside it are touched there.
            t = min2(tc, tr)
            t_in = t if t > t_in else t_in
            if t_in - t1 > _TIE * t_in:
                return best  # a corner on the map's edge (to rounding) is still touched
            if (0 <= c + sc < cols and cheb[r, c + sc] == 0) or (
                0 <= r + sr < rows and cheb[r + sr, c] == 0
            ):
                return t_in if t_in < best else best
            tc += dtc
            tr += dtr
            c += sc
            r += sr
        if t_in >= t1 or c < 0 or c >= cols or r < 0 or r >= rows:
            return best


@njit_helper
def _in_static_solid(
    px: float,
    py: float,
    rings: np.ndarray,
    solid_circles: np.ndarray,
    gx0: float,
    gy0: float,
    h: float,
    nx: int,
    ny: int,
    solid_start: np.ndarray,
    solid_items: np.ndarray,
) -> bool:
    """Whether ``(px, py)`` lies inside a static solid: a solid polygon or circle.

    ``rings`` are the edges of the union of the solid polygons and
    ``solid_start`` / ``solid_items`` their CSR lists (and those of
    ``solid_circles``) in the uniform grid ``gx0, gy0, h, nx, ny``, which holds
    every solid. The horizontal ray from the point toward the nearer side of
    the grid crosses an odd number of edges when the point is inside (a vertex
    on the ray counts as above it); a crossing is counted in the cell where it
    lies, once, though the edge may be filed in several. A solid circle holding
    the point has its boundary on that ray, so it is filed in a cell walked.
    """
    if solid_items.shape[0] == 0:
        return False
    inv_h = 1.0 / h
    u = (px - gx0) * inv_h
    v = (py - gy0) * inv_h
    # Outside the grid's box is outside every solid.
    if not (0.0 <= u < nx and 0.0 <= v < ny):
        return False
    i0 = min2(math.floor(u), nx - 1)
    j = min2(math.floor(v), ny - 1)
    n_rings = rings.shape[0]
    right = nx - 1 - i0 <= i0
    lo = i0 if right else 0
    hi = nx - 1 if right else i0
    inside = False
    for i in range(lo, hi + 1):
        k = j * nx + i
        for m in range(solid_start[k], solid_start[k + 1]):
            item = solid_items[m]
            if item >= n_rings:
                c = item - n_rings
                d = math.hypot(px - solid_circles[c, 0], py - solid_circles[c, 1])
                if d < solid_circles[c, 2]:
                    return True
                continue
            ay = rings[item, 1]
            by = rings[item, 3]
            if (ay > py) == (by > py):
                continue
            ax = rings[item, 0]
            x_cross = ax + (py - ay) * (rings[item, 2] - ax) / (by - ay)
            if (px < x_cross) != right:
                continue
            if min2(max2(math.floor((x_cross - gx0) * inv_h), 0), nx - 1) == i:
                inside = not inside
    return inside


@njit_released
def cast_edge_rays(
    out: np.ndarray,
    dirs: np.ndarray,
    ox: float,
    oy: float,
    heading: float,
    angles: np.ndarray,
    range_max: float,
    last: bool,
    segs: np.ndarray,
    circles: np.ndarray,
    gx0: float,
    gy0: float,
    h: float,
    nx: int,
    ny: int,
    cell_start: np.ndarray,
    cell_items: np.ndarray,
    rings: np.ndarray,
    solid_circles: np.ndarray,
    solid_start: np.ndarray,
    solid_items: np.ndarray,
    dyn_segs: np.ndarray,
    dyn_seg_owner: np.ndarray,
    dyn_circles: np.ndarray,
) -> None:
    """First pass of a scan: segments and circles, static (grid index) and moving.

    Beam ``k`` leaves ``(ox, oy)`` at world angle ``heading + angles[k]``;
    ``out[k]`` becomes the distance to the first segment or circle boundary
    it meets below ``range_max`` (else ``range_max``) and, unless ``last``,
    ``dirs[k]`` its direction ``(cos, sin)``. The static primitives are looked up in the
    uniform grid (skipped when its ``cell_items`` is empty), the moving ones
    (few) tested by brute force. When ``last`` (no other pass follows) ranges
    at or beyond ``range_max`` become ``inf``. Every beam reads 0 when the
    origin is inside a solid: the union of the solid polygons (edges ``rings``),
    a circle of ``solid_circles`` (both filed in ``solid_start`` /
    ``solid_items`` over the same grid) or a moving obstacle (its edges
    ``dyn_segs`` grouped by ``dyn_seg_owner``, or a disc of ``dyn_circles``).
    """
    has_grid = cell_items.shape[0] > 0
    n_dseg = dyn_segs.shape[0]
    n_dcirc = dyn_circles.shape[0]
    inside = _in_static_solid(
        ox, oy, rings, solid_circles, gx0, gy0, h, nx, ny, solid_start, solid_items
    ) or point_in_moving(ox, oy, dyn_segs, dyn_seg_owner, dyn_circles)
    for k in range(angles.shape[0]):
        phi = heading + angles[k]
        dx = math.cos(phi)
        dy = math.sin(phi)
        if not last:
            dirs[k, 0] = dx
            dirs[k, 1] = dy
        if inside:
            out[k] = 0.0
            continue
        best = range_max
        if has_grid:
            best = _cast_edge_grid(
                ox, oy, dx, dy, best, segs, circles, gx0, gy0, h, nx, ny, cell_start, cell_items
            )
        for m in range(n_dseg):
            best = _ray_segment(
                ox, oy, dx, dy, dyn_segs[m, 0], dyn_segs[m, 1], dyn_segs[m, 2], dyn_segs[m, 3],
                best,
            )  # fmt: skip
        for m in range(n_dcirc):
            best = _ray_circle(
                ox, oy, dx, dy, dyn_circles[m, 0], dyn_circles[m, 1], dyn_circles[m, 2], best
            )
        out[k] = best if not last or best < range_max else _INF


@njit_released
def cast_occupancy_rays(
    out: np.ndarray,
    dirs: np.ndarray,
    ox: float,
    oy: float,
    heading: float,
    angles: np.ndarray,
    range_max: float,
    first: bool,
    cheb: np.ndarray,
    gox: float,
    goy: float,
    gcos: float,
    gsin: float,
    res: float,
) -> None:
    """Last pass of a scan: the occupancy grid (``cheb``: its chessboard distances).

    Starts from ``range_max`` when ``first``, otherwise from the ranges and
    directions :func:`cast_edge_rays` left in ``out`` and ``dirs``; ``out[k]``
    becomes the distance at which beam ``k`` enters the first blocked cell
    when that is nearer. Ranges at or beyond ``range_max`` become ``inf``.
    """
    for k in range(angles.shape[0]):
        if first:
            phi = heading + angles[k]
            dx = math.cos(phi)
            dy = math.sin(phi)
            best = range_max
        else:
            dx = dirs[k, 0]
            dy = dirs[k, 1]
            best = out[k]
        best = _cast_occupancy(ox, oy, dx, dy, best, cheb, gox, goy, gcos, gsin, res)
        out[k] = best if best < range_max else _INF


@njit_no_refcount
def apply_range_noise(
    ranges: np.ndarray,
    normals: np.ndarray,
    uniforms: np.ndarray,
    limits: np.ndarray,
    bias: np.ndarray,
    sigma: np.ndarray,
    absolute: np.ndarray,
    dropout: float,
    range_min: float,
    range_max: float,
) -> None:
    """Exact ranges to REP 117 readings, in place.

    A finite range ``r`` in band ``b`` (the first with ``r < limits[b]``)
    becomes ``r * (1 + bias[b] + sigma[b] * normals[k]) + absolute[b] *
    normals[k]`` (the absolute term since review 49); then a beam whose
    ``uniforms[k] < dropout`` reads NaN (a missing measurement), a reading
    below ``range_min`` reads ``-inf`` (too close) and one at or beyond
    ``range_max`` reads ``+inf`` (no return). ``inf`` (nothing in range) stays.
    """
    n_band = limits.shape[0]
    for k in range(ranges.shape[0]):
        r = ranges[k]
        if uniforms[k] < dropout:
            ranges[k] = math.nan
            continue
        if r == _INF:
            continue
        b = 0
        while b < n_band - 1 and r >= limits[b]:
            b += 1
        r = r * (1.0 + bias[b] + sigma[b] * normals[k])
        if absolute[b] != 0.0:
            # Skipped at 0, not added: the relative model's readings stay theirs to the
            # bit (a reading of -0.0 too).
            r += absolute[b] * normals[k]
        if r < range_min:
            r = -_INF
        elif r >= range_max:
            r = _INF
        ranges[k] = r
