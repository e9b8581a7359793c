"""The simulated world: static geometry, an occupancy grid and moving obstacles."""

from __future__ import annotations

import math
import numbers
from collections.abc import Iterable, Mapping
from dataclasses import KW_ONLY, dataclass, field
from types import MappingProxyType
from typing import TYPE_CHECKING, Any, Literal

import numpy as np
import shapely
from numpy.typing import ArrayLike
from shapely.geometry import Polygon
from shapely.geometry.base import BaseGeometry

from navkit._shared.counts import counted
from navkit._shared.deprecation import renamed_keyword
from navkit._shared.frozen import (
    frozen_setattr,
    reduce_record,
    restore_read_only,
    restore_slots,
    slot_names,
)
from navkit._shared.locks import ForkSafeLock
from navkit._shared.text import as_text
from navkit._shared.types import FloatArray, IntArray
from navkit._shared.validation import (
    as_bool,
    as_float_array,
    finite_float,
    kernel_input,
    positive_float,
    refuse_masked,
)
from navkit.geometry import Pose2D, as_pose
from navkit.mapping import OccupancyGrid
from navkit.sim._clearance_kernels import TOUCH, edge_clearance, footprint_clearance
from navkit.sim._edge_grid_kernels import build_cell_lists, chebyshev_distance
from navkit.sim._lidar_kernels import cast_edge_rays, cast_occupancy_rays
from navkit.sim._moving_kernels import EXTEND, LOOP, STOP, place_moving

__all__ = ["Circle", "MovingObstacle", "World"]

#: Largest coordinate magnitude accepted anywhere in a world, m.
MAX_COORD = 1e6
#: What the refusal of world coordinates beyond MAX_COORD suggests: a map in UTM or
#: another projected frame is simulated in a local frame (the LiDAR's on-line
#: tolerance, 1e-9 m, is absolute: a few float steps at 1e6 m, under one at 4.5e6 m).
_LOCAL_FRAME_HINT = (
    " (a map in UTM or another projected frame: simulate it in a local frame, its "
    "origin and every pose shifted by the same offset, e.g. the map's origin)"
)
#: Most segments (edges) a world may hold.
MAX_SEGMENTS = 10_000_000
#: Most (cell, primitive) entries of the edge index.
MAX_INDEX_ENTRIES = 100_000_000
#: Most vertices of a footprint polygon.
MAX_FOOTPRINT_VERTICES = 1000
#: Cells of the edge index per primitive (the index's density).
_CELLS_PER_PRIMITIVE = 2.0
#: Largest number of index cells along one axis.
_MAX_CELLS_PER_AXIS = 2048
#: Most index entries per primitive the cell size allows for the primitives' lengths.
_ENTRIES_PER_PRIMITIVE = 32.0
#: Up to this many solid circles a point is tested against each (NumPy's selection
#: of the near ones costs more than the loop over a few).
_FEW_CIRCLES = 16

_EMPTY4 = np.empty((0, 4))
#: Beam directions of a scan in one pass (never written nor read).
_NO_DIRS = np.empty((0, 2))


def _read_only(arr: np.ndarray) -> np.ndarray:
    arr.flags.writeable = False
    return arr


def _coords(value: ArrayLike, name: str, shape: tuple[int | None, ...]) -> FloatArray:
    arr = as_float_array(value, name, shape=shape)
    if arr.size and float(np.max(np.abs(arr))) > MAX_COORD:
        raise ValueError(f"{name} must lie within ±{MAX_COORD:g} m")
    return arr


MAX_POSE_COORD = 1e12
#: Largest time magnitude of a waypoint or of a query of the moving obstacles, s.
MAX_TIME = 1e9
#: Largest speed along each axis of an obstacle that carries on (``after="extend"``), m/s.
MAX_EXTEND_SPEED = 1e3


def _time_error(name: str, worst: float, shown: str) -> ValueError:
    """The error for a time beyond ±MAX_TIME s, with advice for an epoch stamp.

    ``worst`` is the largest magnitude given, ``shown`` how the message shows the
    value (empty: not shown). Times since 1970 (1.7e9 s in 2024, up to 1e10 s) are
    a recorded track's stamps, most likely (a pedestrian from a bag): a simulation
    starts at t = 0, so such a track needs its times from its own start.

    Examples
    --------
    >>> print(_time_error("times", 1.78e9, ""))
    times must lie within ±1e+09 s (epoch stamps? a simulation starts at t = 0:
    give times since the start, times - times[0])
    """
    hint = ""
    if worst <= 1e10:
        since = "times - times[0]" if name == "times" else "t - t0, t0 the start's stamp"
        hint = f" (epoch stamps? a simulation starts at t = 0: give times since the start, {since})"
    got = f", got {shown}" if shown else ""
    return ValueError(f"{name} must lie within ±{MAX_TIME:g} s{got}{hint}")


def _query_time(t: Any, name: str = "t") -> float:
    """A query time within ±MAX_TIME s.

    With waypoints within ±1e6 m and ``after="extend"`` speeds within ±1e3 m/s
    this keeps every obstacle within ±(1e6 + 2e12) m: finite, with squared
    distances far from overflowing (a huge ``t`` would silently give inf/NaN).
    """
    time = finite_float(t, name)
    if abs(time) > MAX_TIME:
        raise _time_error(name, abs(time), repr(time))
    return time


def as_query_pose(value: Any, name: str = "pose") -> Pose2D:
    """A query pose, its position within ±1e12 m (distances must not overflow)."""
    p = as_pose(value, name)
    if abs(p.x) > MAX_POSE_COORD or abs(p.y) > MAX_POSE_COORD:
        raise ValueError(f"{name} must lie within ±{MAX_POSE_COORD:g} m, got ({p.x:g}, {p.y:g})")
    return p


def as_footprint(value: Any, name: str = "footprint") -> tuple[float, FloatArray]:
    """``(radius, vertices (V, 2))`` of a footprint: a radius or a polygon (robot frame).

    A disc gives ``(radius, empty (0, 2))``; a polygon (shapely ``Polygon`` or
    ``(V, 2)`` vertices, V >= 3) gives ``(0.0, vertices)`` without the closing
    vertex.
    """
    if isinstance(value, bool):
        raise TypeError(f"{name} must be a radius (m) or a polygon, got bool")
    if issubclass(type(value), np.ndarray) and value.ndim == 0 and value.dtype.kind in "fiu":
        refuse_masked(value, name)  # .item() would read a masked radius's data
        value = value.item()
    if isinstance(value, numbers.Real):
        radius = positive_float(value, name)
        if radius > MAX_COORD:
            raise ValueError(f"{name} radius must be at most {MAX_COORD:g} m, got {radius}")
        return radius, _read_only(np.empty((0, 2)))
    if isinstance(value, Polygon):
        if value.is_empty:
            raise ValueError(f"{name} polygon is empty")
        if len(value.interiors):
            raise ValueError(f"{name} polygon must not have holes")
        # x, y only: a polygon with z coordinates has three columns.
        verts = np.asarray(value.exterior.coords, dtype=np.float64)[:-1, :2]
    elif isinstance(value, BaseGeometry):
        raise TypeError(
            f"{name} must be a radius (m) or a Polygon, got a {value.geom_type}"
        )
    else:
        if isinstance(value, (str, bytes)):
            raise TypeError(f"{name} must be a radius (m) or a polygon, got {type(value).__name__}")
        verts = _coords(value, name, (None, 2))
    if verts.shape[0] < 3:
        raise ValueError(f"{name} polygon needs at least 3 vertices, got {verts.shape[0]}")
    if verts.shape[0] > MAX_FOOTPRINT_VERTICES:
        raise ValueError(
            f"{name} polygon may have at most {MAX_FOOTPRINT_VERTICES} vertices, "
            f"got {verts.shape[0]}"
        )
    if float(np.max(np.abs(verts))) > MAX_COORD:
        raise ValueError(f"{name} must lie within ±{MAX_COORD:g} m")
    poly = Polygon(verts)
    if not poly.is_valid or poly.area <= 0.0:
        raise ValueError(f"{name} polygon must be simple (no self-intersection) with area > 0")
    # Read-only like every array handed to the kernels: one compiled specialisation.
    return 0.0, _read_only(np.array(verts, dtype=np.float64, order="C"))


