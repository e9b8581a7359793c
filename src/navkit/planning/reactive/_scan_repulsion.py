"""Repulsive forces straight from a laser scan: every valid beam is an obstacle point.

The per-beam sums equal :class:`KhatibRepulsion` and :class:`PiecewiseRepulsion`
evaluated at the robot on ``scan.to_points()``, without building the points: a
numba kernel sums over the ranges with cached tables of the beam directions.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from navkit._shared.types import FloatArray
from navkit._shared.validation import scan_reading_hint
from navkit.geometry import Pose2D, as_pose
from navkit.mapping import LaserScan
from navkit.planning.reactive._limits import (
    COORDINATE_LIMIT,
    GAIN_MAX,
    GAIN_MIN,
    LENGTH_MAX,
    LENGTH_MIN,
    MIN_DISTANCE,
    gain,
    length,
)
from navkit.planning.reactive._scan_repulsion_kernels import (
    khatib_beam_force_into,
    khatib_entry,
    mounted_khatib_force,
    mounted_piecewise_force,
    piecewise_beam_force,
)

__all__ = ["piecewise_repulsive_force_from_scan", "repulsive_force_from_scan"]

# Beam direction tables keyed by (beam count, angle_min, angle_increment). A robot's
# scanner repeats the same geometry every scan, so the cosines and sines are computed
# once instead of on every call (they would cost more than the whole force sum).
# Each table is (2, N): the cosines in row 0, the sines in row 1 (one array for the
# kernel to unbox instead of two).
_TABLES: dict[tuple[int, float, float], FloatArray] = {}
_TABLES_MAX = 32


# The last table built or found, (angle_min, angle_increment, beam count, table):
# one scanner usually feeds every call, and comparing three numbers costs less
# than hashing a key (repulsive_force_from_scan checks it first).
_LAST: tuple[float, float, int, FloatArray] = (0.0, 0.0, 0, np.empty((2, 0)))


def _beam_directions(scan: LaserScan) -> FloatArray:
    """The read-only (2, N) table of the scan's beam cosines (row 0) and sines (row 1)."""
    global _LAST
    key = (scan.ranges.shape[0], scan.angle_min, scan.angle_increment)
    table = _TABLES.get(key)
    if table is None:
        # LaserScan's own angles, not a subclass's override: the table is shared by
        # every scan of this geometry, plain ones included, and the force is
        # documented over angle_min + k * angle_increment.
        angles = LaserScan.angles(scan)
        # np.cos(angles) as before, then copied (its SIMD loop, whatever the alignment
        # of a row of the table, so the values are those of the earlier tables).
        table = np.array((np.cos(angles), np.sin(angles)))
        table.setflags(write=False)
        # No lock: a thread forked while another held it would deadlock on its
        # first new table. Each dict operation is atomic; threads racing here can
        # at worst lose an entry or pass the bound by one each until the next clear.
        if len(_TABLES) >= _TABLES_MAX:
            _TABLES.clear()
        _TABLES[key] = table
    _LAST = (key[1], key[2], key[0], table)
    return table


# The last table whose rows _beam_table returned, and those rows: (table, cosines,
# sines). Slicing the rows anew made two array views per call, about 0.1 µs (7-9 %
# of piecewise_repulsive_force_from_scan on 360 beams). Holding the table
# keeps its id from being reused, so the identity check cannot match another.
_ROWS: tuple[FloatArray, FloatArray, FloatArray] = (np.empty((2, 0)), np.empty(0), np.empty(0))


def _beam_table(scan: LaserScan) -> tuple[FloatArray, FloatArray]:
    """The rows of :func:`_beam_directions`: (cosines, sines), each (N,), read-only."""
    global _ROWS
    table = _beam_directions(scan)
    # One read of _ROWS, checked and used as it was (another thread may replace it).
    rows = _ROWS
    if rows[0] is not table:
        rows = (table, table[0], table[1])
        _ROWS = rows
    return rows[1], rows[2]


_empty = np.empty

# khatib_beam_force_into's compiled entry, fetched at the first call
# (:func:`_khatib`) so that importing navkit compiles nothing.
_KHATIB: Callable[..., None] | None = None


