"""Planar laser scans (``sensor_msgs/LaserScan``) and the robot-centred local grid."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from navkit._shared.validation import as_float_array, as_points, finite_float, positive_float
from navkit.geometry import Pose2D, as_pose, wrap_angle

__all__ = ["LaserScan", "LocalGrid"]


def _readonly(arr: NDArray[Any]) -> NDArray[Any]:
    arr.flags.writeable = False
    return arr


def _round_half_up(values: NDArray[np.float64]) -> NDArray[np.int64]:
    # np.rint rounds half to even; cell boundaries must not depend on parity.
    return np.floor(values + 0.5).astype(np.int64)


@dataclass(frozen=True, slots=True, eq=False)
class LocalGrid:
    """Square occupancy grid centred on the robot, in the robot frame.

    The grid of the TurtleBot3 obstacle-avoidance paper generalised to any size:
    cell ``(i, j)`` (``occupied[i, j]``) holds the robot-frame points
    (x forward, y left, metres) with ``i = round((y + half_width) / resolution)``
    and ``j = round((x + half_width) / resolution)``; with the defaults this is the
    paper's ``i = 10 y + 10``, ``j = 10 x + 10`` on a 21 × 21 grid. Cell centres
    lie on multiples of ``resolution`` and the robot is in the centre cell
    ``(n // 2, n // 2)``. Rounding is half-up.

    Parameters
    ----------
    occupied : ndarray of bool, shape (n, n)
        True where at least one obstacle point falls in the cell; ``n`` is odd.
    resolution : float
        Cell size in metres.
    half_width : float
        Distance in metres from the robot to the centre of the outermost cells;
        must equal ``(n - 1) / 2 * resolution``.

    Examples
    --------
    >>> grid = LocalGrid.from_points([[0.5, -0.2]], half_width=1.0, resolution=0.1)
    >>> grid.occupied.shape
    (21, 21)
    >>> grid.point_to_cell([0.5, -0.2])
    array([[ 8, 15]])
    >>> bool(grid.occupied[8, 15])
    True
    >>> grid.cell_to_point([10, 10])
    array([[0., 0.]])
    """

    occupied: NDArray[np.bool_]
    resolution: float
    half_width: float

    def __post_init__(self) -> None:
        occ = np.array(self.occupied, copy=True)
        if occ.dtype != np.bool_:
            raise TypeError(f"occupied must be a boolean array, got dtype {occ.dtype}")
        if occ.ndim != 2 or occ.shape[0] != occ.shape[1] or occ.shape[0] % 2 == 0:
            raise ValueError(f"occupied must be a square (n, n) array with n odd, got {occ.shape}")
        res = positive_float(self.resolution, "resolution")
        half = positive_float(self.half_width, "half_width", allow_zero=True)
        half_cells = (occ.shape[0] - 1) // 2
        if not math.isclose(half, half_cells * res, rel_tol=1e-9, abs_tol=1e-12):
            raise ValueError(
                f"half_width must be (n - 1) / 2 * resolution = {half_cells * res} for an "
                f"{occ.shape[0]} x {occ.shape[0]} grid, got {half}"
            )
        object.__setattr__(self, "occupied", _readonly(occ))
        object.__setattr__(self, "resolution", res)
        object.__setattr__(self, "half_width", half)

    @property
    def size(self) -> int:
        """Number of cells ``n`` along each side."""
        return int(self.occupied.shape[0])

    @classmethod
    def from_points(
        cls, points: ArrayLike, half_width: float = 1.0, resolution: float = 0.1
    ) -> LocalGrid:
        """Grid with the cells of the given robot-frame points set.

        Parameters
        ----------
        points : array_like, shape (N, 2)
            Obstacle points ``(x, y)`` in metres in the robot frame; points outside
            the grid are ignored.
        half_width : float, default 1.0
            Half the side of the grid in metres. It is snapped to the nearest
            multiple of ``resolution`` so that the robot sits on a cell centre.
        resolution : float, default 0.1
            Cell size in metres.
        """
        res = positive_float(resolution, "resolution")
        half = positive_float(half_width, "half_width", allow_zero=True)
        half_cells = round(half / res)
        n = 2 * half_cells + 1
        occ = np.zeros((n, n), dtype=np.bool_)
        pts = as_points(points, "points")
        snapped = half_cells * res
        cells = _round_half_up((pts[:, ::-1] + snapped) / res)
        inside = np.all((cells >= 0) & (cells < n), axis=1)
        occ[cells[inside, 0], cells[inside, 1]] = True
        return cls(occ, res, snapped)

    def point_to_cell(self, points: ArrayLike) -> NDArray[np.int64]:
        """Cells ``(row i, col j)`` of robot-frame points ``(x, y)``; shape (N, 2).

        Indices of points outside the grid are returned unclipped (they fall
        outside ``[0, n)``); use :meth:`contains` to test.
        """
        pts = as_points(points, "points")
        return _round_half_up((pts[:, ::-1] + self.half_width) / self.resolution)

    def cell_to_point(self, cells: ArrayLike) -> NDArray[np.float64]:
        """Robot-frame centres ``(x, y)`` in metres of cells ``(row, col)``; shape (N, 2)."""
        arr = as_points(cells, "cells")
        if not np.all(arr == np.round(arr)):
            raise ValueError("cells must hold integer (row, col) indices")
        return arr[:, ::-1] * self.resolution - self.half_width

    def contains(self, points: ArrayLike) -> NDArray[np.bool_]:
        """Whether each robot-frame point ``(x, y)`` falls in a cell of the grid; shape (N,)."""
        cells = self.point_to_cell(points)
        inside: NDArray[np.bool_] = np.all((cells >= 0) & (cells < self.size), axis=1)
        return inside


@dataclass(frozen=True, slots=True, eq=False)
class LaserScan:
    """One planar laser scan with the fields of ROS ``sensor_msgs/LaserScan``.

    Beam ``k`` points at ``angle_min + k * angle_increment`` in the sensor frame
    (x forward, y left). Readings follow ROS REP 117: ``+inf`` means nothing
    within range, ``-inf`` too close, NaN an invalid measurement. A reading is
    *valid* (a real return) when it is finite and ``range_min <= r < range_max``;
    a reading equal to ``range_max`` is treated as "no return", as most drivers
    and CARMEN logs report it.

    Parameters
    ----------
    ranges : array_like, shape (N,)
        Ranges in metres (NaN and ±inf allowed). Stored as a read-only float64 copy.
    angle_min : float
        Angle of the first beam, rad.
    angle_increment : float
        Angle between consecutive beams, rad (non-zero; negative for scanners
        that sweep clockwise).
    range_min, range_max : float
        Valid range interval in metres, ``0 <= range_min < range_max``.
    intensities : array_like, shape (N,), optional
        Intensity of each beam; ``None`` or empty when the sensor gives none.

    Examples
    --------
    >>> import math
    >>> scan = LaserScan([1.0, math.inf, 2.0], -math.pi / 2, math.pi / 2, 0.1, 10.0)
    >>> scan.valid_mask()
    array([ True, False,  True])
    >>> scan.to_points().round(12)
    array([[ 0., -1.],
           [ 0.,  2.]])
    >>> scan.to_points(Pose2D(1.0, 0.0, math.pi / 2)).round(12)
    array([[ 2.,  0.],
           [-1.,  0.]])
    """

    ranges: NDArray[np.float64]
    angle_min: float
    angle_increment: float
    range_min: float
    range_max: float
    intensities: NDArray[np.float64] | None = None

    def __post_init__(self) -> None:
        ranges = np.array(as_float_array(self.ranges, "ranges", ndim=1, finite=False), copy=True)
        if ranges.shape[0] == 0:
            raise ValueError("ranges must hold at least one beam")
        object.__setattr__(self, "ranges", _readonly(ranges))
        object.__setattr__(self, "angle_min", finite_float(self.angle_min, "angle_min"))
        inc = finite_float(self.angle_increment, "angle_increment")
        if inc == 0.0:
            raise ValueError("angle_increment must be non-zero")
        object.__setattr__(self, "angle_increment", inc)
        rmin = positive_float(self.range_min, "range_min", allow_zero=True)
        rmax = positive_float(self.range_max, "range_max")
        if rmax <= rmin:
            raise ValueError(f"range_max ({rmax}) must be greater than range_min ({rmin})")
        object.__setattr__(self, "range_min", rmin)
        object.__setattr__(self, "range_max", rmax)
        if self.intensities is not None:
            inten = np.array(
                as_float_array(self.intensities, "intensities", ndim=1, finite=False), copy=True
            )
            if inten.shape[0] == 0:
                object.__setattr__(self, "intensities", None)
                return
            if inten.shape != ranges.shape:
                raise ValueError(
                    f"intensities must have the same length as ranges ({ranges.shape[0]}), "
                    f"got {inten.shape[0]}"
                )
            object.__setattr__(self, "intensities", _readonly(inten))

    def __len__(self) -> int:
        return int(self.ranges.shape[0])

    @property
    def angle_max(self) -> float:
        """Angle of the last beam, rad (not wrapped)."""
        return self.angle_min + (len(self) - 1) * self.angle_increment

    def angles(self) -> NDArray[np.float64]:
        """Sensor-frame angle of every beam, wrapped to (-π, π]; shape (N,)."""
        raw = self.angle_min + self.angle_increment * np.arange(len(self), dtype=np.float64)
        return np.asarray(wrap_angle(raw), dtype=np.float64)

    def valid_mask(self) -> NDArray[np.bool_]:
        """True for real returns: finite and ``range_min <= r < range_max``; shape (N,)."""
        r = self.ranges
        with np.errstate(invalid="ignore"):
            return np.isfinite(r) & (r >= self.range_min) & (r < self.range_max)

    def to_points(self, pose: Pose2D | ArrayLike | None = None) -> NDArray[np.float64]:
        """End points of the valid beams, shape (M, 2), in the sensor or world frame.

        Parameters
        ----------
        pose : Pose2D or array_like [x, y, theta], optional
            World pose of the sensor. Without it the points are in the sensor frame.
            With it they follow the omnidirectional-robot paper's
            ``X_o = X + d cos(θ_n + θ)``, ``Y_o = Y + d sin(θ_n + θ)``.
        """
        valid = self.valid_mask()
        d = self.ranges[valid]
        phi = self.angles()[valid]
        if pose is None:
            return np.column_stack((d * np.cos(phi), d * np.sin(phi)))
        p = as_pose(pose, "pose")
        phi = phi + p.theta
        return np.column_stack((p.x + d * np.cos(phi), p.y + d * np.sin(phi)))

    def to_local_grid(self, half_width: float = 1.0, resolution: float = 0.1) -> LocalGrid:
        """Robot-centred occupancy grid of the valid returns (TurtleBot3 paper's grid).

        The scan is assumed to be taken in the robot frame (x forward, y left).
        With the defaults the result is the paper's 21 × 21 grid of 0.1 m cells
        covering ±1 m, with ``i = 10 y + 10`` and ``j = 10 x + 10``; see
        :class:`LocalGrid`.

        Examples
        --------
        >>> scan = LaserScan([0.5, 0.5], 0.0, math.pi / 2, 0.05, 3.5)
        >>> grid = scan.to_local_grid()
        >>> [tuple(int(v) for v in ij) for ij in np.argwhere(grid.occupied)]
        [(10, 15), (15, 10)]
        """
        return LocalGrid.from_points(self.to_points(), half_width, resolution)

    @classmethod
    def from_msg(cls, msg: Any) -> LaserScan:
        """Build a scan from any object with the ``sensor_msgs/LaserScan`` field names.

        Reads ``ranges``, ``angle_min``, ``angle_increment``, ``range_min``,
        ``range_max`` and (when present and non-empty) ``intensities``. ROS is not
        imported; a real message or any look-alike works.

        Examples
        --------
        >>> from types import SimpleNamespace
        >>> msg = SimpleNamespace(ranges=[1.0, 2.0], angle_min=0.0, angle_increment=0.1,
        ...                       range_min=0.1, range_max=5.0, intensities=[])
        >>> LaserScan.from_msg(msg).intensities is None
        True
        """
        fields = {}
        for name in ("ranges", "angle_min", "angle_increment", "range_min", "range_max"):
            if not hasattr(msg, name):
                raise TypeError(f"msg has no field {name!r}; expected a sensor_msgs/LaserScan")
            fields[name] = getattr(msg, name)
        intensities = getattr(msg, "intensities", None)
        return cls(
            np.asarray(fields["ranges"], dtype=np.float64),
            fields["angle_min"],
            fields["angle_increment"],
            fields["range_min"],
            fields["range_max"],
            None if intensities is None else np.asarray(intensities, dtype=np.float64),
        )
