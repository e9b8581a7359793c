"""Conversion from and to ROS messages (``nav_msgs/OccupancyGrid``, ``sensor_msgs/LaserScan``).

ROS is never imported: a real message or any look-alike with the same field
names works, and the fields of an outgoing message are returned as plain values.
"""

from __future__ import annotations

import functools
import math
import numbers
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from navkit._shared.counts import counted
from navkit._shared.deprecation import renamed_keyword
from navkit._shared.frozen import frozen_setattr, reduce_record, restore_read_only
from navkit._shared.validation import as_bool, bounded_int, finite_float, refuse_masked, unpack
from navkit.geometry import Pose2D, quaternion_to_matrix, quaternion_to_yaw
from navkit.mapping import LaserScan, MapMode, OccupancyGrid
from navkit.mapping.io._map_files import _unknown_logodds
from navkit.mapping.io._step_tables import (
    LOOK_UP_BLOCK,
    StepLookUp,
    StepTable,
    row_probability,
    step_table,
)

__all__ = ["OccupancyGridMsgFields", "grid_from_msg", "grid_to_msg_fields", "scan_from_msg"]

#: Largest tilt (rad) of a map origin's z axis from the world's: a planar grid turns
#: about z only. Float32 rounding of a message's quaternion tilts it by ~1e-7 rad;
#: projecting a plane tilted 1e-3 rad shortens its lengths by 5e-7 (0.05 mm in 100 m).
#: Beyond it, reading the yaw alone gives a map stretched, or mirrored if upside down.
_MAX_TILT = 1e-3


def _positive_int(value: Any, name: str) -> int:
    out = bounded_int(value, name)
    if out <= 0:
        raise ValueError(f"{name} must be a positive integer, got {out!r}")
    return out


def _resolution(value: Any, name: str) -> float:
    """A cell size in the range every OccupancyGrid accepts ([1e-6, 1e6] m)."""
    out = finite_float(value, name)
    try:
        OccupancyGrid(np.zeros((1, 1)), resolution=out)
    except ValueError as exc:
        raise ValueError(str(exc).replace("resolution", name, 1)) from None
    return out


def _tuple_of_floats(value: Any, n: int, name: str) -> tuple[float, ...]:
    if isinstance(value, (str, bytes)):
        raise TypeError(f"{name} must be a sequence of {n} numbers, got {type(value).__name__}")
    try:
        items = unpack(value, name)
    except TypeError:
        raise TypeError(
            f"{name} must be a sequence of {n} numbers, got {type(value).__name__}"
        ) from None
    if len(items) != n:
        raise ValueError(f"{name} must hold {n} numbers, got {len(items)}")
    return tuple(finite_float(v, f"{name}[{i}]") for i, v in enumerate(items))


def _byte_cells(view: memoryview, name: str) -> NDArray[Any]:
    """The values of ``view``; those of single bytes are the message's int8 cells.

    A memoryview of ``bytes``, of a ``bytearray`` or of ``array.array('B')``
    has format ``'B'``, which NumPy reads as uint8 (``0xFF`` as 255), and one
    cast to ``'c'`` reads as one-byte strings: a forwarded buffer of the
    message's int8 cells either way, read here as ``array.array('b')`` is
    (``0xFF`` is -1). Other formats keep NumPy's reading (that of
    ``array.array('b')`` already is int8).
    """
    try:
        view.format  # noqa: B018 - raises ValueError once the view is released
    except ValueError:
        raise ValueError(f"{name} is a released memoryview: its buffer is gone") from None
    try:
        arr = np.asarray(view)
    except (TypeError, ValueError, NotImplementedError) as exc:  # a format NumPy cannot read
        raise TypeError(f"{name} is a memoryview NumPy cannot read: {exc}") from None
    if arr.dtype.itemsize == 1 and arr.dtype.kind in "uS":
        return arr.view(np.int8)
    return arr