def _khatib() -> Callable[..., None]:
    global _KHATIB
    _KHATIB = khatib_entry()
    return _KHATIB


def _check_scan(scan: Any) -> LaserScan:
    if not isinstance(scan, LaserScan):
        raise TypeError(
            f"scan must be a navkit.mapping.LaserScan, got {type(scan).__name__}"
            + scan_reading_hint(scan)
        )
    return scan


def scan_mount(mount: Pose2D | ArrayLike) -> Pose2D:
    """``mount`` (the sensor's pose in the robot frame) checked: finite, within ±1e9 m."""
    m = as_pose(mount, "mount")
    if not (abs(m.x) <= COORDINATE_LIMIT and abs(m.y) <= COORDINATE_LIMIT):
        raise ValueError(
            f"mount must lie within ±{COORDINATE_LIMIT:g} m in x and y, got ({m.x!r}, {m.y!r})"
        )
    return m


def _rotated(force: FloatArray, theta: float) -> FloatArray:
    """``force`` (sensor frame) turned by the mount's ``theta`` into the robot frame."""
    if theta == 0.0:
        return force
    c, s = np.cos(theta), np.sin(theta)
    fx, fy = force
    return np.array((c * fx - s * fy, s * fx + c * fy))


def _mounted_force(
    scan: LaserScan, mount: Pose2D, kernel: Callable[..., tuple[float, float]], *params: float
) -> FloatArray:
    """The force at the robot's origin from a scan taken at ``mount`` (``params`` checked).

    ``kernel`` is :func:`mounted_khatib_force` or :func:`mounted_piecewise_force`:
    the beams' end points ``scan.to_points(mount)`` (on the beam tables of
    LaserScan's own angles, as the per-beam sums) each push the origin from
    their own distance, as the point fields do; zero ranges, with no
    direction, push nothing.
    """
    cos_t, sin_t = _beam_table(scan)
    fx, fy = kernel(
        scan.ranges, cos_t, sin_t, scan.range_min, scan.range_max, *params,
        mount.x, mount.y, math.cos(mount.theta), math.sin(mount.theta),
    )  # fmt: skip
    return np.array((fx, fy))


