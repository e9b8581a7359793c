"""Ray casting of laser scans into log-odds occupancy grids."""

from __future__ import annotations

import math
from collections.abc import Iterable

import numpy as np
from numpy.typing import ArrayLike

from navkit._shared.deprecation import renamed_keyword
from navkit._shared.validation import as_bool, finite_float, scan_reading_hint, unpack
from navkit.geometry import Pose2D, as_pose
from navkit.mapping._grid import OccupancyGrid
from navkit.mapping._limits import LOGODDS_LIMIT, bounded_float
from navkit.mapping._logodds import DEFAULT_CLAMP, DEFAULT_HIT, DEFAULT_MISS
from navkit.mapping._raycast_kernels import integrate_beams
from navkit.mapping._scan import LaserScan

__all__ = ["integrate_scan"]


def _sensor_model(hit: object, miss: object) -> tuple[float, float]:
    """Checked log-odds increments: ``hit`` in [0, 1e6], ``miss`` in [-1e6, 0]."""
    h = bounded_float(hit, "hit", 0.0, LOGODDS_LIMIT)
    m = finite_float(miss, "miss")
    if m > 0.0:
        raise ValueError(f"miss must be <= 0 (a log-odds decrement), got {m}")
    return h, bounded_float(m, "miss", -LOGODDS_LIMIT, 0.0)


def _clamp_pair(clamp: Iterable[float]) -> tuple[float, float]:
    try:
        lo_raw, hi_raw = unpack(clamp, "clamp")
    except (TypeError, ValueError):
        raise ValueError(f"clamp must be a (low, high) pair, got {clamp!r}") from None
    lo = bounded_float(lo_raw, "clamp[0]", -LOGODDS_LIMIT, LOGODDS_LIMIT)
    hi = bounded_float(hi_raw, "clamp[1]", -LOGODDS_LIMIT, LOGODDS_LIMIT)
    if not lo < hi:
        raise ValueError(f"clamp must satisfy low < high, got {clamp!r}")
    return lo, hi