def _occupancy_values(raw: Any, name: str) -> NDArray[np.integer[Any]]:
    """Occupancy values -1..100 as an integer array; floats, booleans and strings are refused.

    ``bytes``, ``bytearray`` and a ``memoryview`` of single bytes are the
    message's int8 cells as they lie in memory (``0xFF`` is -1), as
    ``array.array('b', raw)`` reads them (:func:`_byte_cells`). The result is not
    copied when ``raw`` already is an integer array or buffer (callers never modify it).
    """
    refuse_masked(raw, name)  # np.asarray would read masked cells as their data
    arr: NDArray[Any]
    if isinstance(raw, memoryview):
        arr = _byte_cells(raw, name)
    else:
        try:
            if isinstance(raw, (bytes, bytearray)):
                arr = np.frombuffer(raw, dtype=np.int8)
            else:
                arr = np.asarray(raw)
        except ValueError:  # NumPy refuses ragged nested sequences
            raise ValueError(
                f"{name} must be a flat sequence of integers, got a ragged one"
            ) from None
    if arr.dtype.kind == "O":
        items = arr.ravel().tolist()
        if all(isinstance(v, numbers.Integral) and not isinstance(v, bool) for v in items):
            # Python integers of any size (an object array, or ints too large for int64).
            if any(not -1 <= v <= 100 for v in items):
                raise ValueError(f"{name} values must be -1 (unknown) or 0..100")
            arr = np.array(items, dtype=np.int64).reshape(arr.shape)
    if arr.dtype == np.bool_ or arr.dtype.kind not in "iu":
        raise TypeError(f"{name} must hold integers, got dtype {arr.dtype}")
    if arr.size and (arr.min() < -1 or arr.max() > 100):
        hint = ""
        if arr.dtype == np.uint8 and arr.max() == 255:
            # A uint8 array is read as the values it holds; it may hold int8 cells as bytes.
            hint = (
                "; if it holds the message's int8 cells as bytes (255 for -1), pass "
                f"{name}.view(np.int8) or its bytes"
            )
        raise ValueError(f"{name} values must be -1 (unknown) or 0..100{hint}")
    return arr


@functools.cache
def _percent_logodds() -> NDArray[np.float32]:
    """Log-odds of the message values -1..100 at index value + 1 (read-only).

    Made by :meth:`OccupancyGrid.from_probabilities` itself (-1 as 0.5), so a
    grid built from the table holds exactly the log-odds that method gives.
    """
    values = np.arange(-1, 101)
    prob = np.where(values < 0, 0.5, values / 100.0).reshape(1, -1)
    table = np.array(OccupancyGrid.from_probabilities(prob, resolution=1.0).logodds[0])
    table.flags.writeable = False
    return table


def _scale_percent(logodds: NDArray[np.float32]) -> NDArray[np.int8]:
    """Mode ``"scale"``'s percentage of every value: the grid's own formula, one cell at a time.

    ``rint(100 p)`` with ``p`` from :meth:`OccupancyGrid.probability`, for values
    within the grid's range (finite, within ±1e6): the oracle of the table of
    :func:`_percent_table`, which gives the same int8 for every float32.
    """
    return np.rint(row_probability(logodds) * 100.0).astype(np.int8)


@functools.cache
def _percent_table() -> StepTable:
    """Look-up tables giving mode ``"scale"``'s percentage of any float32 log-odds.

    :func:`~navkit.mapping.io._step_tables.step_table` of :func:`_scale_percent`:
    its thresholds lie at least 4 % of their size apart, so one comparison
    (``rounds`` 1) finishes each look-up.
    """
    return step_table(_scale_percent, 100)


def _is_unknown(logodds: float, grid: OccupancyGrid) -> bool:
    """Whether ``grid.unknown()`` holds for a cell with these log-odds (for every such cell)."""
    one = OccupancyGrid(
        [[logodds]],
        resolution=1.0,
        occupied_thresh=grid.occupied_thresh,
        free_thresh=grid.free_thresh,
    )
    return bool(one.unknown()[0, 0])


