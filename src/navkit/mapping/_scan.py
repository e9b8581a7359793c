"""Planar laser scans with the fields of ROS ``sensor_msgs/LaserScan``."""

from __future__ import annotations

import math
from dataclasses import KW_ONLY, dataclass
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from navkit._shared.float32 import narrow_float_dtype
from navkit._shared.frozen import frozen_setattr, reduce_record, restore_read_only
from navkit._shared.types import BoolArray, FloatArray
from navkit._shared.validation import as_float_array, finite_float
from navkit.geometry import Pose2D, as_pose, wrap_angle
from navkit.mapping._limits import RANGE_LIMIT, bounded_float
from navkit.mapping._local_grid import LocalGrid

__all__ = ["LaserScan"]

_TURN = 2.0 * math.pi
# Slack for angles rounded to float32 in ROS messages.
_ANGLE_TOL = 1e-5


def _check_angles(angle_min: float, increment: float, n: int) -> None:
    """Refuse beam angles that no scanner gives in radians (degrees, most likely)."""
    angle_max = angle_min + (n - 1) * increment
    span = (n - 1) * abs(increment)
    hint = "the angles look like degrees; give them in radians (e.g. np.radians)"
    if abs(increment) > _TURN + _ANGLE_TOL:
        raise ValueError(f"angle_increment ({increment} rad) exceeds a full turn (2π): {hint}")
    if span > _TURN + abs(increment) + _ANGLE_TOL:
        raise ValueError(
            f"the {n} beams span {span:g} rad (angle_increment {increment} rad), more than "
            f"a full turn (2π = 6.283): {hint}"
        )
    for name, value in (("angle_min", angle_min), ("angle_max", angle_max)):
        if abs(value) > _TURN + _ANGLE_TOL:
            short = f"{value:g}"  # the value itself where :g would round it into range
            text = short if float(short) == value else repr(value)
            raise ValueError(f"{name} ({text} rad) lies beyond ±2π: {hint}")


def _at_limits(ranges: FloatArray, narrow: np.dtype[Any], rmin: float, rmax: float) -> None:
    """Readings of a float32 (or float16) array equal to ``range_min`` or ``range_max``
    in that precision become them, in place (``ranges``: the scan's own copy).

    A driver writing ``range_max`` for "no return" into a float32 array writes
    it rounded (5.6 as 5.599999904632568): compared with a float64
    ``range_max`` of 5.6 it read as a return 5.6 m away, and mapping marked an
    obstacle at every such beam's end (review 53). A ``range_min`` rounded down
    (0.7 as 0.699999988) read as too close likewise.

    A ``range_min`` the dtype rounds to 0 (float16's 2e-8) is left: a zero
    reading is the "no return" of drivers that write 0, and became a return at
    ``range_min``; so is one it rounds to its rounded ``range_max`` (float16's
    1000.1 and 1000.2, both 1000): the reading stays "no return".
    """
    with np.errstate(over="ignore", under="ignore"):  # float16 holds up to 65504 m
        low, high = float(narrow.type(rmin)), float(narrow.type(rmax))
    if math.isfinite(low) and low != rmin and low != 0.0 and low != high:
        ranges[ranges == low] = rmin
    if math.isfinite(high) and high != rmax:
        ranges[ranges == high] = rmax


def _readonly(arr: NDArray[Any]) -> NDArray[Any]:
    arr.flags.writeable = False
    return arr