def repulsive_force_from_scan(
    scan: LaserScan,
    *,
    k_rep: float = 1.0,
    influence_radius: float = 1.0,
    mount: Pose2D | ArrayLike | None = None,
) -> FloatArray:
    """Khatib repulsion summed over the beams of a scan, in the robot frame.

    Each valid beam (``range_min <= r < range_max``) is an obstacle point; the
    result is the force on a robot at the scan origin, in Khatib's symbols
    (``d0`` is ``influence_radius``)::

        F = Σ_k k_rep·(1/r_k - 1/d0)·(1/r_k²)·(-cos θ_k, -sin θ_k)   over r_k <= d0

    which equals ``KhatibRepulsion(scan.to_points(), k_rep=k_rep,
    influence_radius=influence_radius).force((0, 0))`` up to rounding (for
    ranges below about 1e-290 m, ``to_points`` rounds the sub-normal
    coordinates and with them the beam's direction, which the per-beam sum
    keeps exact). Invalid beams and beams
    beyond ``d0`` contribute nothing; as there, a beam shorter than 1e-9 m
    pushes as one of 1e-9 m (a finite force) and a zero range, which has no
    direction, not at all. The scan's arrays were validated when it was built,
    so the call only checks the two parameters.

    The scan is in the sensor frame: the robot frame when the sensor sits at
    the robot's origin facing forward (no ``mount``). A sensor mounted
    elsewhere (a :class:`navkit.sim.Lidar`'s ``mount``, a ``base_link ->
    laser`` transform) takes ``mount``: the force is then on the robot's
    origin from the beam end points ``mount ⊕ (r cos θ, r sin θ)``, each at its
    own distance from the robot, and equals
    ``KhatibRepulsion(scan.to_points(mount), ...).force((0, 0))`` up to
    rounding (zero ranges left out; compiled, like the per-beam sum). A
    mount that only turns the sensor (``x = y = 0``) turns the per-beam sum's
    force by its ``theta``.

    Parameters
    ----------
    scan : navkit.mapping.LaserScan
        The scan, in the sensor frame (x forward, y left of the sensor).
    k_rep : float, default 1.0
        Repulsion gain, in ``[1e-12, 1e12]``.
    influence_radius : float, default 1.0
        Khatib's ``d0`` (m), in ``[1e-6, 1e6]``: beams farther than this do
        not push.
    mount : Pose2D or array_like [x, y, theta], optional
        Pose of the sensor in the robot frame (m, m, rad), ``|x|, |y| <= 1e9``;
        None (the default) or ``(0, 0, 0)``: the scan is in the robot frame.

    Returns
    -------
    ndarray, shape (2,)
        Force ``(Fx, Fy)`` on the robot's origin in the robot frame, finite;
        zero when no beam end point is within ``influence_radius`` of it.

    Raises
    ------
    TypeError
        ``scan`` is not a LaserScan; a parameter is not a real number (or is a
        bool); ``mount`` not three real numbers.
    ValueError
        A parameter out of its range; ``mount`` not finite or beyond ±1e9 m.

    Notes
    -----
    The sum runs over SIMD lanes as wide as the CPU's vectors (the compiler may
    reorder it): the same scan gives the same bits on every machine of one CPU
    type, but may differ in the last bits between CPU types (AVX2 and
    AVX-512, say), and so may a run that steers by it.

    Examples
    --------
    >>> import math
    >>> scan = LaserScan([0.5, math.inf, 4.0], angle_min=0.0, angle_increment=math.pi / 2,
    ...                  range_min=0.1, range_max=10.0)
    >>> repulsive_force_from_scan(scan, k_rep=1.0, influence_radius=1.0)  # the beam 0.5 m ahead
    array([-4.,  0.])

    The same scan from a sensor 0.3 m behind the robot's centre: the wall is
    0.2 m from the centre, which is pushed harder.

    >>> repulsive_force_from_scan(scan, k_rep=1.0, influence_radius=1.0, mount=(-0.3, 0.0, 0.0))
    array([-100.,    0.])
    """
    # A LaserScan's ranges are a read-only C-contiguous float64 copy and its tables
    # match them, so the compiled entry (no type dispatch) can take them; a
    # subclass, whose attributes could be anything, goes through the dispatcher.
    # (The entry is fetched, compiled on a first use, only once the arguments pass.)
    if type(scan) is LaserScan:
        kernel = _KHATIB
    else:
        scan = _check_scan(scan)
        kernel = khatib_beam_force_into
    # Plain floats in range are taken as they are: this runs at every scan.
    if not (type(k_rep) is float and GAIN_MIN <= k_rep <= GAIN_MAX):
        k_rep = gain(k_rep, "k_rep")
    if not (type(influence_radius) is float and LENGTH_MIN <= influence_radius <= LENGTH_MAX):
        influence_radius = length(influence_radius, "influence_radius")
    if mount is not None:
        m = scan_mount(mount)
        if m.x != 0.0 or m.y != 0.0:
            return _mounted_force(
                scan, m, mounted_khatib_force, k_rep, influence_radius, MIN_DISTANCE
            )
        force = repulsive_force_from_scan(scan, k_rep=k_rep, influence_radius=influence_radius)
        return _rotated(force, m.theta)
    ranges = scan.ranges
    # One read of _LAST, checked and used as it was: another thread (or a scan
    # subclass's attribute) may store its own scanner's table in between.
    last = _LAST
    # len(), not .shape[0]: no shape tuple is built (ranges is 1-D).
    if last[2] == len(ranges) and last[0] == scan.angle_min and last[1] == scan.angle_increment:
        directions = last[3]
    else:
        directions = _beam_directions(scan)
    out = _empty(2)  # float64, the default (passing the dtype costs more)
    (kernel or _khatib())(
        ranges, directions, scan.range_min, scan.range_max, k_rep, influence_radius,
        MIN_DISTANCE, out,
    )  # fmt: skip
    return out