def _scale_data(logodds: NDArray[np.float32], unknown: list[float]) -> NDArray[np.int8]:
    """Mode ``"scale"``'s row-major ``data``: ``rint(100 p)``, -1 where ``logodds`` is ``unknown``.

    The same int8s as ``np.rint(grid.probability() * 100.0)`` cell by cell, by
    look-up (:func:`_percent_table`) instead of an ``exp`` per cell: a
    4000 x 4000 map in a fraction of the time, over blocks of cells.
    """
    values = np.ascontiguousarray(logodds, dtype=np.float32).reshape(-1)
    data = np.empty(values.size, dtype=np.int8)
    n = min(values.size, LOOK_UP_BLOCK)
    look_up = StepLookUp(_percent_table(), n)
    mask = np.empty(n, dtype=np.bool_)
    step = np.empty(n, dtype=np.int8)
    for start in range(0, values.size, LOOK_UP_BLOCK):
        block = values[start : start + LOOK_UP_BLOCK]
        out = data[start : start + LOOK_UP_BLOCK]
        m = block.size
        look_up(block, out.view(np.uint8))  # percentages 0..100: the same bytes as int8
        for value in unknown:
            # out = -1 where block == value, without a branch per cell.
            np.equal(block, np.float32(value), out=mask[:m])
            np.add(out, 1, out=step[:m])
            step[:m] *= mask[:m]
            out -= step[:m]
    return data


@frozen_setattr
@dataclass(frozen=True, slots=True, eq=False)
class OccupancyGridMsgFields:
    """Values for the fields of a ``nav_msgs/OccupancyGrid`` message.

    Parameters
    ----------
    width, height : int
        ``info.width`` (columns) and ``info.height`` (rows), >= 1: cell counts
        under the message's own field names, ``grid.shape[1]`` and
        ``grid.shape[0]`` of the :class:`~navkit.mapping.OccupancyGrid`, whose
        own ``width`` and ``height`` are extents in metres.
    resolution : float
        ``info.resolution``, m per cell, in [1e-6, 1e6].
    origin_position : (float, float, float)
        ``info.origin.position`` ``(x, y, z)``, finite.
    origin_orientation : (float, float, float, float)
        ``info.origin.orientation`` quaternion ``(x, y, z, w)``, finite.
    data : array_like of int, shape (width * height,)
        Row-major occupancy in percent (0..100) or -1 for unknown (``bytes``,
        ``bytearray`` and a ``memoryview`` of single bytes are int8 cells,
        ``0xFF`` is -1); stored as a read-only int8 copy (the caller's array is
        neither kept nor frozen).

    Raises
    ------
    TypeError
        A size that is not an integer, ``data`` that is not integers, a number
        that is not a real number.
    ValueError
        A value outside its range, ``data`` of the wrong length.

    Examples
    --------
    >>> fields = OccupancyGridMsgFields(2, 1, 0.1, (0.0, 0.0, 0.0), (0.0, 0.0, 0.0, 1.0),
    ...                                 [100, -1])
    >>> fields.data
    array([100,  -1], dtype=int8)
    """

    width: int
    height: int
    resolution: float
    origin_position: tuple[float, float, float]
    origin_orientation: tuple[float, float, float, float]
    data: NDArray[np.int8]

    if TYPE_CHECKING:
        # The generated ``__init__`` takes ``data`` as array_like (``__post_init__``
        # converts it); this signature tells type checkers so, at no runtime cost.
        def __init__(
            self,
            width: int,
            height: int,
            resolution: float,
            origin_position: tuple[float, float, float],
            origin_orientation: tuple[float, float, float, float],
            data: ArrayLike,
        ) -> None: ...

    def __post_init__(self) -> None:
        width = _positive_int(self.width, "width")
        height = _positive_int(self.height, "height")
        object.__setattr__(self, "width", width)
        object.__setattr__(self, "height", height)
        object.__setattr__(self, "resolution", _resolution(self.resolution, "resolution"))
        object.__setattr__(
            self, "origin_position", _tuple_of_floats(self.origin_position, 3, "origin_position")
        )
        object.__setattr__(
            self,
            "origin_orientation",
            _tuple_of_floats(self.origin_orientation, 4, "origin_orientation"),
        )
        raw = _occupancy_values(self.data, "data")
        if raw.ndim != 1 or raw.shape[0] != width * height:
            raise ValueError(
                f"data must have shape ({width * height},) (width * height), got {raw.shape}"
            )
        data = np.array(raw, dtype=np.int8, copy=True)
        data.flags.writeable = False
        object.__setattr__(self, "data", data)

    def __reduce__(self) -> tuple[Any, ...]:
        """Copy and pickle support: the arrays read-only again, also in subclasses' copies."""
        return reduce_record(self, ("data",))

    def __setstate__(self, state: list[Any]) -> None:
        """Restore from an older pickle, the arrays read-only again."""
        restore_read_only(self, state, ("data",))


