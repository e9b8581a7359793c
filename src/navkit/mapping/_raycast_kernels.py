"""numba kernel for laser ray casting into a log-odds grid (private).

Plain functions on arrays and scalars compiled with ``cache=True``;
:func:`navkit.mapping.integrate_scan` validates input before calling them. Grid
cells are ``(row, col)`` and index ``array[row, col]``. The Bresenham line walk
itself lives in :mod:`navkit._shared.lines`.

``integrate_beams`` ray-casts one scan (Bresenham or exact traversal, one update
per cell per scan).

Examples
--------
>>> import numpy as np
>>> logodds = np.zeros((1, 4), dtype=np.float32)
>>> ranges = np.array([2.0])
>>> ranges.flags.writeable = False  # as a LaserScan's: one compiled signature
>>> integrate_beams(logodds, 0.0, 0.0, 0.0, 1.0, 0.5, 0.5, 0.0, ranges,
...                 0.0, 0.1, 0.1, 5.0, 1.0, -0.5, -2.0, 3.5, False,
...                 np.empty(logodds.size, dtype=np.uint8))
3
>>> logodds
array([[-0.5, -0.5,  1. ,  0. ]], dtype=float32)
"""

from __future__ import annotations

import math

import numpy as np

from navkit._shared.jit import NO_REFCOUNT, njit_released, typed_njit
from navkit._shared.lines import bresenham_step

__all__ = ["integrate_beams"]

# Marks of a cell in the per-scan scratch window.
_MISS = 1
_HIT = 2


@typed_njit(**NO_REFCOUNT, forceinline=True, no_cpython_wrapper=True)
def _miss_cell(
    logodds: np.ndarray,
    mark: np.ndarray,
    r: int,
    c: int,
    w_r0: int,
    w_c0: int,
    w_cols: int,
    miss: float,
    clamp_low: float,
) -> int:
    """Give cell (r, c) (inside the window) the miss update unless already updated.

    Compiled once and inlined by LLVM into both walks of :func:`integrate_beams`.
    """
    # Unsigned indices: the cell is known to be inside, so numba can drop its
    # negative-index wraparound code from the hottest loop.
    k = np.uintp((r - w_r0) * w_cols + c - w_c0)
    if mark[k] != 0:
        return 0
    mark[k] = _MISS
    ur = np.uintp(r)
    uc = np.uintp(c)
    # np.minimum/np.maximum rather than if/elif or min/max: with numba 0.68 the
    # branchy forms made the whole ray loop ~7x slower (measured). Bounded below
    # by min(clamp_low, value), not clamp_low: a cell already below clamp_low
    # stays there (clamping it up would make a cell observed free *less* free);
    # miss <= 0, so no value within the clamp can pass clamp_high. (OctoMap also
    # clamps a cell above clamp_high down to it: a third min/max per cell, 12 %
    # slower at 360 beams, measured.)
    value = float(logodds[ur, uc])  # as compiled when run as Python (NUMBA_DISABLE_JIT)
    logodds[ur, uc] = np.maximum(value + miss, np.minimum(clamp_low, value))
    return 1