def _footprint_arrays(
    verts: FloatArray,
) -> tuple[FloatArray | None, FloatArray | None, FloatArray | None]:
    """A footprint's vertices and two work arrays of their shape, as the kernels take them.

    None for a disc (no vertices): the kernels then compile only the disc's
    distance code.
    """
    if verts.shape[0] == 0:
        return None, None, None
    return verts, np.empty_like(verts), np.empty_like(verts)


@frozen_setattr
@dataclass(frozen=True, slots=True, eq=False)
class Circle:
    """A circular obstacle, intersected analytically by rays and footprints.

    Parameters
    ----------
    center_xy : array_like, shape (2,)
        Centre, m (world frame). Stored as a read-only float64 copy.
    radius : float
        Radius, m, in (0, 1e6].
    solid : bool, default True
        True for a solid disc (a pillar, a ball); False for a circular wall,
        e.g. the boundary of a circular room, inside which a robot may stand.
        Keyword-only.

    Raises
    ------
    TypeError
        A non-numeric ``center_xy`` or ``radius``.
    ValueError
        A ``radius`` not > 0; NaN or inf.

    Examples
    --------
    >>> room = Circle((0.0, 0.0), 5.0, solid=False)
    >>> room.radius, room.solid
    (5.0, False)
    """

    center_xy: FloatArray
    radius: float
    _: KW_ONLY
    solid: bool = True

    if TYPE_CHECKING:
        # The generated ``__init__`` takes the arrays as array_like (``__post_init__``
        # converts them); this signature tells type checkers so, at no runtime cost.
        def __init__(
            self,
            center_xy: ArrayLike,
            radius: float,
            *,
            solid: bool = ...,
        ) -> None: ...

    def __post_init__(self) -> None:
        center = np.array(_coords(self.center_xy, "center_xy", (2,)), copy=True)
        object.__setattr__(self, "center_xy", _read_only(center))
        radius = positive_float(self.radius, "radius")
        if radius > MAX_COORD:
            raise ValueError(f"radius must be at most {MAX_COORD:g} m, got {radius}")
        object.__setattr__(self, "radius", radius)
        object.__setattr__(self, "solid", as_bool(self.solid, "solid"))

    def __reduce__(self) -> tuple[Any, ...]:
        """Copy and pickle support: the arrays read-only again, also in subclasses' copies."""
        return reduce_record(self, ("center_xy",))

    def __setstate__(self, state: list[Any]) -> None:
        """Restore from an older pickle, the arrays read-only again."""
        restore_read_only(self, state, ("center_xy",))


_AFTER_CODES = {"stop": STOP, "loop": LOOP, "extend": EXTEND}