def grid_from_msg(msg: Any) -> OccupancyGrid:
    """Grid from a ``nav_msgs/OccupancyGrid`` (or any look-alike with its field names).

    ``data`` is row-major int8 with row 0 at the origin: -1 is unknown and
    0..100 the occupancy probability in percent. The origin's quaternion is
    normalised and reduced to its yaw (a zero quaternion, ROS 1's default,
    gives yaw 0); it must be a rotation about z, within 1e-3 rad of tilt
    (float32 rounding tilts it by ~1e-7 rad): a grid is planar, and a map plane
    rolled or pitched (upside down at π) has no yaw that places its cells.

    ``info.resolution`` is used as given: in a real message it is a float32,
    so a map saved at 0.05 m reads as 0.05000000074505806 m, as ROS's own
    consumers (Nav2's costmaps, rviz) read it. Cells then agree with a grid of
    the same map read from its YAML (:func:`~navkit.mapping.io.read_map`,
    0.05 exactly) to within ``width × 7.5e-10`` m, but a point lying exactly on
    a cell boundary of one may fall in the neighbouring cell of the other.
    Radii (``OccupancyGrid.inflate``, ``cells_near``, ``costmap``, a planner's
    ``robot_radius``) are taken in cells of the decimal the float32 stands for:
    0.15 m is 3 cells of either map, and both are inflated alike.
    ``info.origin.position.z`` is ignored. (Nav2's map_saver writes the yaw of
    any orientation, and its costmaps ignore the orientation: a tilted map
    there is silently projected or mirrored.)

    map_server publishes a ``mode: scale`` map's in-between pixels rescaled
    between its thresholds, ``rint((p - free_thresh) / (occupied_thresh -
    free_thresh) * 100)`` (Nav2's ``map_io.cpp``), not as the pixel's
    probability p: read here, such a value is taken as a probability, so a cell
    may class differently than in :func:`~navkit.mapping.io.read_map` of the same
    files (p = 0.6 under thresholds 0.65 / 0.196 is published as 89: occupied
    here, unknown there). Trinary maps (0, 100, -1) read the same both ways.

    A value of 50 is probability 0.5, log-odds 0, which is also what -1 reads
    as: the grid cannot tell the two apart, and :func:`grid_to_msg_fields`
    publishes such a cell as -1 (never observed). Every other value, and the
    origin's position, come back from :func:`grid_to_msg_fields` (mode
    ``"scale"``) as they were; the yaw, through its quaternion, to within a few units
    in the last place.

    The grid classes cells by its thresholds (0.65 and 0.196): values 66..100
    are occupied, 0..19 free and 20..65 unknown. Nav2's costmap reads the
    message itself instead: its static layer, with its defaults
    (``trinary_costmap``, ``lethal_cost_threshold: 100``), makes only 100
    lethal and every other value free, -1 unknown with ``track_unknown_space:
    true`` (as Nav2's bringup sets it for the global costmap; the costmap
    node's default, false, makes -1 free too). The two agree on trinary
    maps (0, 100, -1: what map_server publishes for ``mode: trinary``; -1
    tracked as unknown); on a
    message with other values (Cartographer's, a ``mode: scale`` map)
    :func:`~navkit.mapping.costmap` of this grid has obstacles (66..99) and
    unknown cells (20..65) where Nav2's costmap has free space.

    Parameters
    ----------
    msg : nav_msgs/OccupancyGrid or look-alike
        Any object with ``info.width``, ``info.height``, ``info.resolution``
        (m), ``info.origin.position.{x, y}`` (m),
        ``info.origin.orientation.{x, y, z, w}`` and ``data``: an
        ``array.array('b')`` (rclpy), a NumPy integer array (rosbags), a
        sequence of ints (rospy's tuple), or ``bytes``, ``bytearray`` or a
        ``memoryview`` of any of these holding the int8 cells (``0xFF`` is -1,
        also in a memoryview of format ``'B'``, as ``memoryview(bytes)`` is).
        Arrays, bytes and memoryviews are read through their buffer, with no
        Python work per cell.

    Returns
    -------
    OccupancyGrid
        ``info.height`` rows by ``info.width`` columns: occupancy ``data / 100``
        (-1 as 0.5, unknown), origin ``(x, y, yaw)``, the default thresholds.

    Raises
    ------
    TypeError
        ``msg`` lacks a field of the message, or a field has the wrong type
        (a size that is not an integer, ``data`` that is not integers).
    ValueError
        Non-positive size, more than ``OccupancyGrid.MAX_CELLS`` cells,
        ``data`` of the wrong length or with values outside -1..100 (a NumPy
        uint8 array's 255 among them: pass ``data.view(np.int8)`` if it holds
        int8 cells), a released memoryview, a resolution or origin outside the
        ranges of :class:`~navkit.mapping.OccupancyGrid`, an origin orientation
        tilted beyond 1e-3 rad (a roll or pitch, naming
        ``msg.info.origin.orientation``).

    Examples
    --------
    >>> from types import SimpleNamespace as NS
    >>> msg = NS(info=NS(width=2, height=1, resolution=0.1,
    ...                  origin=NS(position=NS(x=1.0, y=0.0, z=0.0),
    ...                            orientation=NS(x=0.0, y=0.0, z=0.0, w=1.0))),
    ...          data=[100, -1])
    >>> grid = grid_from_msg(msg)
    >>> grid.occupied().tolist(), grid.unknown().tolist(), grid.origin.x
    ([[True, False]], [[False, True]], 1.0)
    """
    try:
        info = msg.info
        width_raw, height_raw, resolution_raw = info.width, info.height, info.resolution
        pos = info.origin.position
        q = info.origin.orientation
        xyz = (pos.x, pos.y)
        quat = (q.x, q.y, q.z, q.w)
        raw = msg.data
    except AttributeError as exc:
        raise TypeError(f"msg is not a nav_msgs/OccupancyGrid: {exc}") from None
    width = _positive_int(width_raw, "msg.info.width")
    height = _positive_int(height_raw, "msg.info.height")
    if width * height > OccupancyGrid.MAX_CELLS:
        raise ValueError(
            f"msg.info width x height = {width} x {height} = {width * height} cells exceeds "
            f"OccupancyGrid.MAX_CELLS (2**28 = {OccupancyGrid.MAX_CELLS})"
        )
    resolution = _resolution(resolution_raw, "msg.info.resolution")
    ox, oy = (
        finite_float(v, f"msg.info.origin.position.{k}") for v, k in zip(xyz, "xy", strict=True)
    )
    qx, qy, qz, qw = (
        finite_float(v, f"msg.info.origin.orientation.{k}")
        for v, k in zip(quat, "xyzw", strict=True)
    )
    data = _occupancy_values(raw, "msg.data").ravel()
    if data.size != width * height:
        raise ValueError(
            f"msg.data has {counted(data.size, 'value')}, expected width*height = {width * height}"
        )
    # Normalised without underflow (sub-normal components) and a zero quaternion (ROS
    # 1's default) read as no rotation.
    matrix = quaternion_to_matrix((qx, qy, qz, qw))
    tilt = math.atan2(math.hypot(matrix[0, 2], matrix[1, 2]), matrix[2, 2])
    if tilt > _MAX_TILT:
        flipped = ", upside down" if tilt > math.pi / 2 else ""
        raise ValueError(
            f"msg.info.origin.orientation (x, y, z, w) = {(qx, qy, qz, qw)} tilts the map "
            f"plane by {tilt:.6g} rad (a roll or pitch{flipped}): a grid's origin may only "
            f"turn about z (tilt at most {_MAX_TILT:g} rad)"
        )
    yaw = float(quaternion_to_yaw((qx, qy, qz, qw)))
    # One table look-up per cell (the message has 102 values), not a logarithm:
    # a 4000 x 4000 map converts in a fraction of the time, to the same float32s.
    logodds = _percent_logodds()[data.reshape(height, width) + 1]
    try:
        # The grid keeps the new look-up array (not a copy: 4 bytes a cell less).
        return OccupancyGrid._adopting(logodds, resolution=resolution, origin=Pose2D(ox, oy, yaw))
    except ValueError as exc:
        raise ValueError(f"msg.info: {exc}") from None