def integrate_scan(
    grid: OccupancyGrid,
    scan: LaserScan,
    pose: Pose2D | ArrayLike,
    *,
    hit: float = DEFAULT_HIT,
    miss: float = DEFAULT_MISS,
    clamp: tuple[float, float] = DEFAULT_CLAMP,
    range_max: float | None = None,
    exact: bool = False,
    max_range: float | None = None,
) -> int:
    """Ray-cast one scan into ``grid``, updating its log-odds **in place**.

    Every valid beam (finite, ``range_min <= r < range_max``) adds ``miss`` to
    the cells it crosses and ``hit`` to its end cell. The crossed cells are
    the Bresenham line from the sensor's cell to the end cell (default, the
    fastest), or with ``exact=True`` every cell the beam segment passes
    through (Amanatides–Woo traversal: about 25 % slower, leaves no gaps
    between neighbouring beams where Bresenham steps diagonally). Readings
    ``>= range_max`` and ``+inf`` (no return) clear the cells up to
    ``range_max`` and mark nothing; NaN, ``-inf`` and too-close readings are
    skipped. Beams are clipped to the map (the sensor may be outside it): the
    walk runs between the cells where the beam enters and leaves the map, and
    a beam ending outside marks no hit.

    Each cell changes at most once per scan, even when several beams cross it
    (near the sensor almost all of them do): it takes ``hit`` if it is the end
    cell of any beam and ``miss`` otherwise (occupied wins, as in OctoMap's
    ``computeUpdate``). An update stops at the bound of ``clamp`` it would
    pass, and never moves a cell against its sign: a cell already beyond that
    bound keeps its value (a miss leaves a cell below ``clamp[0]`` alone, a
    hit one above ``clamp[1]``, as OctoMap's ``updateNode`` does), and a cell
    beyond the other bound moves by the increment alone. So a grid holding
    values more certain than ``clamp`` (a loaded map: about ±6.9) is never
    made less certain by a scan that agrees with it, and one that disagrees
    moves it as it moves any other cell. (OctoMap clamps such a cell into
    ``clamp`` at once; doing so costs a third min/max per cell, about 12 %
    of a 360-beam scan.)

    The bounds of ``clamp`` are also the map's memory over long runs: however
    many scans have hit a cell (10 or 100,000), it is free again after at most
    the misses that take it from ``clamp[1]`` below the grid's free threshold,
    and occupied again after the hits from ``clamp[0]`` (a door seen shut for
    hours, then open). With the defaults and the grid's thresholds (0.65,
    0.196) that is 13 scans to free and 4 to occupied, the same after 10 hits
    as after 10^5; unclamped (``clamp`` at ±1e6) the misses needed would grow
    with the hits. :class:`~navkit.mapping.ScanMapper`'s ±50 takes 127 misses
    (``ceil((50 + 1.41) / 0.405)``).

    The result does not depend on the order of the beams, nor on where the
    grid and the sensor are in the world (moving both by one rigid motion
    gives the same cells, up to rounding where a beam ends or passes within a
    rounding error of a cell edge). But a scan integrated in parts is not the
    same as the scan integrated at once: a cell that beams of both parts
    reach takes two updates, and, near the bounds of ``clamp`` (and by
    float32 rounding), successive updates depend on their order.

    Threads integrating scans into one grid take turns: the call holds the
    grid's lock while it writes (the ray casting itself releases the GIL), so
    each scan is written whole, in the order the threads got the lock.

    Parameters
    ----------
    grid : OccupancyGrid
        The grid to update.
    scan : LaserScan
        The scan, beam angles in the sensor frame.
    pose : Pose2D or array_like [x, y, theta]
        World pose of the sensor; beam ``n`` ends at
        ``(x + d cos(θ_n + θ), y + d sin(θ_n + θ))``.
    hit, miss : float
        Log-odds increments, ``hit`` in [0, 1e6] and ``miss`` in [-1e6, 0];
        defaults are OctoMap's ``logit(0.7)`` and ``logit(0.4)``.
    clamp : (float, float)
        Log-odds bounds ``low < high``, both within ±1e6; default
        ``(logit(0.12), logit(0.97))``.
    range_max : float, optional
        Use ``min(scan.range_max, range_max)`` as the maximum range (m, > 0):
        longer readings clear up to it and mark no hit.
    exact : bool, default False
        Exact grid traversal instead of Bresenham lines.

    Other Parameters
    ----------------
    max_range : float, optional
        Deprecated name of `range_max`.

    Raises
    ------
    TypeError
        ``grid`` or ``scan`` of the wrong type, ``exact`` not a bool, a number
        that is not a real number.
    ValueError
        A number outside its range.

    Returns
    -------
    int
        Number of cells updated.

    Examples
    --------
    >>> from navkit.mapping import LaserScan, OccupancyGrid
    >>> grid = OccupancyGrid.empty(width=4.0, height=4.0, resolution=0.5)
    >>> scan = LaserScan([1.4], angle_min=0.0, angle_increment=0.1,
    ...                  range_min=0.1, range_max=3.0)
    >>> integrate_scan(grid, scan, Pose2D(0.25, 1.25, 0.0))
    4
    >>> grid.occupied()[2].astype(int)
    array([0, 0, 0, 1, 0, 0, 0, 0])
    >>> bool((grid.logodds[2, :3] < 0).all())
    True
    """
    if not isinstance(grid, OccupancyGrid):
        raise TypeError(f"grid must be an OccupancyGrid, got {type(grid).__name__}")
    if not isinstance(scan, LaserScan):
        raise TypeError(
            f"scan must be a LaserScan, got {type(scan).__name__}" + scan_reading_hint(scan)
        )
    p = as_pose(pose, "pose")
    h, m = _sensor_model(hit, miss)
    lo, hi = _clamp_pair(clamp)
    walk_exact = as_bool(exact, "exact")
    named = "range_max" if max_range is None else "max_range"  # as the caller wrote it
    range_max = renamed_keyword("max_range", max_range, "range_max", range_max, None)
    rmax = scan.range_max
    if range_max is not None:
        rmax = min(rmax, bounded_float(range_max, named, 0.0, math.inf, "m", low_open=True))
    o = grid.origin
    scratch = np.empty(grid._logodds.size, dtype=np.uint8)  # the kernel's
    # The kernel releases the GIL: without the grid's lock two threads casting
    # into one grid interleave cell by cell and lose updates. With it they take
    # turns, each scan written whole, as when every kernel call held the GIL.
    with grid._writer_lock():
        updated = integrate_beams(
            # The grid's own storage, written in place: ray casting is the one
            # job that mutates an OccupancyGrid (its public view is read-only).
            grid._logodds,
            o.x,
            o.y,
            o.theta,
            grid.resolution,
            p.x,
            p.y,
            p.theta,
            scan.ranges,
            scan.angle_min,
            scan.angle_increment,
            scan.range_min,
            rmax,
            h,
            m,
            lo,
            hi,
            walk_exact,
            scratch,
        )
    return int(updated)