@frozen_setattr
@dataclass(frozen=True, slots=True, eq=False)
class MovingObstacle:
    """An obstacle that translates along a timed polyline (it never rotates).

    Build one with :meth:`constant_velocity` or :meth:`scripted`. Its position
    at time ``t`` is interpolated linearly between the waypoints; before the
    first time it waits at the first waypoint, after the last it stops
    (``after="stop"``), starts over from the first (``"loop"``, which jumps
    back unless the path is closed) or carries on with the last leg's velocity
    (``"extend"``).

    Parameters
    ----------
    shape : float, shapely Polygon or array_like (V, 2)
        A radius (m) for a disc, or a polygon (or its vertices, stored as a
        Polygon) given relative to the obstacle's reference point (its position).
    path_xy : array_like, shape (K, 2)
        Waypoints of the reference point, m.
    times : array_like, shape (K,)
        Time of each waypoint, s, strictly increasing, within ±1e9 s.
    after : {"stop", "loop", "extend"}, default "stop"
        Motion after the last waypoint (keyword-only). With ``"extend"`` the
        last leg's velocity must lie within ±1e3 m/s along each axis (as for
        :meth:`constant_velocity`), so that positions at any query time
        (within ±1e9 s) stay finite.

    Raises
    ------
    TypeError
        A ``shape`` that is neither a radius nor a polygon; non-numeric
        ``path_xy`` or ``times``.
    ValueError
        A ``shape`` not > 0, bad shapes of ``path_xy`` and ``times``, NaN or
        inf.

    Examples
    --------
    >>> ball = MovingObstacle.constant_velocity(0.1, start_xy=(0.0, 0.0), velocity_xy=(1.0, 0.5))
    >>> ball.position_at(2.0)
    array([2., 1.])
    >>> opponent = MovingObstacle.scripted(0.2, [(0.0, 0.0), (2.0, 0.0)], speed=0.5, after="loop")
    >>> opponent.position_at(1.0), opponent.position_at(5.0)
    (array([0.5, 0. ]), array([0.5, 0. ]))
    """

    shape: float | Polygon
    path_xy: FloatArray
    times: FloatArray
    _: KW_ONLY
    after: Literal["stop", "loop", "extend"] = "stop"

    # The velocity given to constant_velocity (read-only (2,)), None otherwise: the
    # difference of its two waypoints loses the velocity's bits below ulp(start),
    # a drift of up to ulp(start) · t. Not an init field: dataclasses.replace,
    # which may change the waypoints, leaves it None (the waypoints then rule).
    _velocity: FloatArray | None = field(default=None, init=False, repr=False)

    if TYPE_CHECKING:
        # The generated ``__init__`` takes vertices and arrays as array_like
        # (``__post_init__`` converts them); this tells type checkers so, at no runtime cost.
        def __init__(
            self,
            shape: float | Polygon | ArrayLike,
            path_xy: ArrayLike,
            times: ArrayLike,
            *,
            after: Literal["stop", "loop", "extend"] = ...,
        ) -> None: ...

    def __post_init__(self) -> None:
        radius, verts = as_footprint(self.shape, "shape")
        if radius:
            object.__setattr__(self, "shape", radius)
        elif not isinstance(self.shape, Polygon):
            # Vertices (V, 2), accepted as for a footprint: stored as the Polygon the
            # rest of the class (and World) works with.
            object.__setattr__(self, "shape", Polygon(verts))
        path = np.array(_coords(self.path_xy, "path_xy", (None, 2)), copy=True)
        if path.shape[0] == 0:
            raise ValueError("path_xy must hold at least one waypoint")
        times = np.array(as_float_array(self.times, "times", shape=(path.shape[0],)), copy=True)
        if times.size and (worst := float(np.max(np.abs(times)))) > MAX_TIME:
            raise _time_error("times", worst, "")
        if np.any(np.diff(times) <= 0.0):
            raise ValueError("times must be strictly increasing")
        if not isinstance(self.after, str):
            raise ValueError(f"after must be 'stop', 'loop' or 'extend', got {self.after!r}")
        # Plain str (an np.str_ printed as np.str_('loop') in the record's repr), checked
        # as stored: a subclass's own == (case-blind, say) let "LOOP" through, and World
        # then found no code for it (a bare KeyError).
        after = as_text(self.after, "after")
        if after not in _AFTER_CODES:
            raise ValueError(f"after must be 'stop', 'loop' or 'extend', got {after!r}")
        object.__setattr__(self, "after", after)
        if self.after == "extend" and path.shape[0] < 2:
            raise ValueError("after='extend' needs at least two waypoints")
        if self.after == "extend":
            with np.errstate(over="ignore"):
                # The division may overflow (legs of a few ulp): inf fails the check.
                velocity = (path[-1] - path[-2]) / (times[-1] - times[-2])
            if float(np.max(np.abs(velocity))) > MAX_EXTEND_SPEED:
                raise ValueError(
                    f"after='extend' needs the last leg of path_xy/times at most "
                    f"{MAX_EXTEND_SPEED:g} m/s along each axis, got {velocity.tolist()} m/s"
                )
        object.__setattr__(self, "path_xy", _read_only(path))
        object.__setattr__(self, "times", _read_only(times))

    def __reduce__(self) -> tuple[Any, ...]:
        """Copy and pickle support: the arrays read-only again, also in subclasses' copies."""
        return reduce_record(self, ("path_xy", "times", "_velocity"))

    def __setstate__(self, state: list[Any]) -> None:
        """Restore from an older pickle, the arrays read-only again."""
        # Pickles made before the velocity was kept hold only the four init fields.
        values = [*state, None] if len(state) == 4 else state
        restore_read_only(self, values, ("path_xy", "times", "_velocity"))

    @classmethod
    def constant_velocity(
        cls, shape: float | Polygon | ArrayLike, *, start_xy: ArrayLike, velocity_xy: ArrayLike
    ) -> MovingObstacle:
        """An obstacle at ``start_xy`` at t = 0 moving at ``velocity_xy`` (m/s) forever.

        Parameters
        ----------
        shape : float, shapely Polygon or array_like (V, 2)
            A radius (m) for a disc, or a polygon (or its vertices) given
            relative to the obstacle's reference point (its position).
        start_xy : array_like, shape (2,)
            Position of the reference point at t = 0, m (keyword-only).
        velocity_xy : array_like, shape (2,)
            Constant velocity, m/s, each component within ±1e3 (keyword-only);
            ``start_xy + velocity_xy`` (the second waypoint) must lie within
            ±1e6 m.

        Returns
        -------
        MovingObstacle
            A two-waypoint obstacle (t = 0 and t = 1 s) with ``after="extend"``;
            before t = 0 it waits at ``start_xy``. It keeps ``velocity_xy``
            itself: its position at t >= 0 is ``start_xy + velocity_xy · t``
            correctly rounded twice (the product, then the sum), not
            extrapolated from the waypoints, whose difference may lose up to
            ulp(start_xy) of the velocity (a drift growing with t).

        Raises
        ------
        TypeError, ValueError
            An argument of the wrong type, shape or range, naming it.

        Examples
        --------
        >>> ob = MovingObstacle.constant_velocity(0.2, start_xy=(1, 1), velocity_xy=(0, -1))
        >>> ob.position_at(0.5)
        array([1. , 0.5])
        """
        start = _coords(start_xy, "start_xy", (2,))
        vel = as_float_array(velocity_xy, "velocity_xy", shape=(2,))
        if float(np.max(np.abs(vel))) > 1e3:
            raise ValueError("velocity_xy must lie within ±1e3 m/s")
        if float(np.max(np.abs(start + vel))) > MAX_COORD:
            # Its second waypoint (t = 1 s), a path_xy the caller never gave.
            raise ValueError(
                f"start_xy + velocity_xy (the position at t = 1 s) must lie within "
                f"±{MAX_COORD:g} m, got {(start + vel).tolist()}"
            )
        # Built as "stop", then made to carry on: the constructor's check of a caller's
        # last leg would test the waypoints' difference, which may round beyond the
        # velocity checked above (start -24.3, velocity -1e3: a leg of
        # -1000.0000000000001 m/s, refused); the positions use the velocity itself.
        obstacle = cls(shape, np.stack((start, start + vel)), np.array([0.0, 1.0]), after="stop")
        object.__setattr__(obstacle, "after", "extend")
        object.__setattr__(obstacle, "_velocity", _read_only(np.array(vel, copy=True)))
        return obstacle

    @classmethod
    def scripted(
        cls,
        shape: float | Polygon | ArrayLike,
        path_xy: ArrayLike | None = None,
        *,
        times: ArrayLike | None = None,
        speed: float | None = None,
        after: Literal["stop", "loop", "extend"] = "stop",
        waypoints_xy: ArrayLike | None = None,
        loop: bool | None = None,
    ) -> MovingObstacle:
        """An obstacle visiting ``path_xy`` (K, 2) at ``times`` or at constant ``speed``.

        Give exactly one of ``times`` (s, strictly increasing) and ``speed``
        (m/s, > 0; the first waypoint is left at t = 0). ``after`` says what it
        does after the last waypoint, as for the class.

        Parameters
        ----------
        shape : float, shapely Polygon or array_like (V, 2)
            A radius (m) for a disc, or a polygon (or its vertices) given
            relative to the obstacle's reference point (its position).
        path_xy : array_like, shape (K, 2)
            Waypoints of the reference point, m. Required (its default None
            only lets the deprecated ``waypoints_xy`` stand in for it).
        times : array_like, shape (K,), optional
            Time of each waypoint, s, strictly increasing (keyword-only).
        speed : float, optional
            Constant speed along the legs, m/s, in (0, 1e3]; consecutive
            waypoints must differ, by enough for each to be reached at a later
            time than the one before (keyword-only).
        after : {"stop", "loop", "extend"}, default "stop"
            Stop at the last waypoint, start over from the first, or carry on
            with the last leg's velocity (keyword-only; see the class).

        Other Parameters
        ----------------
        waypoints_xy : array_like, shape (K, 2), optional
            Deprecated name of `path_xy`.
        loop : bool, optional
            Deprecated: ``loop=True`` is ``after="loop"``, ``loop=False``
            ``after="stop"``.

        Returns
        -------
        MovingObstacle
            The obstacle.

        Raises
        ------
        TypeError, ValueError
            Both or neither of ``times`` and ``speed``, a missing ``path_xy``,
            an old and a new name given together, or an argument of the wrong
            type, shape or range, naming it.

        Examples
        --------
        >>> ob = MovingObstacle.scripted(0.2, [(0, 0), (1, 0), (1, 1)], times=[0, 1, 3])
        >>> ob.position_at(2.0)
        array([1. , 0.5])
        """
        # The class's own vocabulary (path_xy, after); the old names warn, and errors
        # name the keyword the caller wrote.
        name = "path_xy" if waypoints_xy is None else "waypoints_xy"
        path_xy = renamed_keyword("waypoints_xy", waypoints_xy, "path_xy", path_xy, None)
        if path_xy is None:
            raise TypeError("MovingObstacle.scripted() missing the argument path_xy")
        if loop is not None:
            old_after: Literal["stop", "loop"] = "loop" if as_bool(loop, "loop") else "stop"
            after = renamed_keyword(
                "loop", old_after, "after", after, "stop", use=f"after={old_after!r}"
            )
        pts = _coords(path_xy, name, (None, 2))
        if (times is None) == (speed is None):
            raise ValueError("give exactly one of times and speed")
        if speed is not None:
            v = positive_float(speed, "speed")
            if v > 1e3:
                raise ValueError(f"speed must be at most 1e3 m/s, got {v}")
            legs = np.hypot(*np.diff(pts, axis=0).T)
            if np.any(legs == 0.0):
                raise ValueError(f"{name} must not repeat a point consecutively with speed")
            with np.errstate(over="ignore"):
                stamps = np.concatenate(([0.0], np.cumsum(legs) / v))
            if not stamps[-1] <= MAX_TIME:
                # The caller gave no times: name what made them too late.
                raise ValueError(
                    f"speed {v:g} m/s is too slow for {name}: the last waypoint "
                    f"would be reached after the ±{MAX_TIME:g} s time limit"
                )
            if np.any(np.diff(stamps) <= 0.0):
                # A leg shorter than the rounding of the time already spent (1e-11 m
                # after 1e6 m) gets no time of its own: name what the caller gave.
                k = int(np.argmax(np.diff(stamps) <= 0.0))
                raise ValueError(
                    f"{name}[{k + 1}] is too close to {name}[{k}] to be reached "
                    f"at a later time at speed {v:g} m/s (the leg is shorter than the "
                    "rounding of the time spent before it)"
                )
        else:
            assert times is not None
            stamps = as_float_array(times, "times", shape=(pts.shape[0],))
        return cls(shape, pts, stamps, after=after)

    def position_at(self, t: float) -> FloatArray:
        """Position ``(x, y)`` of the reference point at time ``t`` (s), shape (2,).

        Parameters
        ----------
        t : float
            Time, s, within ±1e9 s.

        Returns
        -------
        ndarray, shape (2,)
            New array ``(x, y)``, m, interpolated between the waypoints.

        Raises
        ------
        TypeError, ValueError
            ``t`` not a real number within ±1e9 s.

        Examples
        --------
        >>> ob = MovingObstacle(0.2, [(0, 0), (2, 0), (2, 2)], [1.0, 3.0, 5.0])
        >>> [ob.position_at(t).tolist() for t in (0.0, 2.0, 4.0, 9.0)]  # waits, moves, stops
        [[0.0, 0.0], [1.0, 0.0], [2.0, 1.0], [2.0, 2.0]]
        >>> looping = MovingObstacle(0.2, [(0, 0), (2, 0), (2, 2)], [1.0, 3.0, 5.0], after="loop")
        >>> looping.position_at(6.0)  # one 4 s round later: as at t = 2 s
        array([1., 0.])
        """
        time = _query_time(t)
        path, origin = self._kernel_path()
        first = np.zeros(1, dtype=np.int64)
        count = np.array([path.shape[0]], dtype=np.int64)
        after = np.array([_AFTER_CODES[self.after]], dtype=np.int64)
        out = np.empty((1, 3))
        # A disc of radius 0 centred on the origin: placed, its centre is the position,
        # rounded exactly as World's kernels round it.
        place_moving(
            time, np.array(path), self.times.copy(),  # writable: one signature
            first, count, after, _EMPTY4, np.empty(0, dtype=np.int64), np.empty((0, 4)),
            np.array([[origin[0], origin[1], 0.0]]), np.zeros(1, dtype=np.int64), out,
        )  # fmt: skip
        position: FloatArray = out[0, :2].copy()
        return position

    def _kernel_path(self) -> tuple[FloatArray, FloatArray]:
        """Waypoints for the moving-obstacle kernel, relative to an origin ``(2,)``.

        The kernel places the obstacle's shape, given relative to the origin, at
        its interpolated position. The waypoints themselves, with the origin 0,
        for any obstacle but a constant-velocity one: ``(0, velocity)`` from
        ``start_xy``, so that the kernel's difference of the two waypoints is the
        velocity exactly and a position is ``start + fl(velocity · t)``.
        """
        if self._velocity is None:
            return self.path_xy, np.zeros(2)
        return np.stack((np.zeros(2), self._velocity)), np.array(self.path_xy[0], copy=True)

    def geometry_at(self, t: float) -> BaseGeometry:
        """The obstacle at time ``t`` as a shapely geometry (a disc as a fine polygon).

        Parameters
        ----------
        t : float
            Time, s, within ±1e9 s.

        Returns
        -------
        shapely geometry
            The shape translated to :meth:`position_at` ``(t)``, world frame (m);
            a disc as a polygon of 256 vertices.

        Raises
        ------
        TypeError
            ``t`` not a real number (a bool, a string).
        ValueError
            ``t`` not finite, or beyond ±1e9 s.

        Examples
        --------
        >>> ob = MovingObstacle.constant_velocity(1.0, start_xy=(0, 0), velocity_xy=(1, 0))
        >>> round(ob.geometry_at(3.0).centroid.x, 9)
        3.0
        """
        x, y = self.position_at(t)
        if isinstance(self.shape, Polygon):
            return shapely.affinity.translate(self.shape, float(x), float(y))
        return shapely.Point(float(x), float(y)).buffer(float(self.shape), quad_segs=64)