def grid_to_msg_fields(
    grid: OccupancyGrid, *, mode: MapMode = "scale", trinary: bool | None = None
) -> OccupancyGridMsgFields:
    """Field values of the ``nav_msgs/OccupancyGrid`` equivalent to ``grid``.

    Parameters
    ----------
    grid : OccupancyGrid
        The map.
    mode : {"scale", "trinary"}, default "scale"
        The modes of :func:`~navkit.mapping.io.write_map` and
        :meth:`~navkit.mapping.OccupancyGrid.save` (whose default is
        ``"trinary"``). ``"scale"``: ``data`` is the rounded probability in percent, with -1 for
        cells whose log-odds are exactly 0 (never observed) and for unknown cells
        whose log-odds are exactly those :func:`~navkit.mapping.io.read_map` gives
        unknown pixels (the middle of the unknown band when the thresholds do not
        class p = 0.5 as unknown), as :func:`~navkit.mapping.io.write_map`'s scale
        mode writes them transparent: a consumer such as Nav2's static layer reads
        any value but -1 as known space. ``"trinary"``: 100 for
        occupied, 0 for free, -1 for unknown cells according to the grid's
        thresholds (what map_server publishes).

    Returns
    -------
    OccupancyGridMsgFields
        ``width`` and ``height`` are the cell counts ``grid.shape[1]`` and
        ``grid.shape[0]`` (ROS's names; ``grid.width`` and ``grid.height`` are
        metres), ``origin_position`` is ``(x, y, 0)``, ``origin_orientation``
        the yaw's quaternion and ``data`` the row-major cells (row 0 at the
        origin).

    Other Parameters
    ----------------
    trinary : bool, optional
        Deprecated form of `mode`: True is ``mode="trinary"``, False ``mode="scale"``.

    Raises
    ------
    TypeError
        ``grid`` not an :class:`~navkit.mapping.OccupancyGrid`, ``mode`` not a
        str, ``trinary`` not a bool, or both ``mode`` and ``trinary`` given.
    ValueError
        ``mode`` neither ``"scale"`` nor ``"trinary"``.

    Notes
    -----
    ``data`` is a NumPy int8 array. An rclpy (ROS 2) message's ``data`` setter
    accepts an ``array.array('b')`` or a sequence of Python ints but, with
    assertions on (the default), refuses a NumPy array: assign
    ``array.array('b', fields.data.tobytes())`` (or ``fields.data.tolist()``).
    ``resolution`` is a float64; the message stores it as a float32 (see
    :func:`grid_from_msg` for what reading it back gives).

    Examples
    --------
    >>> grid = OccupancyGrid.from_occupancy(np.array([[True, False]]), resolution=0.1)
    >>> fields = grid_to_msg_fields(grid)
    >>> fields.data, fields.width, fields.height
    (array([100,   0], dtype=int8), 2, 1)
    """
    if not isinstance(grid, OccupancyGrid):
        raise TypeError(f"grid must be an OccupancyGrid, got {type(grid).__name__}")
    old_mode: MapMode | None = None
    if trinary is not None:
        old_mode = "trinary" if as_bool(trinary, "trinary") else "scale"
    mode = renamed_keyword("trinary", old_mode, "mode", mode, "scale", use=f"mode={old_mode!r}")
    if not isinstance(mode, str):
        raise TypeError(f"mode must be a str, got {type(mode).__name__}")
    if mode not in ("scale", "trinary"):
        raise ValueError(f"mode must be 'scale' or 'trinary', got {mode!r}")
    if mode == "trinary":
        data = np.full(grid.shape, -1, dtype=np.int8)
        data[grid.occupied()] = 100
        data[grid.free()] = 0
    else:
        unknown = [0.0]
        unknown_l = float(np.float32(_unknown_logodds(grid.occupied_thresh, grid.free_thresh)))
        if unknown_l != 0.0 and _is_unknown(unknown_l, grid):
            # A map read with a band that excludes p = 0.5: its unknown pixels carry
            # the band's middle, not 0; published as that percentage, they would be
            # known space to every consumer of the message.
            unknown.append(unknown_l)
        data = _scale_data(grid.logodds, unknown)
    o = grid.origin
    half = 0.5 * o.theta
    return OccupancyGridMsgFields(
        width=grid.shape[1],
        height=grid.shape[0],
        resolution=grid.resolution,
        origin_position=(o.x, o.y, 0.0),
        origin_orientation=(0.0, 0.0, math.sin(half), math.cos(half)),
        data=data.reshape(-1),
    )


