"""Repulsive forces straight from a laser scan: every valid beam is an obstacle point."""

from __future__ import annotations

import math
import threading
from typing import Any

import numpy as np
from numpy.typing import NDArray

from navkit._shared.validation import positive_float
from navkit.mapping import LaserScan
from navkit.planning.reactive._scan_repulsion_kernels import khatib_beam_force, piecewise_beam_force

__all__ = ["piecewise_repulsive_force_from_scan", "repulsive_force_from_scan"]

FloatArray = NDArray[np.float64]

# Beam direction tables keyed by (beam count, angle_min, angle_increment). A robot's
# scanner repeats the same geometry every scan, so the cosines and sines are computed
# once instead of on every call (they would cost more than the whole force sum).
_TABLES: dict[tuple[int, float, float], tuple[FloatArray, FloatArray]] = {}
_TABLES_MAX = 32
_TABLES_LOCK = threading.Lock()


def _beam_table(scan: LaserScan) -> tuple[FloatArray, FloatArray]:
    key = (scan.ranges.shape[0], scan.angle_min, scan.angle_increment)
    table = _TABLES.get(key)
    if table is None:
        angles = scan.angles()
        cos_t = np.cos(angles)
        sin_t = np.sin(angles)
        cos_t.setflags(write=False)
        sin_t.setflags(write=False)
        table = (cos_t, sin_t)
        with _TABLES_LOCK:
            if len(_TABLES) >= _TABLES_MAX:
                _TABLES.clear()
            _TABLES[key] = table
    return table


def _positive(value: Any, name: str, *, allow_zero: bool = False) -> float:
    # Fast path for the common plain-float argument; anything else gets the full checks.
    if type(value) is float and (value > 0.0 or (allow_zero and value == 0.0)) and value < math.inf:
        return value
    return positive_float(value, name, allow_zero=allow_zero)


def _check_scan(scan: Any) -> LaserScan:
    if not isinstance(scan, LaserScan):
        raise TypeError(f"scan must be a navkit.mapping.LaserScan, got {type(scan).__name__}")
    return scan


def repulsive_force_from_scan(scan: LaserScan, k_rep: float = 1.0, d0: float = 1.0) -> FloatArray:
    """Khatib repulsion summed over the beams of a scan, in the robot (sensor) frame.

    Each valid beam (``range_min <= r < range_max``) is an obstacle point; the
    result is the force on a robot at the scan origin::

        F = Σ_k k_rep·(1/r_k - 1/d0)·(1/r_k²)·(-cos θ_k, -sin θ_k)   over r_k <= d0

    which equals ``KhatibRepulsion(scan.to_points(), k_rep=k_rep, d0=d0).force((0, 0))``.
    Invalid beams and beams beyond ``d0`` contribute nothing. The scan's arrays
    were validated when it was built, so the call only checks the two gains.

    Parameters
    ----------
    scan : navkit.mapping.LaserScan
        The scan, taken in the robot frame (x forward, y left).
    k_rep : float, default 1.0
        Repulsion gain, > 0.
    d0 : float, default 1.0
        Influence distance (m), > 0.

    Returns
    -------
    ndarray, shape (2,)
        Force ``(Fx, Fy)`` in the robot frame; zero when no beam is within ``d0``.

    Examples
    --------
    >>> import math
    >>> scan = LaserScan([0.5, math.inf, 4.0], 0.0, math.pi / 2, 0.1, 10.0)
    >>> repulsive_force_from_scan(scan, k_rep=1.0, d0=1.0)  # only the beam at 0.5 m ahead
    array([-4.,  0.])
    """
    scan = _check_scan(scan)
    k = _positive(k_rep, "k_rep")
    d = _positive(d0, "d0")
    cos_t, sin_t = _beam_table(scan)
    fx, fy = khatib_beam_force(scan.ranges, cos_t, sin_t, scan.range_min, scan.range_max, k, d)
    return np.array((fx, fy))


def piecewise_repulsive_force_from_scan(
    scan: LaserScan, delta: float = 1.0, beta: float = 1.0, r: float = 0.0, s: float = 1.0
) -> FloatArray:
    """Piecewise repulsion summed over the beams of a scan, in the robot (sensor) frame.

    The omnidirectional LiDAR robot's field with every valid beam as an obstacle:
    a beam at range ``ρ`` pushes the robot away with magnitude ``δ`` for
    ``ρ < r``, ``β(s + r - ρ)`` for ``r <= ρ <= s + r`` and 0 beyond. Equals
    ``PiecewiseRepulsion(scan.to_points(), ...).force((0, 0))``.

    Parameters
    ----------
    scan : navkit.mapping.LaserScan
        The scan, taken in the robot frame (x forward, y left).
    delta : float, default 1.0
        Force magnitude inside ``r``, > 0.
    beta : float, default 1.0
        Gain of the linear zone, > 0.
    r : float, default 0.0
        Obstacle (safety) radius in metres, >= 0.
    s : float, default 1.0
        Width of the linear zone in metres, > 0.

    Returns
    -------
    ndarray, shape (2,)
        Force ``(Fx, Fy)`` in the robot frame.

    Examples
    --------
    >>> import math
    >>> scan = LaserScan([0.5, math.nan], 0.0, math.pi / 2, 0.1, 10.0)
    >>> piecewise_repulsive_force_from_scan(scan, beta=2.0, s=1.0)  # 2·(1 - 0.5) backwards
    array([-1.,  0.])
    """
    scan = _check_scan(scan)
    dl = _positive(delta, "delta")
    bt = _positive(beta, "beta")
    rr = _positive(r, "r", allow_zero=True)
    ss = _positive(s, "s")
    cos_t, sin_t = _beam_table(scan)
    fx, fy = piecewise_beam_force(
        scan.ranges, cos_t, sin_t, scan.range_min, scan.range_max, dl, bt, rr, ss
    )
    return np.array((fx, fy))