def _solid_rings(world: Any) -> FloatArray:
    """The edges of a world's solid union (its ``_solids``), read-only, (n, 4)."""
    parts: list[FloatArray] = []
    if world._solids is not None:
        _segments_of(world._solids, parts, [])
    rings = np.concatenate(parts) if parts else np.empty((0, 4))
    rings = rings[(rings[:, 0] != rings[:, 2]) | (rings[:, 1] != rings[:, 3])]
    return _read_only(np.ascontiguousarray(rings))


def _solid_start(world: Any) -> IntArray:
    """The CSR starts of a world's solid edges and circles, read-only."""
    return _read_only(world._cell_lists(world._solid_rings, world._solid_circles)[0])


def _solid_items(world: Any) -> IntArray:
    """The CSR items of a world's solid edges and circles, read-only."""
    return _read_only(world._cell_lists(world._solid_rings, world._solid_circles)[1])


def _has_edges(world: Any) -> bool:
    """Whether a world's scans need the pass over segments and circles."""
    return bool(
        world._cell_items.shape[0] > 0 or world._dyn_base_segs.shape[0] > 0
        or world._dyn_base_circles.shape[0] > 0
    )  # fmt: skip


def _edges_only(world: Any) -> bool:
    """Whether a world's only obstacles are static segments and circles (or none).

    The simulation and the clearance queries then use kernels compiled without
    the grid's and the moving obstacles' code.
    """
    return bool(world._occ.shape[0] == 0 and not world._moving)


def _segments_of(geom: BaseGeometry, segs: list[FloatArray], solids: list[BaseGeometry]) -> None:
    """Append the edges of ``geom`` to ``segs`` and its polygons to ``solids``."""
    if geom.is_empty:
        return
    kind = geom.geom_type
    if kind in ("MultiPolygon", "MultiLineString", "GeometryCollection"):
        for part in shapely.get_parts(geom):
            _segments_of(part, segs, solids)
        return
    if kind == "Polygon":
        rings = [geom.exterior, *geom.interiors]
        solids.append(geom)
    elif kind in ("LineString", "LinearRing"):
        rings = [geom]
    else:
        raise ValueError(
            f"obstacles must be polygons, lines or Circles; a {kind} has no extent "
            "(use Circle for a round obstacle)"
        )
    for ring in rings:
        # shapely.get_coordinates (x, y as float64) and one filled array, rather than
        # ring.coords and np.hstack: the same edges in the same order, a world of
        # 50,000 lines built in 0.49 s instead of 0.79 (CPU, medians).
        pts = shapely.get_coordinates(ring)
        if pts.shape[0] >= 2:
            edges = np.empty((pts.shape[0] - 1, 4))
            edges[:, :2] = pts[:-1]
            edges[:, 2:] = pts[1:]
            segs.append(edges)