def scan_from_msg(msg: Any) -> LaserScan:
    """Scan from any object with the ``sensor_msgs/LaserScan`` field names.

    Reads ``ranges``, ``angle_min``, ``angle_increment``, ``range_min``,
    ``range_max`` and (when present and non-empty) ``intensities``, checked
    as :class:`~navkit.mapping.LaserScan` checks them. ``angle_max`` is not
    read: beam ``k`` of ``ranges`` points at ``angle_min + k * angle_increment``
    whatever ``angle_max`` says (drivers disagree on whether it is the last
    beam's angle; ROS's laser_geometry trusts ``ranges`` and the increment too).

    ``time_increment`` and ``scan_time`` are not read either: the beams are
    taken as simultaneous, with no correction for the sensor's motion during
    the sweep (laser_geometry's ``transformLaserScanToPointCloud`` interpolates
    the sensor pose over it; navkit does not). The header stamp, which the
    message defines as the time of the first beam, is the scan's time
    (:func:`~navkit.mapping.io.read_bag_scans`). At 1 m/s and a 0.1 s sweep the
    last beam was taken up to 0.1 m from where the first was: de-skew such
    scans before converting them if that matters.

    Parameters
    ----------
    msg : sensor_msgs/LaserScan or look-alike
        Any object with those fields (ranges in m, angles in rad).

    Returns
    -------
    LaserScan
        The scan, with ``intensities`` None when the message has none.

    Raises
    ------
    TypeError
        ``msg`` lacks one of the fields, or a field is not real-valued
        (complex numbers, strings, booleans).
    ValueError
        A value outside the ranges of :class:`~navkit.mapping.LaserScan`
        (angles in degrees included).

    Examples
    --------
    >>> from types import SimpleNamespace
    >>> msg = SimpleNamespace(ranges=[1.0, 2.0], angle_min=0.0, angle_increment=0.1,
    ...                       range_min=0.1, range_max=5.0, intensities=[])
    >>> scan = scan_from_msg(msg)
    >>> len(scan), scan.intensities is None
    (2, True)
    """
    fields = {}
    for name in ("ranges", "angle_min", "angle_increment", "range_min", "range_max"):
        if not hasattr(msg, name):
            raise TypeError(f"msg has no field {name!r}; expected a sensor_msgs/LaserScan")
        fields[name] = getattr(msg, name)
    intensities = getattr(msg, "intensities", None)
    return LaserScan(
        fields["ranges"],
        angle_min=fields["angle_min"],
        angle_increment=fields["angle_increment"],
        range_min=fields["range_min"],
        range_max=fields["range_max"],
        intensities=intensities,
    )