@frozen_setattr
@dataclass(frozen=True, slots=True, eq=False)
class LaserScan:
    """One planar laser scan with the fields of ROS ``sensor_msgs/LaserScan``.

    Beam ``k`` points at ``angle_min + k * angle_increment`` in the sensor frame
    (x forward, y left). Readings follow ROS REP 117: ``+inf`` means nothing
    within range, ``-inf`` too close, NaN an invalid measurement. A reading is
    *valid* (a real return) when it is finite and ``range_min <= r < range_max``;
    a reading equal to ``range_max`` is treated as "no return", as most drivers
    and CARMEN logs report it. Ranges given as float32 (or float16) are compared
    in their precision: a reading equal to ``range_max`` (or ``range_min``)
    rounded to that dtype, as a driver writes it, is stored as ``range_max``
    (``range_min``) itself, so that 5.6 m written into a float32 array (5.5999999)
    is "no return" for a ``range_max`` of 5.6 too. ROS messages convert with
    :func:`navkit.mapping.io.scan_from_msg`. A driver that writes ``0`` for
    "no return" needs ``range_min > 0`` (the sensor's real minimum range):
    with ``range_min=0`` a zero reading is a valid return at the sensor
    itself, and mapping marks the robot's own cell occupied.

    Parameters
    ----------
    ranges : array_like, shape (N,)
        Ranges in metres (NaN and ±inf allowed), N >= 1. Stored as a read-only
        float64 copy (the caller's array is neither kept nor frozen).
    angle_min : float
        Angle of the first beam, rad, within ±2π.
    angle_increment : float
        Angle between consecutive beams, rad (non-zero; negative for scanners
        that sweep clockwise), at most a full turn. The last beam ``angle_max``
        must lie within ±2π too, and the beams may span at most a full turn
        plus one increment. Each of these limits has 1e-5 rad of slack, for
        angles rounded to float32 in ROS messages.
    range_min, range_max : float
        Valid range interval in metres, ``0 <= range_min < range_max <= 1e9``.
    intensities : array_like, shape (N,), optional
        Intensity of each beam; ``None`` or empty when the sensor gives none.
        Any float64 values, NaN and ±inf included: they are kept as the driver
        or log gave them (navkit computes nothing from them). Stored as a
        read-only float64 copy.

    Raises
    ------
    TypeError
        Complex, string or boolean data; a number that is not a real number.
    ValueError
        Empty ``ranges``, mismatched ``intensities``, a number outside its
        range, or beam angles that span more than a full turn or lie beyond
        ±2π (degrees given as radians: the message says so).

    Examples
    --------
    >>> import math
    >>> scan = LaserScan([1.0, math.inf, 2.0], angle_min=-math.pi / 2,
    ...                  angle_increment=math.pi / 2, range_min=0.1, range_max=10.0)
    >>> scan.valid_mask()
    array([ True, False,  True])
    >>> scan.to_points().round(12)
    array([[ 0., -1.],
           [ 0.,  2.]])
    >>> scan.to_points(Pose2D(1.0, 0.0, math.pi / 2)).round(12)
    array([[ 2.,  0.],
           [-1.,  0.]])
    """

    ranges: FloatArray
    _: KW_ONLY
    angle_min: float
    angle_increment: float
    range_min: float
    range_max: float
    intensities: FloatArray | None = None

    if TYPE_CHECKING:
        # The generated ``__init__`` takes the arrays as array_like (``__post_init__``
        # converts them); this signature tells type checkers so, at no runtime cost.
        def __init__(
            self,
            ranges: ArrayLike,
            *,
            angle_min: float,
            angle_increment: float,
            range_min: float,
            range_max: float,
            intensities: ArrayLike | None = ...,
        ) -> None: ...

    def __post_init__(self) -> None:
        ranges = np.array(as_float_array(self.ranges, "ranges", ndim=1, finite=False), copy=True)
        narrow = narrow_float_dtype(self.ranges)
        if ranges.shape[0] == 0:
            raise ValueError("ranges must hold at least one beam")
        object.__setattr__(self, "ranges", _readonly(ranges))
        start = finite_float(self.angle_min, "angle_min")
        inc = finite_float(self.angle_increment, "angle_increment")
        if inc == 0.0:
            raise ValueError("angle_increment must be non-zero")
        _check_angles(start, inc, ranges.shape[0])
        object.__setattr__(self, "angle_min", start)
        object.__setattr__(self, "angle_increment", inc)
        rmax = bounded_float(self.range_max, "range_max", 0.0, RANGE_LIMIT, "m", low_open=True)
        rmin = bounded_float(self.range_min, "range_min", 0.0, RANGE_LIMIT, "m")
        if rmax <= rmin:
            raise ValueError(f"range_max ({rmax}) must be greater than range_min ({rmin})")
        object.__setattr__(self, "range_min", rmin)
        object.__setattr__(self, "range_max", rmax)
        if narrow is not None:
            ranges.flags.writeable = True  # the scan's own copy, frozen again next
            _at_limits(ranges, narrow, rmin, rmax)
            ranges.flags.writeable = False
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

    def __reduce__(self) -> tuple[Any, ...]:
        """Copy and pickle support: the arrays read-only again, also in subclasses' copies."""
        return reduce_record(self, ("ranges", "intensities"))

    def __setstate__(self, state: list[Any]) -> None:
        """Restore from an older pickle, the arrays read-only again."""
        restore_read_only(self, state, ("ranges", "intensities"))

    def __len__(self) -> int:
        return int(self.ranges.shape[0])

    @property
    def angle_max(self) -> float:
        """Angle of the last beam, rad (not wrapped).

        Examples
        --------
        >>> LaserScan([1.0, 1.0, 1.0], angle_min=-0.5, angle_increment=0.25,
        ...           range_min=0.1, range_max=5.0).angle_max
        0.0
        """
        return self.angle_min + (len(self) - 1) * self.angle_increment

    def angles(self) -> FloatArray:
        """Sensor-frame angle of every beam, wrapped to (-π, π]; shape (N,).

        Returns
        -------
        ndarray, shape (N,)
            New array: ``angle_min + k * angle_increment`` in rad, wrapped.

        Examples
        --------
        >>> LaserScan([1.0, 1.0], angle_min=3.0, angle_increment=0.5,
        ...           range_min=0.1, range_max=5.0).angles().round(4)
        array([ 3.    , -2.7832])
        """
        raw = self.angle_min + self.angle_increment * np.arange(len(self), dtype=np.float64)
        # wrap_angle's arithmetic without its checks and fmod (most of this
        # call's time; a scanner whose angle_min varies from scan to scan pays
        # it at every repulsion call, which then misses its table cache). The
        # angles grow (or fall) with k, rounding included, so the two ends
        # bound them; within ±2π fmod returns them unchanged and only the fold
        # by 2π is left, on the same values: the result is wrap_angle's bit for
        # bit.
        if raw.size:
            first, last = float(raw[0]), float(raw[-1])
            low, high = min(first, last), max(first, last)
            if low > -math.pi and high <= math.pi:
                return raw
            if low > -_TURN and high < _TURN:
                above = raw > math.pi
                below = raw <= -math.pi
                raw[above] -= _TURN
                raw[below] += _TURN
                return raw
        return np.asarray(wrap_angle(raw), dtype=np.float64)

    def valid_mask(self) -> BoolArray:
        """True for real returns: finite and ``range_min <= r < range_max``; shape (N,).

        Returns
        -------
        ndarray of bool, shape (N,)
            New array, one entry per beam.

        Examples
        --------
        >>> LaserScan([0.01, 1.0, 5.0], angle_min=0.0, angle_increment=0.1,
        ...           range_min=0.1, range_max=5.0).valid_mask()
        array([False,  True, False])
        """
        r = self.ranges
        with np.errstate(invalid="ignore"):
            return np.isfinite(r) & (r >= self.range_min) & (r < self.range_max)

    def to_points(self, pose: Pose2D | ArrayLike | None = None) -> FloatArray:
        """End points of the valid beams, shape (M, 2), in the sensor or world frame.

        Parameters
        ----------
        pose : Pose2D or array_like [x, y, theta], optional
            World pose of the sensor. Without it the points are in the sensor frame.
            With it they follow the omnidirectional-robot paper's
            ``X_o = X + d cos(θ_n + θ)``, ``Y_o = Y + d sin(θ_n + θ)``.

        Returns
        -------
        ndarray, shape (M, 2)
            New array of ``(x, y)`` points in metres, one per valid beam (see
            :meth:`valid_mask`), in beam order.

        Raises
        ------
        TypeError, ValueError
            A ``pose`` that is not three finite real numbers.

        Examples
        --------
        >>> scan = LaserScan([2.0], angle_min=0.0, angle_increment=0.1,
        ...                  range_min=0.1, range_max=5.0)
        >>> scan.to_points((1.0, 1.0, 0.0))
        array([[3., 1.]])
        """
        valid = self.valid_mask()
        d = self.ranges[valid]
        phi = self.angles()[valid]
        if pose is None:
            return np.column_stack((d * np.cos(phi), d * np.sin(phi)))
        p = as_pose(pose, "pose")
        phi = phi + p.theta
        return np.column_stack((p.x + d * np.cos(phi), p.y + d * np.sin(phi)))

    def to_local_grid(
        self,
        *,
        half_width: float = 1.0,
        resolution: float = 0.1,
        mount: Pose2D | ArrayLike | None = None,
    ) -> LocalGrid:
        """Robot-centred occupancy grid of the valid returns (TurtleBot3 paper's grid).

        The grid is in the robot frame (x forward, y left): without ``mount``
        the scan is taken as one from the robot's centre, facing forward; with
        it each return is placed at its end point seen from the sensor's pose
        on the robot (``to_points(mount)``). With the defaults the result is
        the paper's 21 × 21 grid of 0.1 m cells centred from -1 m to 1 m, with
        ``i = 10 y + 10`` and ``j = 10 x + 10``.

        Parameters
        ----------
        half_width : float, default 1.0
            Distance in metres from the robot to the centres of the outermost
            cells (half the side less half a cell), in [0, 1e6], snapped to a
            multiple of ``resolution`` (keyword-only; as
            :meth:`LocalGrid.from_points <navkit.mapping.LocalGrid.from_points>`).
        resolution : float, default 0.1
            Cell size in metres, in [1e-6, 1e6] (keyword-only).
        mount : Pose2D or array_like [x, y, theta], optional
            The sensor's pose in the robot frame (m, m, rad), as
            ``navkit.sim.Lidar(mount=)`` (keyword-only). Default: at the
            robot's centre, facing forward.

        Returns
        -------
        LocalGrid
            The grid with the cells of the valid returns set; returns beyond
            the grid are dropped.

        Raises
        ------
        TypeError
            ``half_width`` or ``resolution`` not a real number (a bool
            included), or a ``mount`` that is not three real numbers.
        ValueError
            A number outside its range, a ``mount`` that is not finite, or a
            grid of more than ``2**28`` cells.

        Examples
        --------
        >>> import math
        >>> scan = LaserScan([0.5, 0.5], angle_min=0.0, angle_increment=math.pi / 2,
        ...                  range_min=0.05, range_max=3.5)
        >>> grid = scan.to_local_grid()
        >>> [tuple(int(v) for v in ij) for ij in np.argwhere(grid.occupied)]
        [(10, 15), (15, 10)]

        The same scan from a sensor 0.3 m ahead of the robot's centre:

        >>> grid = scan.to_local_grid(mount=(0.3, 0.0, 0.0))
        >>> [tuple(int(v) for v in ij) for ij in np.argwhere(grid.occupied)]
        [(10, 18), (15, 13)]
        """
        points = self.to_points() if mount is None else self.to_points(as_pose(mount, "mount"))
        return LocalGrid.from_points(points, half_width=half_width, resolution=resolution)