@njit_released
def integrate_beams(
    logodds: np.ndarray,
    origin_x: float,
    origin_y: float,
    origin_yaw: float,
    resolution: float,
    sensor_x: float,
    sensor_y: float,
    sensor_theta: float,
    ranges: np.ndarray,
    angle_min: float,
    angle_increment: float,
    range_min: float,
    range_max: float,
    hit: float,
    miss: float,
    clamp_low: float,
    clamp_high: float,
    exact: bool,
    scratch: np.ndarray,
) -> int:
    """Ray-cast one scan into a float32 log-odds grid in place.

    Beam ``k`` leaves the sensor at world heading
    ``sensor_theta + angle_min + k * angle_increment``. Readings in
    ``[range_min, range_max)`` end in a hit cell; ``+inf`` and readings
    ``>= range_max`` clear the beam up to ``range_max`` and mark nothing; NaN,
    ``-inf`` and readings below ``range_min`` are skipped. Each beam is clipped
    to the grid (Liang–Barsky) before it is walked, so the walk never leaves the
    grid and its length is bounded by the grid size whatever the range; the
    sensor may be outside the map, and a beam ending outside marks no hit.

    The cells of a beam are those of the Bresenham line between the sensor's cell
    and the end cell, or with ``exact`` every cell the segment passes through
    (Amanatides–Woo traversal). Each cell receives at most one update per call:
    ``hit`` if it is the end cell of any beam, otherwise ``miss`` if any beam
    crossed it. An update stops at the bound of ``[clamp_low, clamp_high]``
    it would pass, but never moves a cell against its sign: a cell already
    beyond that bound keeps its value (as in OctoMap's ``updateNode``), and
    one beyond the other bound moves by the increment alone (OctoMap clamps
    it into the range at once). Hits are applied in a first pass so that the
    miss pass can skip them.

    ``scratch`` is a writable uint8 C-contiguous buffer of at least
    ``logodds.size`` elements, whose contents do not matter: the marks of the
    cells the scan can reach, cleared here. The caller allocates it (NumPy:
    ``np.empty``) so that this kernel allocates nothing, which saves about a
    tenth of a second of first-use compilation.

    Returns
    -------
    int
        Number of distinct cells updated.
    """
    rows = logodds.shape[0]
    cols = logodds.shape[1]
    inv_res = 1.0 / resolution
    cy = math.cos(origin_yaw)
    sy = math.sin(origin_yaw)
    dx = sensor_x - origin_x
    dy = sensor_y - origin_y
    # Sensor in continuous grid coordinates (u along columns, v along rows).
    su = (cy * dx + sy * dy) * inv_res
    sv = (-sy * dx + cy * dy) * inv_res
    n_beams = ranges.shape[0]
    longest = 0.0
    for k in range(n_beams):
        rng = ranges[k]
        if rng >= range_max:
            longest = range_max
            break
        if rng >= range_min and rng > longest:
            longest = rng
    reach = longest * inv_res + 2.0
    # A sensor farther from the grid than any beam reaches updates nothing. The
    # test also keeps huge coordinates (a pose at 1e300 m) away from the integer
    # conversions below; with navkit's ranges (range_max <= 1e9 m, resolution
    # >= 1e-6 m, origin within 1e9 m) su, sv and reach are never NaN.
    if not (-reach <= su <= cols + reach and -reach <= sv <= rows + reach):
        return 0
    # Scratch window: the cells any beam can reach, clipped to the grid. The
    # bounds are clipped as floats first so that huge coordinates never reach an
    # integer conversion.
    # (Conditional expressions rather than min/max, here and below: each of
    # those is one more function for numba to compile on first use; same values.)
    lo_v = sv - reach
    hi_v = sv + reach
    lo_u = su - reach
    hi_u = su + reach
    w_r0 = math.floor(0.0 if lo_v < 0.0 else lo_v)
    w_r1 = math.floor(float(rows - 1) if float(rows - 1) < hi_v else hi_v) + 1
    w_c0 = math.floor(0.0 if lo_u < 0.0 else lo_u)
    w_c1 = math.floor(float(cols - 1) if float(cols - 1) < hi_u else hi_u) + 1
    if w_r0 >= w_r1 or w_c0 >= w_c1:
        return 0
    # Marks of the window's cells, row-major in the caller's buffer, cleared here.
    w_cols = w_c1 - w_c0
    mark = scratch
    for i in range((w_r1 - w_r0) * w_cols):
        mark[i] = 0
    base = sensor_theta - origin_yaw + angle_min
    n_updated = 0
    # Pass 1: end cells of real returns.
    for k in range(n_beams):
        rng = ranges[k]
        if not (range_min <= rng < range_max):
            continue
        phi = base + k * angle_increment
        ev = sv + rng * inv_res * math.sin(phi)
        eu = su + rng * inv_res * math.cos(phi)
        if not (w_r0 <= ev < w_r1 and w_c0 <= eu < w_c1):
            continue
        r = math.floor(ev)
        c = math.floor(eu)
        if mark[(r - w_r0) * w_cols + c - w_c0] == 0:
            mark[(r - w_r0) * w_cols + c - w_c0] = _HIT
            # np.minimum/np.maximum rather than if/elif or min/max: with numba
            # 0.68 the branchy forms made the ray loop ~7x slower (measured). As
            # in _miss_cell: a cell above clamp_high stays, a hit never lowers it.
            value = float(logodds[r, c])
            logodds[r, c] = np.minimum(value + hit, np.maximum(clamp_high, value))
            n_updated += 1
    # Pass 2: free space along every beam (the end cell too for max-range beams).
    for k in range(n_beams):
        rng = ranges[k]
        if not (rng >= range_min):  # NaN, -inf and too-close readings
            continue
        is_hit = rng < range_max
        if not is_hit:
            rng = range_max
        phi = base + k * angle_increment
        du = rng * inv_res * math.cos(phi)
        dv = rng * inv_res * math.sin(phi)
        # Liang–Barsky: the part t in [t0, t1] of the beam inside the window
        # (t0 > t1 when the beam misses it).
        t0 = 0.0
        t1 = 1.0
        for axis in range(2):
            s = su if axis == 0 else sv
            d = du if axis == 0 else dv
            lo = w_c0 if axis == 0 else w_r0
            hi = w_c1 if axis == 0 else w_r1
            if d == 0.0:
                # Cells are half-open: a beam along the window's top or right
                # edge line runs outside it.
                if s < lo or s >= hi:
                    t0 = 1.0
                    t1 = 0.0
            else:
                ta = (lo - s) / d
                tb = (hi - s) / d
                if ta > tb:
                    ta, tb = tb, ta
                t0 = ta if ta > t0 else t0
                t1 = tb if tb < t1 else t1
        if t0 > t1:
            continue  # the beam misses the grid
        # Walk only the part of the beam inside the window, so the walk needs no
        # bounds checks and its length is bounded by the grid, not by the range.
        au = su + t0 * du if t0 > 0.0 else su
        av = sv + t0 * dv if t0 > 0.0 else sv
        if t0 == t1 and not (au < w_c1 and av < w_r1):
            continue  # it only touches the window's top or right edge: no cell entered
        # Start and end cells clamped to the window.
        r = math.floor(av)
        r = w_r0 if r < w_r0 else w_r1 - 1 if r >= w_r1 else r
        c = math.floor(au)
        c = w_c0 if c < w_c0 else w_c1 - 1 if c >= w_c1 else c
        r1 = math.floor(sv + dv if t1 >= 1.0 else sv + t1 * dv)
        c1 = math.floor(su + du if t1 >= 1.0 else su + t1 * du)
        # The end cell gets the hit (pass 1) only when the beam really ends there.
        ends_inside = t1 >= 1.0 and w_r0 <= r1 < w_r1 and w_c0 <= c1 < w_c1
        skip_end = is_hit and ends_inside
        r1 = w_r0 if r1 < w_r0 else w_r1 - 1 if r1 >= w_r1 else r1
        c1 = w_c0 if c1 < w_c0 else w_c1 - 1 if c1 >= w_c1 else c1
        sr = 1 if r1 > r else -1
        sc = 1 if c1 > c else -1
        ddr = abs(r1 - r)
        ddc = abs(c1 - c)
        err = ddc - ddr
        t_c = t_r = t_dc = t_dr = 0.0
        if exact:
            # Parameter t along the beam at the next column / row line.
            t_dc = abs(1.0 / du) if du != 0.0 else math.inf
            t_dr = abs(1.0 / dv) if dv != 0.0 else math.inf
            t_c = (c + 1 - au) * t_dc if du > 0.0 else (au - c) * t_dc if du < 0.0 else math.inf
            t_r = (r + 1 - av) * t_dr if dv > 0.0 else (av - r) * t_dr if dv < 0.0 else math.inf
        # Bresenham takes one cell per step along the major axis, the exact walk
        # one per crossed grid line; either reaches the end cell after n steps,
        # and every cell between two window cells is a window cell (monotone walk).
        if exact:
            for i in range(ddr + ddc + 1):
                if i < ddr + ddc or not skip_end:
                    n_updated += _miss_cell(
                        logodds, mark, r, c, w_r0, w_c0, w_cols, miss, clamp_low
                    )
                # Never step past the end cell's row or column, so rounding in
                # t cannot make the walk miss the end cell.
                if c == c1 or (r != r1 and t_r < t_c):
                    r += sr
                    t_r += t_dr
                else:
                    c += sc
                    t_c += t_dc
        else:
            n_steps = ddc if ddc > ddr else ddr
            for i in range(n_steps + 1):
                if i < n_steps or not skip_end:
                    n_updated += _miss_cell(
                        logodds, mark, r, c, w_r0, w_c0, w_cols, miss, clamp_low
                    )
                r, c, err = bresenham_step(r, c, err, ddr, ddc, sr, sc)
    return n_updated