class World:
    """Obstacles for the simulator: shapely geometry, circles, a map and moving obstacles.

    Static obstacles are polygons (solid: a robot may not stand inside them;
    holes are free space), lines (walls: ``LineString``, ``LinearRing``, e.g.
    ``box(0, 0, 10, 8).exterior`` for a room), :class:`Circle` s (exact) and
    the cells of an :class:`~navkit.mapping.OccupancyGrid` that are not free
    (``p >= free_thresh``: occupied and, by default, unknown cells, as navkit's
    planners treat unknown space; outside the map is free). Their edges
    and circles are indexed once, in a uniform grid of about two cells per
    primitive, so rays and clearance queries only visit what is near them.
    Moving obstacles (:class:`MovingObstacle`) are placed at the time of each
    query: a query sees them at that instant only. A :class:`Simulation`
    likewise checks them only at the end of each physics step (long steps
    are swept against the static obstacles alone), so an obstacle crossing
    the robot's way within one step goes unnoticed. All inputs are copied;
    the world never changes them.

    An ordinary class with ``__slots__`` rather than a frozen dataclass: it
    builds and keeps its index and the moving obstacles' work arrays.

    Parameters
    ----------
    obstacles : shapely geometry, Circle, or iterable of them, optional
        Static obstacles, coordinates in metres within ±1e6 m; at most 10^7
        edges in all.
    grid : OccupancyGrid, optional
        A map whose occupied cells are obstacles (any map_server map through
        ``OccupancyGrid.load``); copied.
    unknown_blocks : bool, default True
        Unknown cells of ``grid`` block beams and robots too. Many saved maps
        draw walls in grey levels between ``free_thresh`` and
        ``occupied_thresh`` (the Willow Garage map's are), so their walls are
        "unknown"; with False only cells with ``p > occupied_thresh`` block.
        Choose it with the planner's ``unknown_cost`` on that map
        (:class:`~navkit.planning.MapPlanner`,
        :func:`~navkit.mapping.traversal_costs`): ``True`` with ``inf`` (the
        defaults of both), ``False`` with a finite cost. A route planned
        across unknown cells at a finite cost runs into them in a World where
        they block.
    moving : iterable of MovingObstacle, optional
        Obstacles that move (solid).

    Raises
    ------
    TypeError
        ``obstacles`` that are not shapely geometries or :class:`Circle`
        objects; a ``grid`` that is not an :class:`~navkit.mapping.OccupancyGrid`.
    ValueError
        Geometry with NaN or inf coordinates, or other values out of range.

    Notes
    -----
    A world is never changed by its queries, so one world may be shared by
    any number of threads: :meth:`raycast`, :meth:`clearance`,
    :meth:`collides`, :meth:`Lidar.scan <navkit.sim.Lidar.scan>` and
    :class:`Simulation` runs may use it at once, at different times ``t``,
    and give what they give one at a time (each query places the moving
    obstacles in arrays of its own).

    Examples
    --------
    >>> import math
    >>> from shapely.geometry import box
    >>> world = World([box(0, 0, 10, 8).exterior, Circle((7.0, 4.0), 0.5)])
    >>> world.raycast((2.0, 4.0, 0.0), [0.0, math.pi / 2, math.pi], range_max=20.0).tolist()
    [4.5, 4.0, 2.0]
    >>> world.clearance(0.3, (2.0, 4.0, 0.0))
    1.7
    >>> world.collides(0.3, (6.5, 4.0, 0.0))
    True
    """

    __slots__ = (
        "__weakref__",  # weakref.ref(obj) for callbacks and caches (review 36)
        "_cell_items",
        "_cell_start",
        "_cheb",
        "_circles",
        "_dyn_base_circles",
        "_dyn_base_segs",
        "_dyn_circle_owner",
        "_dyn_seg_owner",
        "_edges_only",
        "_grid",
        "_has_edges",
        "_index",
        "_moving",
        "_mv_after",
        "_mv_count",
        "_mv_first",
        "_mv_path",
        "_mv_times",
        "_occ",
        "_occ_frame",
        "_placed",
        "_scanners",
        "_segs",
        "_solid_circles",
        "_solid_items",
        "_solid_rings",
        "_solid_start",
        "_solids",
    )

    # Slots added since a release, for pickles made before (see
    # navkit._shared.frozen.fill_added_fields), each made from the others as
    # __init__ makes it. Not annotated: it would read as a slot's type.
    _added_fields = MappingProxyType(
        {
            "_solid_rings": _solid_rings,
            "_solid_start": _solid_start,
            "_solid_items": _solid_items,
            "_has_edges": _has_edges,
            "_edges_only": _edges_only,
        }
    )

    def __init__(
        self,
        obstacles: BaseGeometry | Circle | Iterable[BaseGeometry | Circle] = (),
        *,
        grid: OccupancyGrid | None = None,
        unknown_blocks: bool = True,
        moving: Iterable[MovingObstacle] = (),
    ) -> None:
        items: list[Any]
        unknown_blocks = as_bool(unknown_blocks, "unknown_blocks")
        if isinstance(obstacles, (BaseGeometry, Circle)):
            items = [obstacles]
        elif isinstance(obstacles, (str, bytes, Mapping)) or not isinstance(obstacles, Iterable):
            raise TypeError(
                "obstacles must be a shapely geometry, a Circle or an iterable of them, "
                f"got {type(obstacles).__name__}"
            )
        else:
            items = list(obstacles)
        seg_parts: list[FloatArray] = []
        solids: list[BaseGeometry] = []
        circles: list[tuple[float, float, float]] = []
        solid_circles: list[tuple[float, float, float]] = []
        for k, item in enumerate(items):
            if isinstance(item, Circle):
                row = (float(item.center_xy[0]), float(item.center_xy[1]), item.radius)
                circles.append(row)
                if item.solid:
                    solid_circles.append(row)
            elif isinstance(item, BaseGeometry):
                _segments_of(item, seg_parts, solids)
            else:
                raise TypeError(
                    f"obstacles[{k}] must be a shapely geometry or a Circle, "
                    f"got {type(item).__name__}"
                )
        segs = np.concatenate(seg_parts) if seg_parts else np.empty((0, 4))
        if segs.shape[0] > MAX_SEGMENTS:
            raise ValueError(
                f"obstacles hold {segs.shape[0]} edges; the maximum is {MAX_SEGMENTS}"
            )
        if segs.size and not np.all(np.isfinite(segs)):
            raise ValueError("obstacles must have finite coordinates")
        if segs.size and float(np.max(np.abs(segs))) > MAX_COORD:
            raise ValueError(f"obstacles must lie within ±{MAX_COORD:g} m{_LOCAL_FRAME_HINT}")
        # Zero-length edges (repeated vertices) carry nothing.
        keep = (segs[:, 0] != segs[:, 2]) | (segs[:, 1] != segs[:, 3])
        self._segs: FloatArray = _read_only(np.ascontiguousarray(segs[keep]))
        self._circles: FloatArray = _read_only(
            np.array(circles, dtype=np.float64).reshape(-1, 3)
        )
        self._solid_circles: FloatArray = _read_only(
            np.array(solid_circles, dtype=np.float64).reshape(-1, 3)
        )
        self._solids: BaseGeometry | None = None
        if solids:
            union = shapely.union_all(solids)
            shapely.prepare(union)
            self._solids = union
        self._index = self._build_index()
        start, cell_items = self._cell_lists(self._segs, self._circles)
        self._cell_start: IntArray = _read_only(start)
        self._cell_items: IntArray = _read_only(cell_items)
        # The edges of the union of the solid polygons, and their cell lists (with the
        # solid circles') in the same grid: a LiDAR tells by them whether it is inside
        # a solid (the union, so that overlapping solids count once).
        self._solid_rings: FloatArray = _solid_rings(self)
        start, cell_items = self._cell_lists(self._solid_rings, self._solid_circles)
        self._solid_start: IntArray = _read_only(start)
        self._solid_items: IntArray = _read_only(cell_items)
        # Occupancy grid.
        self._grid: OccupancyGrid | None = None
        self._occ = _read_only(np.zeros((0, 0), dtype=np.uint8))
        self._cheb = _read_only(np.zeros((0, 0), dtype=np.uint8))
        self._occ_frame = (0.0, 0.0, 1.0, 0.0, 1.0)
        if grid is not None:
            if not isinstance(grid, OccupancyGrid):
                raise TypeError(f"grid must be an OccupancyGrid, got {type(grid).__name__}")
            self._grid = grid.copy()
            blocked = (
                ~self._grid.free() if as_bool(unknown_blocks, "unknown_blocks")
                else self._grid.occupied()
            )
            occ = np.ascontiguousarray(blocked, dtype=np.uint8)
            self._occ = _read_only(occ)
            # Capped at 255 cells: a uint8 map keeps the walk's loads in cache.
            cheb = np.minimum(chebyshev_distance(occ), 255).astype(np.uint8)
            self._cheb = _read_only(cheb)
            o = self._grid.origin
            if max(abs(o.x), abs(o.y)) > MAX_COORD:
                raise ValueError(
                    f"grid origin must lie within ±{MAX_COORD:g} m{_LOCAL_FRAME_HINT}"
                )
            self._occ_frame = (
                o.x, o.y, math.cos(o.theta), math.sin(o.theta), self._grid.resolution
            )
        self._init_moving(moving)
        self._has_edges = _has_edges(self)
        self._edges_only = _edges_only(self)
        self._scanners: dict[Any, Any] = {}

    # ------------------------------------------------------- copy and pickle
    #: The arrays built once and handed to the kernels read-only.
    _READ_ONLY = (
        "_segs", "_circles", "_solid_circles", "_cell_start", "_cell_items", "_solid_rings",
        "_solid_start", "_solid_items", "_occ", "_cheb",
    )  # fmt: skip

    def __getstate__(self) -> tuple[dict[str, Any] | None, dict[str, Any]]:
        """The world's state for pickle and :mod:`copy`, without its LiDAR cache."""
        # The default state's layout, (a subclass's __dict__ or None, every slot of
        # every class), so that subclasses copy whole.
        names = slot_names(type(self))
        slots = {name: getattr(self, name) for name in names if hasattr(self, name)}
        # Scanners are bound to this world: rebuilt on use; so is the last placement.
        slots["_scanners"] = {}
        slots.pop("_placed", None)
        return getattr(self, "__dict__", None) or None, slots

    def __setstate__(
        self, state: dict[str, Any] | tuple[dict[str, Any] | None, dict[str, Any]]
    ) -> None:
        """Restore from a pickle or a (deep) copy: arrays read-only, work arrays its own."""
        instance, slots = state if isinstance(state, tuple) else (None, state)
        # Worlds pickled before placements were published whole kept their work
        # arrays in three slots that no longer exist; the placement is rebuilt below.
        slots = {k: v for k, v in slots.items() if k not in _OLD_PLACEMENT_SLOTS}
        restore_slots(self, (instance, slots), read_only=self._READ_ONLY)
        self._placed: tuple[float, FloatArray, FloatArray] = (
            math.nan, self._dyn_base_segs, self._dyn_base_circles
        )
        self._scanners = {}
        if self._solids is not None:
            shapely.prepare(self._solids)
        self._place(0.0)

    # ------------------------------------------------------------ construction
    def _cell_lists(self, segs: FloatArray, circles: FloatArray) -> tuple[IntArray, IntArray]:
        """CSR cell lists of ``segs`` and ``circles`` in the world's uniform grid."""
        start, cell_items = (
            build_cell_lists(segs, circles, *self._index, MAX_INDEX_ENTRIES)
            if segs.shape[0] + circles.shape[0]
            else (np.zeros(2, dtype=np.int64), np.empty(0, dtype=np.int64))
        )
        if int(start[-1]) > cell_items.shape[0]:
            raise ValueError(
                f"the obstacles' edge index would need {int(start[-1])} entries; the maximum "
                f"is {MAX_INDEX_ENTRIES} (too many long edges)"
            )
        return start, cell_items

    def _build_index(self) -> tuple[float, float, float, int, int]:
        """``(x0, y0, cell, nx, ny)`` of the uniform grid over edges and circles."""
        n = self._segs.shape[0] + self._circles.shape[0]
        if n == 0:
            return 0.0, 0.0, 1.0, 1, 1
        xs = [self._segs[:, 0], self._segs[:, 2], self._circles[:, 0] - self._circles[:, 2],
              self._circles[:, 0] + self._circles[:, 2]]  # fmt: skip
        ys = [self._segs[:, 1], self._segs[:, 3], self._circles[:, 1] - self._circles[:, 2],
              self._circles[:, 1] + self._circles[:, 2]]  # fmt: skip
        xmin = min(float(a.min()) for a in xs if a.size)
        xmax = max(float(a.max()) for a in xs if a.size)
        ymin = min(float(a.min()) for a in ys if a.size)
        ymax = max(float(a.max()) for a in ys if a.size)
        pad = 1e-6 * max(xmax - xmin, ymax - ymin, 1.0)
        xmin -= pad
        ymin -= pad
        width = xmax - xmin + pad
        height = ymax - ymin + pad
        side = max(width, height)
        cell = math.sqrt(width * height / (_CELLS_PER_PRIMITIVE * n))
        # A primitive is filed in about (|dx| + |dy|) / cell cells (a circle 8 r / cell):
        # cells sized by the area alone made long edges stacked in a small area (one
        # box given 10,000 times) fill O(n^1.5) entries (0.9 s; 50,000 copies took 39 s
        # to be refused). The queries' results do not depend on the cell size.
        segs = self._segs
        extent = float(np.abs(segs[:, 2:] - segs[:, :2]).sum())
        extent += 8.0 * float(self._circles[:, 2].sum())
        cell = max(cell, extent / (_ENTRIES_PER_PRIMITIVE * n), side / _MAX_CELLS_PER_AXIS)
        nx = max(1, math.ceil(width / cell))
        ny = max(1, math.ceil(height / cell))
        return xmin, ymin, cell, nx, ny

    def _init_moving(self, moving: Iterable[MovingObstacle]) -> None:
        if isinstance(moving, MovingObstacle):
            moving = [moving]
        if isinstance(moving, (str, bytes, Mapping)) or not isinstance(moving, Iterable):
            raise TypeError(
                f"moving must be an iterable of MovingObstacle, got {type(moving).__name__}"
            )
        obs = tuple(moving)
        for k, ob in enumerate(obs):
            if not isinstance(ob, MovingObstacle):
                raise TypeError(f"moving[{k}] must be a MovingObstacle, got {type(ob).__name__}")
        self._moving = obs
        paths, times, first, count, after = [], [], [], [], []
        segs: list[FloatArray] = []
        seg_owner: list[IntArray] = []
        circles: list[tuple[float, float, float]] = []
        circle_owner: list[int] = []
        offset = 0
        for m, ob in enumerate(obs):
            # The shapes go in relative to the path's origin (not always the reference
            # point: a constant-velocity obstacle's path starts at 0, its shape at start).
            path, (ox, oy) = ob._kernel_path()
            paths.append(path)
            times.append(ob.times)
            first.append(offset)
            count.append(path.shape[0])
            after.append(_AFTER_CODES[ob.after])
            offset += path.shape[0]
            if isinstance(ob.shape, Polygon):
                # x, y only: a polygon with z coordinates has three columns.
                pts = np.asarray(ob.shape.exterior.coords, dtype=np.float64)[:, :2]
                segs.append(np.hstack((pts[:-1], pts[1:])) + np.array([ox, oy, ox, oy]))
                seg_owner.append(np.full(pts.shape[0] - 1, m, dtype=np.int64))
            else:
                circles.append((float(ox), float(oy), float(ob.shape)))
                circle_owner.append(m)
        self._mv_path = np.ascontiguousarray(np.concatenate(paths)) if obs else np.empty((0, 2))
        self._mv_times = np.concatenate(times) if obs else np.empty(0)
        self._mv_first = np.array(first, dtype=np.int64)
        self._mv_count = np.array(count, dtype=np.int64)
        self._mv_after = np.array(after, dtype=np.int64)
        self._dyn_base_segs = np.concatenate(segs) if segs else np.empty((0, 4))
        self._dyn_seg_owner = (
            np.concatenate(seg_owner) if seg_owner else np.empty(0, dtype=np.int64)
        )
        self._dyn_base_circles = np.array(circles, dtype=np.float64).reshape(-1, 3)
        self._dyn_circle_owner = np.array(circle_owner, dtype=np.int64)
        # (time, segments, circles) of the last placement: replaced whole, never
        # written after (see _place).
        self._placed = (math.nan, self._dyn_base_segs, self._dyn_base_circles)
        self._place(0.0)

    def _query_time(self, t: Any) -> float:
        """A query time ``t``: finite, and within ±MAX_TIME s when obstacles move.

        Only moving obstacles need the bound (their positions must stay finite);
        a world without them ignores the time, as its LiDAR scans always did.
        """
        if self._moving:
            return _query_time(t)
        return finite_float(t, "t")

    def _place(self, t: float) -> tuple[FloatArray, FloatArray]:
        """The moving obstacles' segments and circles at time ``t`` (ValueError beyond ±1e9 s).

        Threads may query one world at different times at once: each placement
        goes into new arrays, published with its time as one tuple (a single
        attribute store) and never written after, and a query reads the arrays
        returned here, never the world's attribute again.
        """
        placed = self._placed
        if placed[0] == t or not self._moving:
            return placed[1], placed[2]
        if abs(t) > MAX_TIME:
            # Reached from the LiDAR, which checks only that t is finite.
            raise _time_error("t", abs(t), repr(t))
        segs = np.empty_like(self._dyn_base_segs)
        circles = np.empty_like(self._dyn_base_circles)
        place_moving(
            t, self._mv_path, self._mv_times, self._mv_first, self._mv_count, self._mv_after,
            self._dyn_base_segs, self._dyn_seg_owner, segs,
            self._dyn_base_circles, self._dyn_circle_owner, circles,
        )  # fmt: skip
        self._placed = (t, segs, circles)
        return segs, circles

    # -------------------------------------------------------------- properties
    @property
    def grid(self) -> OccupancyGrid | None:
        """The world's occupancy grid (a copy of the one given), or None."""
        return self._grid

    @property
    def moving(self) -> tuple[MovingObstacle, ...]:
        """The moving obstacles."""
        return self._moving

    @property
    def segments(self) -> FloatArray:
        """Static edges, rows ``[x0, y0, x1, y1]`` (m), shape (S, 4), read-only."""
        return self._segs

    @property
    def circles(self) -> FloatArray:
        """Static circles, rows ``[cx, cy, r]`` (m), shape (C, 3), read-only."""
        return self._circles

    @property
    def solid_circles(self) -> FloatArray:
        """The solid ones among :attr:`circles` (``Circle(..., solid=True)``), shape (K, 3).

        Rows ``[cx, cy, r]`` (m), read-only; a non-solid circle is only its rim.
        """
        return self._solid_circles

    @property
    def solids(self) -> BaseGeometry | None:
        """Union of the solid polygons (their inside is an obstacle), or None.

        Lines and polygon rings given as walls are not in it, nor are a grid's
        blocked cells (the world keeps them as a cell mask, not as
        :attr:`segments`).
        """
        return self._solids

    @property
    def bounds(self) -> tuple[float, float, float, float] | None:
        """``(xmin, ymin, xmax, ymax)`` of the static obstacles and the map, or None.

        Examples
        --------
        >>> from shapely.geometry import box
        >>> World(box(0, 0, 4, 3).exterior).bounds
        (0.0, 0.0, 4.0, 3.0)
        """
        boxes: list[tuple[float, float, float, float]] = []
        if self._segs.shape[0]:
            s = self._segs
            boxes.append((
                float(min(s[:, 0].min(), s[:, 2].min())), float(min(s[:, 1].min(), s[:, 3].min())),
                float(max(s[:, 0].max(), s[:, 2].max())), float(max(s[:, 1].max(), s[:, 3].max())),
            ))  # fmt: skip
        if self._circles.shape[0]:
            c = self._circles
            boxes.append((
                float((c[:, 0] - c[:, 2]).min()), float((c[:, 1] - c[:, 2]).min()),
                float((c[:, 0] + c[:, 2]).max()), float((c[:, 1] + c[:, 2]).max()),
            ))  # fmt: skip
        if self._grid is not None:
            g = self._grid
            corners = g.origin.transform_points(
                [[0.0, 0.0], [g.width, 0.0], [0.0, g.height], [g.width, g.height]]
            )
            lo = corners.min(axis=0)
            hi = corners.max(axis=0)
            boxes.append((float(lo[0]), float(lo[1]), float(hi[0]), float(hi[1])))
        if not boxes:
            return None
        arr = np.array(boxes)
        return (
            float(arr[:, 0].min()), float(arr[:, 1].min()),
            float(arr[:, 2].max()), float(arr[:, 3].max()),
        )  # fmt: skip

    def __repr__(self) -> str:
        # The call's form, what it was given summarised as <...> (as AStarPlanner's
        # costs): "edges=4" read as keywords the constructor does not take.
        grid = "None"
        if self._grid is not None:
            rows, cols = self._grid.shape
            grid = f"<{rows}x{cols} cells>"
        edges = counted(self._segs.shape[0], "edge")
        circles = counted(self._circles.shape[0], "circle")
        moving = counted(len(self._moving), "obstacle")
        return f"{type(self).__name__}(<{edges}, {circles}>, grid={grid}, moving=<{moving}>)"

    # ----------------------------------------------------------------- queries
    def _cast(
        self, out: FloatArray, x: float, y: float, heading: float, angles: FloatArray,
        range_max: float, t: float,
    ) -> None:  # fmt: skip
        """Exact ranges into ``out`` (validated inputs; the LiDAR's fast path).

        A pass over the segments and circles (static and moving), then one
        over the occupancy grid: a world without a grid never compiles the grid
        walk, nor one with only a grid the other.
        """
        dyn_segs, dyn_circles = self._place(t)
        has_occ = self._occ.shape[0] > 0
        # Beam directions, written by the first pass when the grid's pass follows.
        dirs = np.empty((angles.shape[0], 2)) if has_occ and self._has_edges else _NO_DIRS
        if self._has_edges or not has_occ:
            gx0, gy0, h, nx, ny = self._index
            cast_edge_rays(
                out, dirs, x, y, heading, angles, range_max, not has_occ,
                self._segs, self._circles, gx0, gy0, h, nx, ny, self._cell_start,
                self._cell_items, self._solid_rings, self._solid_circles, self._solid_start,
                self._solid_items, dyn_segs, self._dyn_seg_owner, dyn_circles,
            )  # fmt: skip
        if has_occ:
            gox, goy, gcos, gsin, res = self._occ_frame
            cast_occupancy_rays(
                out, dirs, x, y, heading, angles, range_max, not self._has_edges,
                self._cheb, gox, goy, gcos, gsin, res,
            )  # fmt: skip

    def _clearance(
        self,
        x: float,
        y: float,
        theta: float,
        radius: float,
        verts: FloatArray | None,
        work: FloatArray | None,
        scratch: FloatArray | None,
        t: float,
        limit: float,
    ) -> float:
        """Footprint clearance for validated inputs (None arrays for a disc footprint)."""
        gx0, gy0, h, nx, ny = self._index
        if self._edges_only:
            # No grid, no moving obstacles: the kernel that compiles without their code.
            distance: float = edge_clearance(
                x, y, theta, radius, verts, work, self._segs, self._circles,
                gx0, gy0, h, nx, ny, self._cell_start, self._cell_items, limit,
            )  # fmt: skip
            return distance
        dyn_segs, dyn_circles = self._place(t)
        gox, goy, gcos, gsin, res = self._occ_frame
        distance = footprint_clearance(
            x, y, theta, radius, verts, work, scratch,
            self._segs, self._circles, gx0, gy0, h, nx, ny, self._cell_start,
            self._cell_items, self._occ, gox, goy, gcos, gsin, res,
            dyn_segs, dyn_circles, limit,
        )  # fmt: skip
        return distance

    def raycast(
        self,
        pose: Pose2D | ArrayLike,
        angles: ArrayLike,
        *,
        range_max: float,
        t: float = 0.0,
    ) -> FloatArray:
        """Exact distance to the first obstacle along each ray (no noise, no minimum range).

        Parameters
        ----------
        pose : Pose2D or array_like [x, y, theta]
            Origin and heading of the rays (world frame).
        angles : array_like, shape (N,)
            Ray angles relative to the heading, rad.
        range_max : float
            Longest distance looked at, m, in (0, 1e6].
        t : float, default 0.0
            Time at which the moving obstacles are placed, s: finite, and within
            ±1e9 s when the world has moving obstacles (otherwise unused).

        Returns
        -------
        ndarray, shape (N,)
            Distances in metres; ``inf`` where nothing lies closer than
            ``range_max``; 0 on every ray when the origin is on an edge or a
            circle, or on or inside an obstacle: a blocked cell of the grid, a
            solid polygon, a solid :class:`Circle` or a moving obstacle (from
            inside, the obstacle's own boundary is not seen).

        Raises
        ------
        TypeError
            ``pose``, ``angles``, ``range_max`` or ``t`` not numeric.
        ValueError
            ``pose`` not three finite values, ``angles`` not 1-D or not finite,
            ``range_max`` not in (0, 1e6], ``t`` not finite (or, with moving
            obstacles, beyond ±1e9 s).

        Examples
        --------
        >>> from shapely.geometry import box
        >>> World(box(-1, -1, 1, 1).exterior).raycast([0, 0, 0], [0.0, 3.0], range_max=0.5)
        array([inf, inf])
        """
        p = as_query_pose(pose)
        ang = kernel_input(as_float_array(angles, "angles", ndim=1))
        rmax = positive_float(range_max, "range_max")
        if rmax > MAX_COORD:
            raise ValueError(f"range_max must be at most {MAX_COORD:g} m, got {rmax}")
        out = np.empty(ang.shape[0])
        self._cast(out, p.x, p.y, p.theta, ang, rmax, self._query_time(t))
        return out

    def clearance(
        self,
        footprint: float | Polygon | ArrayLike,
        pose: Pose2D | ArrayLike,
        *,
        t: float = 0.0,
    ) -> float:
        """Distance from a footprint at ``pose`` to the nearest obstacle boundary, m.

        0 when the footprint touches or overlaps an obstacle's boundary (an edge,
        a circle, an occupied cell, a moving obstacle). A footprint wholly inside
        a solid obstacle has a positive clearance to its boundary: use
        :meth:`collides` to test a placement.

        Parameters
        ----------
        footprint : float, shapely Polygon or array_like (V, 2)
            A radius (m) for a round robot or a polygon in the robot frame.
        pose : Pose2D or array_like [x, y, theta]
            Where the robot is.
        t : float, default 0.0
            Time at which the moving obstacles are placed, s: finite, and within
            ±1e9 s when the world has moving obstacles (otherwise unused).

        Returns
        -------
        float
            Distance, m, >= 0 (``inf`` in a world with nothing in it).

        Raises
        ------
        TypeError
            ``footprint`` neither a number nor a polygon, ``pose`` or ``t`` not
            numeric.
        ValueError
            A radius not positive and finite, a polygon of fewer than 3
            vertices or not of shape (V, 2), ``pose`` not three finite values,
            ``t`` not finite (or, with moving obstacles, beyond ±1e9 s).

        Examples
        --------
        >>> from shapely.geometry import box
        >>> World(box(0, 0, 4, 3).exterior).clearance([[-0.2, -0.1], [0.2, -0.1], [0.2, 0.1],
        ...                                           [-0.2, 0.1]], (1.0, 1.0, 0.0))
        0.8
        """
        radius, verts = as_footprint(footprint)
        p = as_query_pose(pose)
        body, work, scratch = _footprint_arrays(verts)
        return self._clearance(
            p.x, p.y, p.theta, radius, body, work, scratch, self._query_time(t), math.inf
        )

    def collides(
        self,
        footprint: float | Polygon | ArrayLike,
        pose: Pose2D | ArrayLike,
        *,
        t: float = 0.0,
    ) -> bool:
        """Whether a footprint at ``pose`` touches an obstacle or lies inside a solid one.

        Parameters
        ----------
        footprint : float, shapely Polygon or array_like (V, 2)
            A radius (m) for a round robot or a polygon in the robot frame.
        pose : Pose2D or array_like [x, y, theta]
            Where the robot is.
        t : float, default 0.0
            Time at which the moving obstacles are placed, s: finite, and within
            ±1e9 s when the world has moving obstacles (otherwise unused;
            keyword-only).

        Returns
        -------
        bool
            True when the footprint touches an obstacle's boundary (comes
            within 1e-12 m of it, the distance computation's rounding) or lies
            inside a solid obstacle.

        Raises
        ------
        TypeError
            ``footprint`` neither a number nor a polygon, ``pose`` or ``t`` not
            numeric.
        ValueError
            A radius not positive and finite, a polygon of fewer than 3
            vertices or not of shape (V, 2), ``pose`` not three finite values,
            ``t`` not finite (or, with moving obstacles, beyond ±1e9 s).

        Examples
        --------
        >>> from shapely.geometry import box
        >>> world = World([box(2, 2, 3, 3)])
        >>> world.collides(0.1, (2.5, 2.5, 0.0)), world.collides(0.1, (1.0, 1.0, 0.0))
        (True, False)
        """
        radius, verts = as_footprint(footprint)
        p = as_query_pose(pose)
        time = self._query_time(t)
        body, work, scratch = _footprint_arrays(verts)
        # A small positive limit: the search stops at once unless something touches.
        if self._clearance(p.x, p.y, p.theta, radius, body, work, scratch, time, 1e-9) <= TOUCH:
            return True
        return self._point_in_solid(p, verts, time)

    def _point_in_solid(self, pose: Pose2D, verts: FloatArray, t: float) -> bool:
        """Whether one point of a footprint that touches no boundary is inside a solid.

        Such a footprint is wholly inside or wholly outside every obstacle, so
        one of its points decides.
        """
        x, y = (pose.x, pose.y) if verts.shape[0] == 0 else pose.transform_points(verts[0])[0]
        if self._solids is not None:
            # GEOS's prepared geometries are not thread-safe (libgeos/geos#825) and
            # shapely releases the GIL here: two threads at once corrupt the heap.
            with _GEOS_LOCK:
                inside = bool(shapely.contains_xy(self._solids, x, y))
            if inside:
                return True
        circles = self._solid_circles
        if circles.shape[0] > _FEW_CIRCLES:
            # The exact test below for the circles whose bounding square (widened by a
            # relative 1e-9 for hypot's rounding) holds the point, picked at C speed: a
            # Python loop over every solid circle cost 0.5 µs each (4 ms at 8000).
            reach = circles[:, 2] * (1.0 + 1e-9)
            near = (np.abs(x - circles[:, 0]) <= reach) & (np.abs(y - circles[:, 1]) <= reach)
            circles = circles[near]
        for cx, cy, r in circles:
            if math.hypot(x - cx, y - cy) < r:
                return True
        if self._occ.shape[0]:
            cell = self._grid.world_to_cell([x, y]) if self._grid is not None else None
            if cell is not None:
                row, col = int(cell[0]), int(cell[1])
                rows, cols = self._occ.shape
                if 0 <= row < rows and 0 <= col < cols and self._occ[row, col]:
                    return True
        for cx, cy, r in self._place(t)[1]:
            if math.hypot(x - cx, y - cy) < r:
                return True
        for ob in self._moving:
            if isinstance(ob.shape, Polygon):
                cx, cy = ob.position_at(t)
                # contains_xy prepares the shared shape on first use: as above.
                with _GEOS_LOCK:
                    inside = bool(shapely.contains_xy(ob.shape, x - cx, y - cy))
                if inside:
                    return True
        return False


#: Serializes the queries of shared shapely geometries (see World._point_in_solid).
#: Re-entrant: a signal handler querying a world runs in the main thread between two
#: bytecodes, also while that thread holds the lock (right after shapely returns, a
#: signal that arrived during the test being handled then), and with a plain lock it
#: waited for ever (review 35). Its query runs after the interrupted one's GEOS call
#: has returned, never beside it.
_GEOS_LOCK = ForkSafeLock(reentrant=True)

#: Slots of the worlds pickled before :meth:`World._place` published its placements whole.
_OLD_PLACEMENT_SLOTS = frozenset({"_dyn_segs", "_dyn_circles", "_moving_t"})


def as_world(value: Any, name: str = "world") -> World:
    """``value`` if it is a :class:`World`, else a TypeError naming ``name``."""
    if not isinstance(value, World):
        raise TypeError(f"{name} must be a World, got {type(value).__name__}")
    return value