def piecewise_repulsive_force_from_scan(
    scan: LaserScan,
    *,
    delta: float = 1.0,
    beta: float = 1.0,
    obstacle_radius: float = 0.0,
    spread: float = 1.0,
    mount: Pose2D | ArrayLike | None = None,
) -> FloatArray:
    """Piecewise repulsion summed over the beams of a scan, in the robot frame.

    The omnidirectional LiDAR robot's field with every valid beam as an obstacle:
    in the paper's symbols (``r`` is ``obstacle_radius``, ``s`` is ``spread``) a
    beam at range ``ρ`` pushes the robot away with magnitude ``δ`` for ``ρ < r``,
    ``β(s + r - ρ)`` for ``r <= ρ <= s + r`` and 0 beyond. Equals
    ``PiecewiseRepulsion(scan.to_points(), ...).force((0, 0))`` with the same
    parameters, up to rounding at the jump: each range itself is compared
    with ``r`` here, while the point field recomputes the distance as
    ``hypot(ρ cos θ, ρ sin θ)``, which can round a range equal to ``r`` to just
    below it, so such a beam pushes with ``β·s`` here and ``δ`` there.
    A scan from a sensor mounted off the robot's origin takes ``mount``, as
    in :func:`repulsive_force_from_scan`: the force is then
    ``PiecewiseRepulsion(scan.to_points(mount), ...).force((0, 0))`` up to
    rounding (zero ranges left out).

    Parameters
    ----------
    scan : navkit.mapping.LaserScan
        The scan, in the sensor frame (x forward, y left of the sensor).
    delta : float, default 1.0
        Force magnitude ``δ`` inside ``obstacle_radius``, in ``[1e-12, 1e12]``.
    beta : float, default 1.0
        Gain ``β`` of the linear zone, in ``[1e-12, 1e12]``.
    obstacle_radius : float, default 0.0
        Obstacle (safety) radius ``r`` in metres, in ``[0, 1e6]``.
    spread : float, default 1.0
        Width ``s`` of the linear zone in metres, in ``[1e-6, 1e6]``.
    mount : Pose2D or array_like [x, y, theta], optional
        Pose of the sensor in the robot frame (m, m, rad), ``|x|, |y| <= 1e9``;
        None (the default) or ``(0, 0, 0)``: the scan is in the robot frame.

    Returns
    -------
    ndarray, shape (2,)
        Force ``(Fx, Fy)`` on the robot's origin in the robot frame, finite.

    Raises
    ------
    TypeError, ValueError
        As :func:`repulsive_force_from_scan`.

    Notes
    -----
    Summed over SIMD lanes, as :func:`repulsive_force_from_scan`: bit for bit
    the same on one CPU type, possibly not in the last bits across CPU types.

    Examples
    --------
    >>> import math
    >>> scan = LaserScan([0.5, math.nan], angle_min=0.0, angle_increment=math.pi / 2,
    ...                  range_min=0.1, range_max=10.0)
    >>> piecewise_repulsive_force_from_scan(scan, beta=2.0, spread=1.0)  # 2·(1 - 0.5) back
    array([-1.,  0.])
    >>> piecewise_repulsive_force_from_scan(scan, beta=2.0, spread=1.0,
    ...                                     mount=(0.25, 0.0, 0.0))  # 0.75 m ahead of the centre
    array([-0.5,  0. ])
    """
    scan = _check_scan(scan)
    dl = gain(delta, "delta")
    bt = gain(beta, "beta")
    rr = length(obstacle_radius, "obstacle_radius", allow_zero=True)
    ss = length(spread, "spread")
    if mount is not None:
        m = scan_mount(mount)
        if m.x != 0.0 or m.y != 0.0:
            return _mounted_force(scan, m, mounted_piecewise_force, dl, bt, rr, ss)
        force = piecewise_repulsive_force_from_scan(
            scan, delta=dl, beta=bt, obstacle_radius=rr, spread=ss
        )
        return _rotated(force, m.theta)
    cos_t, sin_t = _beam_table(scan)
    fx, fy = piecewise_beam_force(
        scan.ranges, cos_t, sin_t, scan.range_min, scan.range_max, dl, bt, rr, ss
    )
    return np.array((fx, fy))
