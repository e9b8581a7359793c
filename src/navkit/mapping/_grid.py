"""Log-odds occupancy grids in the ROS ``nav_msgs/OccupancyGrid`` convention.

:class:`OccupancyGrid` holds the storage, the grid ⇄ world coordinates, the
occupied / free / unknown views and obstacle inflation. Building grids from
polygons (:mod:`navkit.mapping._rasterize`), costmaps (:mod:`navkit.mapping._costs`),
ray casting (:mod:`navkit.mapping._raycast`) and map files
(:mod:`navkit.mapping.io`) live in their own modules; the grid's methods of the
same names are thin conveniences that call them.
"""

from __future__ import annotations

import copy
import math
import os
import threading
from collections.abc import Callable
from contextvars import ContextVar
from pathlib import Path
from types import MappingProxyType
from typing import TYPE_CHECKING, Any, ClassVar, Literal, TypeVar, cast, overload

import numpy as np
from numpy.typing import ArrayLike, NDArray

from navkit._shared.deprecation import renamed_keyword
from navkit._shared.dunders import slot_state
from navkit._shared.frozen import fill_added_fields, slot_names
from navkit._shared.grid_coords import CELL_LIMIT, as_pairs, inside, one_or_many
from navkit._shared.locks import ForkSafeLock
from navkit._shared.types import BoolArray, FloatArray, IntArray
from navkit._shared.validation import (
    as_array,
    as_bool,
    as_float_array,
    finite_float,
    holds_bool,
    is_ndarray,
)
from navkit.geometry import Pose2D, as_pose
from navkit.mapping._cells_near_kernels import cells_near_kernel
from navkit.mapping._grid_kernels import (
    cell_to_world_entry,
    world_to_cell_entry,
    world_to_continuous_kernel,
)
from navkit.mapping._limits import (
    CELL_INDEX_LIMIT,
    COORDINATE_LIMIT,
    LOGODDS_LIMIT,
    MAX_CELLS,
    RADIUS_LIMIT,
    bounded_float,
    check_cell_count,
    check_cell_range,
    grid_shape,
    resolution_float,
)
from navkit.mapping._logodds import (
    DEFAULT_CLAMP,
    DEFAULT_FREE_THRESH,
    DEFAULT_HIT,
    DEFAULT_MISS,
    DEFAULT_OCCUPIED_THRESH,
    P_MAX,
    P_MIN,
    logit_bound,
)
from navkit.mapping._new_cells_kernel import NewCellsEntry, new_cells_entry
from navkit.mapping._obstacle_distance import (
    obstacle_distance,
    obstacle_distance_bands,
    reach_cells,
)

if TYPE_CHECKING:
    from navkit.mapping._scan import LaserScan

__all__ = ["MapMode", "OccupancyGrid"]

MapMode = Literal["trinary", "scale"]
"""How a map's image encodes its cells: ``mode`` of :meth:`OccupancyGrid.save`,
:func:`navkit.mapping.io.write_map` and :func:`navkit.mapping.io.grid_to_msg_fields`
(map_server's trinary and scale modes; its ``raw`` mode is read, never written)."""

_FLOAT64 = np.dtype(np.float64)
_INT64 = np.dtype(np.int64)
_empty = np.empty
_ndarray = np.ndarray
# The strides of a C-contiguous (N, 2) float64 array: what the world_to_cell
# fast path asks of its points (with two columns and the dtype).
_PAIR_STRIDES = (16, 8)
# Exact types (no subclasses) whose one pair the single-point fast paths read.
_ONE_PAIR_TYPES = (list, tuple, np.ndarray)

# world_to_cell_kernel's compiled entry, fetched at the first fast-path call
# (:func:`_cells_entry`) so that importing navkit compiles nothing.
_CELLS_ENTRY: Callable[..., bool] | None = None


def _cells_entry() -> Callable[..., bool]:
    global _CELLS_ENTRY
    _CELLS_ENTRY = world_to_cell_entry()
    return _CELLS_ENTRY


def _first_new_cells(
    points: object, origin_x: float, origin_y: float, origin_yaw: float, resolution: float
) -> IntArray | None:
    """world_to_cell's fast path until its entry is fetched: by the first points it takes.

    Anything else (a list, a tuple, one point as a (2,) array: a start, a goal)
    goes the general way, which compiles no kernel for one point: those calls
    must not compile the fast path's entry either (about 0.35 s in an empty
    cache). Python's tests of the former fast path, until then.
    """
    global _NEW_CELLS
    if not (
        type(points) is _ndarray
        and points.dtype is _FLOAT64
        and points.strides == _PAIR_STRIDES
        and points.shape[1] == 2
    ):
        return None
    _NEW_CELLS = new_cells_entry()
    return _NEW_CELLS(points, origin_x, origin_y, origin_yaw, resolution)


# world_to_new_cells's compiled entry (world_to_cell's fast path; navkit.mapping.
# _new_cells_kernel), in place of _first_new_cells from the first points it takes
# on, so that importing navkit compiles nothing.
_NEW_CELLS: NewCellsEntry = _first_new_cells


# cell_to_world_kernel's compiled entries by cell dtype, each fetched at the first
# fast-path call with such cells (:func:`_points_entry`), as _CELLS_ENTRY.
_POINTS_ENTRIES: dict[np.dtype[Any], Callable[..., bool]] = {}


def _points_entry(dtype: np.dtype[Any]) -> Callable[..., bool]:
    entry = _POINTS_ENTRIES[dtype] = cell_to_world_entry(dtype)
    return entry


def _one_pair(value: Any, ints: bool) -> tuple[float, float] | None:
    """One pair given as a list, tuple or (2,) float64 array as two finite floats, else None.

    Items must be floats (``np.float64`` too) or, with ``ints``, integers within
    ±2**53 (converted exactly, as NumPy's int64 to float64). None sends the
    value the general way, which converts and validates anything else.
    """
    if type(value) is _ndarray:
        if value.dtype is not _FLOAT64 or value.shape != (2,):
            return None
        # tolist() reads any strides without compiling anything for the layout.
        value = value.tolist()
    elif len(value) != 2:
        return None
    a, b = value
    pair = []
    for v in (a, b):
        kind = type(v)
        if kind is float or kind is np.float64:
            v = float(v)
            if not math.isfinite(v):
                return None
        elif ints and kind is int and -(2**53) <= v <= 2**53:
            v = float(v)
        else:
            return None
        pair.append(v)
    return pair[0], pair[1]


_IDENTITY = Pose2D(0.0, 0.0, 0.0)

# The grids' writer locks (OccupancyGrid._writer_lock) are stamped with the
# number of forks into this process, and made under this lock where missing: a
# child forked while another thread held a grid's lock (mid-scan) would wait
# for ever on that thread, which does not exist in the child, so a lock made
# before a fork is made anew after it (one registration for every grid).
# Re-entrant: a signal handler copying a grid can run while the main thread makes a
# lock under it (at _new_lock's call; every grid's first use in a forked child makes
# one), and with a plain lock it waited for ever there (review 25).
_LOCK_MAKING = ForkSafeLock(reentrant=True)
_FORKS = [0]


def _forked() -> None:
    _FORKS[0] += 1


def _new_lock() -> tuple[threading.RLock, int]:
    """A grid's writer lock, stamped with the forks so far (``OccupancyGrid._writer_lock``)."""
    return threading.RLock(), _FORKS[0]


if hasattr(os, "register_at_fork"):
    os.register_at_fork(after_in_child=_forked)


def _threshold(value: float | None, default: float, name: str) -> float:
    if value is None:
        return default
    out = finite_float(value, name)
    if not 0.0 <= out <= 1.0:
        raise ValueError(f"{name} must lie in [0, 1], got {out}")
    return out


def _thresholds(
    occupied: float, free: float, *, own_occupied: bool = False, own_free: bool = False
) -> None:
    """Refuse ``free >= occupied``; ``own_*``: that value is the grid's, not the caller's."""
    if free < occupied:
        return
    if own_free and not own_occupied:
        # "Swapped?" would blame two values the caller did not both give.
        raise ValueError(
            f"occupied_thresh ({occupied}) must be larger than free_thresh ({free}: the "
            "grid's own, as free_thresh was not given)"
        )
    if own_occupied and not own_free:
        raise ValueError(
            f"free_thresh ({free}) must be smaller than occupied_thresh ({occupied}: the "
            "grid's own, as occupied_thresh was not given)"
        )
    raise ValueError(
        f"free_thresh ({free}) must be smaller than occupied_thresh ({occupied}); "
        "are the two swapped?"
    )


def grid_origin(value: Pose2D | ArrayLike, name: str = "origin") -> Pose2D:
    """``value`` as a Pose2D whose x and y lie within ±1e9 m."""
    origin = as_pose(value, name)
    if not (abs(origin.x) <= COORDINATE_LIMIT and abs(origin.y) <= COORDINATE_LIMIT):
        raise ValueError(f"{name} x and y must lie within ±1e9 m, got ({origin.x}, {origin.y})")
    return origin


def _bool_grid(value: ArrayLike, name: str) -> BoolArray:
    arr = as_array(value, name)
    if arr.dtype != np.bool_:
        raise TypeError(f"{name} must be a boolean array, got dtype {arr.dtype}")
    if arr.ndim != 2 or arr.shape[0] == 0 or arr.shape[1] == 0:
        raise ValueError(f"{name} must be a non-empty 2-D (rows, cols) array, got {arr.shape}")
    return arr


# Float dtypes whose conversion to float32 rounds exactly as through float64
# (one rounding), so the grid stores them without a float64 copy.
_NARROW_FLOATS = (np.dtype(np.float16), np.dtype(np.float32), _FLOAT64)


def _logodds_array(value: ArrayLike) -> NDArray[Any]:
    """``value`` as a 2-D real array, not widened to float64 when it is a float array.

    Integers and other values go through :func:`as_float_array` (an integer above
    2**24 converted to float32 directly could round differently than via float64).
    """
    if type(value) is np.ndarray and value.dtype in _NARROW_FLOATS:
        if value.ndim != 2:
            raise ValueError(f"logodds must be 2-D, got shape {value.shape}")
        return value
    if is_ndarray(value) and value.dtype == np.bool_:
        # An occupancy mask is the usual first grid: name the constructor that takes it.
        raise TypeError(f"logodds must hold real numbers, got dtype bool: {_MASK_HINT}")
    if _message_dtype(value) in _MESSAGE_CELLS:
        # A message's cells taken as log-odds would be a silent wrong map: free (0)
        # cells unknown, a costmap's lethal 254 occupied and its free 0 unknown.
        raise TypeError(
            f"logodds must hold log-odds, got dtype {_message_dtype(value)}, the dtype of ROS map "
            "cells (nav_msgs/OccupancyGrid's int8 percentages and -1, a costmap's uint8 "
            "costs): read a message with navkit.mapping.io.grid_from_msg, convert "
            "percentages with OccupancyGrid.from_probabilities(np.where(cells < 0, 0.5, "
            "cells / 100), resolution=...), or convert the array to float first if it "
            "really holds log-odds"
        )
    try:
        return as_float_array(value, "logodds", ndim=2, finite=False)
    except TypeError as exc:
        # Nested lists of bools (a mask typed by hand) get the mask's hint too.
        if isinstance(value, (list, tuple)) and holds_bool(value):
            raise TypeError(f"{exc}: {_MASK_HINT}") from None
        raise


def _message_dtype(value: object) -> np.dtype[Any] | None:
    """The dtype NumPy gives ``value`` (None if it gives none), to spot ROS map cells.

    An ndarray's own; for anything else (rclpy's ``array.array('b')`` rows of a
    message, a memoryview, an object with ``__array__``) what ``np.asarray``
    makes of it, once: building a grid from a non-array is not a hot path.
    """
    try:
        dtype: np.dtype[Any] = value.dtype if is_ndarray(value) else np.asarray(value).dtype
    except Exception:  # the general conversion that follows raises navkit's error
        return None
    return dtype


#: The advice given with a boolean ``logodds``: an occupancy mask is the usual first grid.
_MASK_HINT = (
    "make a grid of a boolean occupancy mask with "
    "OccupancyGrid.from_occupancy(mask, resolution=...)"
)

#: The dtypes of ROS map cells (nav_msgs/OccupancyGrid's int8, a costmap's uint8): no
#: log-odds grid is stored as them.
_MESSAGE_CELLS = (np.dtype(np.int8), np.dtype(np.uint8))


# Cells per block of :func:`_probability_logodds`: its float64 temporaries stay
# this small (2 x 512 KiB) whatever the grid's size.
_BLOCK_CELLS = 1 << 16


_G = TypeVar("_G", bound="OccupancyGrid")

#: The log-odds array a constructor of this module made for the grid being built
#: (see :func:`_owned_grid`): ``__init__`` keeps that one array instead of copying it.
_ADOPTED: ContextVar[NDArray[np.float32] | None] = ContextVar("_ADOPTED", default=None)


def _owned_grid(cls: type[_G], logodds: NDArray[np.float32], **kwargs: Any) -> _G:
    """``cls(logodds, **kwargs)`` keeping ``logodds`` itself, a new array no one else holds.

    The constructor copies its input (the caller may still hold and change it);
    an array made by one of this module's constructors for the grid has no other
    holder, and copying it doubled their peak memory: ``OccupancyGrid.empty``
    took 8 bytes a cell for a 4-byte grid, 2 GiB at :data:`MAX_CELLS`. It is
    kept only when ``__init__`` receives that very object (a subclass's
    constructor that passes another array has it copied) as float32,
    C-contiguous, writable and owning its data.
    """
    token = _ADOPTED.set(logodds)
    try:
        return cls(logodds, **kwargs)
    finally:
        _ADOPTED.reset(token)


def _adoptable(arr: NDArray[Any]) -> bool:
    return (
        arr is _ADOPTED.get()
        and arr.dtype == np.float32
        and arr.base is None
        and arr.flags.c_contiguous
        and arr.flags.writeable
    )


def _probability_logodds(p: FloatArray) -> NDArray[np.float32]:
    """Float32 ``log(p / (1 - p))`` of ``p`` clipped to [P_MIN, P_MAX], shape (rows, cols).

    Computed in float64 over blocks of rows, each rounded to float32 once, as
    ``np.log(p / (1 - p)).astype(np.float32)`` of the whole grid would be but
    without its three float64 temporaries of the grid's size (24 bytes a cell).
    """
    rows, cols = p.shape
    out = np.empty((rows, cols), dtype=np.float32)
    step = max(1, _BLOCK_CELLS // max(cols, 1))
    for r in range(0, rows, step):
        block = np.clip(p[r : r + step], P_MIN, P_MAX)
        ratio = 1.0 - block
        np.divide(block, ratio, out=ratio)
        np.log(ratio, out=ratio)
        out[r : r + step] = ratio
    return out


class OccupancyGrid:
    """A 2-D occupancy grid storing the log-odds of occupancy of every cell.

    Cells are indexed ``[row, col]``. As in ROS ``nav_msgs/OccupancyGrid``, cell
    ``(0, 0)`` is the one at the map origin, rows grow along the origin's y axis
    and columns along its x axis, so **row 0 is the lowest y** (an image file's
    top row is the last map row). Cell ``(row, col)`` covers
    ``[col, col + 1) × [row, row + 1)`` times ``resolution`` in the origin frame.

    Continuous grid coordinates are float ``(row, col)`` with integers at cell
    centres: cell ``(r, c)`` covers ``[r - ½, r + ½) × [c - ½, c + ½)``, so the
    map origin (the lower-left corner of cell (0, 0)) is at ``(-0.5, -0.5)``.

    Log-odds 0 (probability 0.5) means unknown. The views :meth:`occupied`,
    :meth:`free` and :meth:`unknown` classify cells with the thresholds of
    map_server: occupied when ``p > occupied_thresh``, free when
    ``p < free_thresh``, unknown in between.

    An ordinary class with ``__slots__`` rather than a frozen dataclass because
    ray casting (:func:`navkit.mapping.integrate_scan`) updates its log-odds in
    place. Writers take turns: each grid has a lock that every scan written
    into it holds, so threads integrating scans into one grid at once add
    whole scans, one after another, and :meth:`copy` (which holds it too)
    returns the grid after a whole number of scans. Other readers take no
    lock: a thread reading the log-odds, costs or occupancy meanwhile may see
    a scan half written (the mapping guide's "Threads" section shows how to
    publish snapshots).

    Parameters
    ----------
    logodds : array_like, shape (rows, cols)
        Log-odds of occupancy, finite and within ±1e6; copied to a new float32
        array. At most :attr:`MAX_CELLS` (``2**28``) cells.
    resolution : float
        Cell size, m, in [1e-6, 1e6].
    origin : Pose2D or array_like [x, y, yaw], default Pose2D(0, 0, 0)
        World pose of the corner of cell (0, 0) (its lower-left corner), x and y
        within ±1e9 m; the yaw rotates the whole grid about that corner (the
        meaning of ``nav_msgs/OccupancyGrid``'s ``info.origin`` orientation;
        Nav2's costmaps ignore a map's yaw, so keep it 0 for maps meant for Nav2).
    occupied_thresh, free_thresh : float
        Default thresholds of the views, ``0 <= free_thresh < occupied_thresh <= 1``.

    Raises
    ------
    TypeError
        ``logodds`` is not real-valued (complex, strings, booleans), an int8 or
        uint8 array (the dtypes of ROS map cells: :func:`navkit.mapping.io.grid_from_msg`
        reads a message), a number is not a real number.
    ValueError
        Wrong shape, NaN or ±inf, a value outside its range, more than
        :attr:`MAX_CELLS` cells.

    Examples
    --------
    >>> grid = OccupancyGrid.empty(width=4.0, height=2.0, resolution=0.5)
    >>> grid.shape
    (4, 8)
    >>> grid.world_to_cell([[0.1, 1.9], [3.9, 0.2]])
    array([[3, 0],
           [0, 7]])
    >>> grid.world_to_cell([0.1, 1.9])
    array([3, 0])
    >>> grid.cell_to_world([3, 0])
    array([0.25, 1.75])
    >>> grid.cell_to_world([-0.5, -0.5])
    array([0., 0.])
    >>> bool(grid.unknown().all())
    True
    """

    __slots__ = (
        "__weakref__",  # weakref.ref(obj) for callbacks and caches (review 36)
        "_free_thresh",
        "_lock",
        "_logodds",
        "_occupied_thresh",
        "_origin",
        "_origin_x",
        "_origin_y",
        "_origin_yaw",
        "_resolution",
    )

    # Slots added since a release, for pickles made before (see
    # navkit._shared.frozen.fill_added_fields): the origin's plain floats, as
    # __init__ makes them. Not annotated: it would read as a slot's type.
    _added_fields = MappingProxyType(
        {
            "_origin_x": lambda grid: float(grid._origin.x),
            "_origin_y": lambda grid: float(grid._origin.y),
            "_origin_yaw": lambda grid: float(grid._origin.theta),
        }
    )

    def __getstate__(self) -> object:
        # slot_state (pickle protocols 0 and 1 too), less the lock: a lock cannot
        # be pickled, and a copy or a pickle is a grid of its own with its own.
        # Python's state is the __dict__ (or None) alone where no slot is set (a grid
        # built by __new__ that a subclass has not filled yet).
        state = slot_state(self)
        instance, slots = cast(
            "tuple[dict[str, Any] | None, dict[str, Any]]",
            state if isinstance(state, tuple) else (state, {}),
        )
        return instance, {k: v for k, v in slots.items() if k != "_lock"}

    def __setstate__(self, state: object) -> None:
        # Pickles of any release (those written before the lock included) load,
        # with a lock of their own.
        instance, slots = state if isinstance(state, tuple) else (state, None)
        if instance:
            self.__dict__.update(instance)
        for name, value in (slots or {}).items():
            if name != "_lock":
                object.__setattr__(self, name, value)
        if slots:
            # The origin's floats came later (review 51: a MapPlanner pickled at 908ac92
            # raised AttributeError at its first query). Not for a grid built by
            # __new__ and not filled, whose state holds no slot to make them from.
            fill_added_fields(self)
        self._lock = _new_lock()

    def __deepcopy__(self, memo: dict[int, Any]) -> OccupancyGrid:
        # copy.deepcopy's own way, from the same reduction (a subclass's
        # __getnewargs__, __reduce__ or __getstate__ count as without this method),
        # but with the log-odds copied under the writer lock, as copy() does: a
        # scan another thread is writing ends first. The rest is copied outside
        # it (a subclass's attributes may run code of their own when copied).
        # None: a grid built by __new__, not filled yet. In the memo: deep-copied
        # already (held elsewhere in what is copied), and kept shared.
        logodds = getattr(self, "_logodds", None)
        if logodds is not None and id(logodds) not in memo:
            with self._writer_lock():
                memo[id(logodds)] = logodds.copy()  # what the state's log-odds copy to
            memo.setdefault(id(memo), []).append(logodds)  # copy.deepcopy's keep-alive
        reduced = self.__reduce_ex__(4)
        if isinstance(reduced, str):  # copy.deepcopy's rule: a global is itself
            return self
        func, args, state = reduced[0], reduced[1], (*reduced, None)[2]
        new: OccupancyGrid = func(*copy.deepcopy(args, memo))
        memo[id(self)] = new
        if state is not None:
            new.__setstate__(copy.deepcopy(state, memo))
        return new

    def _writer_lock(self) -> threading.RLock:
        """The lock every writer of the log-odds holds (ray casting, :meth:`copy`).

        Made by the constructor, copies and pickles, and here on first need
        where none was (a grid built by ``__new__``, as a subclass's own
        constructor may); made anew in a process forked while another thread
        held it (that thread is not in the child).
        Re-entrant: a signal handler (saving the map on Ctrl-C, say) runs in
        the main thread as its ray casting returns, still holding the lock,
        and its ``copy()`` waited there for ever; it now copies the grid with
        that scan whole.
        """
        held: tuple[threading.RLock, int] | None = getattr(self, "_lock", None)
        forks = _FORKS[0]
        if held is not None and held[1] == forks:
            return held[0]
        with _LOCK_MAKING:  # one lock, whichever threads get here at once
            held = getattr(self, "_lock", None)
            if held is None or held[1] != forks:
                made = _new_lock()
                # A signal handler run during that call may have made (and another
                # thread since taken) one: kept. Read with no call, where no handler
                # runs, up to the store.
                try:
                    held = self._lock
                except AttributeError:
                    held = None
                if held is None or held[1] != forks:
                    held = self._lock = made
            return held[0]

    #: Largest number of cells of a grid (``2**28`` = 268,435,456: 1 GiB of
    #: float32 log-odds, e.g. 16384 × 16384 cells, 819 m × 819 m at 5 cm). Every
    #: constructor, file reader and message converter checks it before allocating.
    MAX_CELLS: ClassVar[int] = MAX_CELLS

    def __init__(
        self,
        logodds: ArrayLike,
        *,
        resolution: float,
        origin: Pose2D | ArrayLike = _IDENTITY,
        occupied_thresh: float = DEFAULT_OCCUPIED_THRESH,
        free_thresh: float = DEFAULT_FREE_THRESH,
    ) -> None:
        arr = _logodds_array(logodds)
        if arr.shape[0] == 0 or arr.shape[1] == 0:
            raise ValueError(f"logodds must not be empty, got shape {arr.shape}")
        check_cell_count(float(arr.size), "logodds")
        # Range and finiteness from min and max: no temporary array of the grid's
        # size (np.isfinite and np.abs of a float64 copy cost 17 bytes a cell).
        low, high = float(arr.min()), float(arr.max())
        if not (math.isfinite(low) and math.isfinite(high)):
            raise ValueError("logodds must contain only finite values")
        if not max(-low, high) <= LOGODDS_LIMIT:
            raise ValueError(f"logodds must lie within ±1e6, got {max(-low, high)}")
        self._resolution = resolution_float(resolution)
        self._origin = grid_origin(origin)
        # Plain floats for the per-call kernel arguments of world_to_cell.
        self._origin_x = float(self._origin.x)
        self._origin_y = float(self._origin.y)
        self._origin_yaw = float(self._origin.theta)
        occ = bounded_float(occupied_thresh, "occupied_thresh", 0.0, 1.0)
        free = bounded_float(free_thresh, "free_thresh", 0.0, 1.0)
        _thresholds(occ, free)
        # The one mutable array: ray casting (navkit.mapping._raycast) writes into it.
        # A log-odds of 1e-200 rounds to 0 in float32: no error, whatever np.seterr says.
        with np.errstate(under="ignore"):
            self._logodds: NDArray[np.float32] = (
                arr if _adoptable(arr) else np.array(arr, dtype=np.float32, order="C", copy=True)
            )
        self._occupied_thresh = occ
        self._free_thresh = free
        # Held by every writer of _logodds whose kernel releases the GIL (ray
        # casting) and by copy(): writers take turns, so no cell update is lost
        # (+0.3 % on a 360-beam scan into a 140 x 100 grid, 48 us). Taken
        # through _writer_lock, which also makes it where it is missing.
        self._lock = _new_lock()

    # ------------------------------------------------------------------ basics
    @property
    def logodds(self) -> NDArray[np.float32]:
        """Read-only view of the log-odds, shape (rows, cols), float32.

        A view, not a copy: ray casting into the grid (in place, as
        :func:`~navkit.mapping.integrate_scan`) changes what it shows; copy it
        (``.copy()``) to keep a snapshot.
        """
        view: NDArray[np.float32] = self._logodds.view()
        view.flags.writeable = False
        return view

    @property
    def resolution(self) -> float:
        """Cell size, m."""
        return self._resolution

    @property
    def origin(self) -> Pose2D:
        """World pose of the lower-left corner of cell (0, 0)."""
        return self._origin

    @property
    def shape(self) -> tuple[int, int]:
        """``(rows, cols)``."""
        rows, cols = self._logodds.shape
        return int(rows), int(cols)

    @property
    def occupied_thresh(self) -> float:
        """Default probability above which a cell is occupied."""
        return self._occupied_thresh

    @property
    def free_thresh(self) -> float:
        """Default probability below which a cell is free."""
        return self._free_thresh

    @property
    def width(self) -> float:
        """Extent along the origin's x axis, m (``cols * resolution``)."""
        return self.shape[1] * self._resolution

    @property
    def height(self) -> float:
        """Extent along the origin's y axis, m (``rows * resolution``)."""
        return self.shape[0] * self._resolution

    def __repr__(self) -> str:
        # The log-odds, an argument not printed, as <...> (as AStarPlanner's costs):
        # "shape=" read as a keyword the constructor does not take.
        rows, cols = self.shape
        return (
            f"{type(self).__name__}(<{rows}x{cols} cells>, resolution={self._resolution}, "
            f"origin={self._origin!r})"
        )

    def copy(self) -> OccupancyGrid:
        """Independent copy (log-odds array included).

        Returns
        -------
        OccupancyGrid
            A new grid of the same class with a copy of the log-odds, the same
            resolution, origin and thresholds (a subclass's own attributes are
            copied as :func:`copy.copy` copies them: shallowly).

        Examples
        --------
        >>> grid = OccupancyGrid.empty(width=1.0, height=1.0, resolution=0.5)
        >>> grid.copy().logodds is grid.logodds
        False
        """
        cls = type(self)
        if cls is OccupancyGrid:
            with self._writer_lock():  # a scan being written by another thread ends first
                return OccupancyGrid(
                    self._logodds,
                    resolution=self._resolution,
                    origin=self._origin,
                    occupied_thresh=self._occupied_thresh,
                    free_thresh=self._free_thresh,
                )
        # A subclass is copied as itself, with what it adds (its __dict__, its
        # own slots), as copy.copy copies any object, and its own log-odds and lock.
        new = cls.__new__(cls)
        for name in slot_names(cls):
            if name != "_lock" and hasattr(self, name):
                object.__setattr__(new, name, getattr(self, name))
        instance = getattr(self, "__dict__", None)
        if instance:
            new.__dict__.update(instance)
        with self._writer_lock():
            new._logodds = self._logodds.copy()
        new._lock = _new_lock()
        return new

    def __copy__(self) -> OccupancyGrid:
        # Ray casting updates the log-odds in place: a shallow copy sharing the
        # array would write its scans into this grid, so copy.copy copies it too.
        return self.copy()

    # ------------------------------------------------------------ constructors
    @classmethod
    def _adopting(cls: type[_G], logodds: NDArray[np.float32], **kwargs: Any) -> _G:
        """``cls(logodds, **kwargs)`` keeping ``logodds`` itself (:func:`_owned_grid`).

        For navkit's readers in other subpackages (``mapping.io``), which build a
        new log-odds array no one else holds.
        """
        return _owned_grid(cls, logodds, **kwargs)

    @classmethod
    def empty(
        cls,
        *,
        width: float,
        height: float,
        resolution: float,
        origin: Pose2D | ArrayLike = _IDENTITY,
    ) -> OccupancyGrid:
        """All-unknown grid of ``width × height`` metres, rounded up to whole cells.

        The grid covers the extent requested to within 1e-9 of a cell, or, at
        a float32 ``resolution`` (a ROS message's), to within that float32's
        rounding of the decimal it stands for: its cells are counted in cells
        of that decimal and may be a little smaller (see Returns).

        Parameters
        ----------
        width, height : float
            Extent along the origin's x and y axes, m (> 0).
        resolution : float
            Cell size, m, in [1e-6, 1e6].
        origin : Pose2D or array_like [x, y, yaw], optional
            World pose of the lower-left corner, x and y within ±1e9 m.

        Returns
        -------
        OccupancyGrid
            ``height / resolution`` rows by ``width / resolution`` columns,
            each rounded up to a whole cell (at least one; a ratio within 1e-9
            of an integer, or within its float rounding, a few ulps, is not
            rounded up: ``width = n * resolution`` gives ``n`` columns for any
            ``n``), every log-odds 0 (unknown). So ``cols * resolution`` is at
            least ``width - (1e-9 + 2**-50 * cols) * resolution`` (the
            rounding of the count; likewise rows). A float32 ``resolution`` (a ROS
            message's) counts cells of the decimal it stands for: 10 m at
            ``float(np.float32(0.01))`` are 1000 cells, as at 0.01, and as
            that float32 lies below 0.01 they span 9.99999977 m; such a grid
            falls short of ``width`` by at most float32's rounding of the
            resolution, ``2**-24`` (6e-8) of ``width``, beside that 1e-9 of a
            cell (a width of whole float32 cells is that many cells).

        Raises
        ------
        TypeError
            ``width``, ``height`` or ``resolution`` not a real number, or an
            ``origin`` that is not a pose.
        ValueError
            A value outside its range (an ``origin`` with NaN, inf or the wrong
            length included), or a grid of more than :attr:`MAX_CELLS` cells
            (the message says how many it would need); nothing is allocated.

        Examples
        --------
        >>> OccupancyGrid.empty(width=1.01, height=0.2, resolution=0.5).shape
        (1, 3)
        >>> ros = OccupancyGrid.empty(width=10.0, height=0.5, resolution=np.float32(0.01))
        >>> ros.shape, float(ros.shape[1] * ros.resolution)  # cells of 0.0099999998 m
        ((50, 1000), 9.999999776482582)
        """
        w = bounded_float(width, "width", 0.0, math.inf, "m", low_open=True)
        h = bounded_float(height, "height", 0.0, math.inf, "m", low_open=True)
        res = resolution_float(resolution)
        pose = grid_origin(origin)
        rows, cols = grid_shape(
            width=w,
            height=h,
            resolution=res,
            what=f"a grid of {w:g} m x {h:g} m at resolution {res:g} m",
        )
        zeros = np.zeros((rows, cols), dtype=np.float32)
        return _owned_grid(cls, zeros, resolution=res, origin=pose)

    @classmethod
    def from_probabilities(
        cls,
        probabilities: ArrayLike,
        *,
        resolution: float,
        origin: Pose2D | ArrayLike = _IDENTITY,
        occupied_thresh: float = DEFAULT_OCCUPIED_THRESH,
        free_thresh: float = DEFAULT_FREE_THRESH,
    ) -> OccupancyGrid:
        """Grid from occupancy probabilities in [0, 1] (0.5 = unknown), shape (rows, cols).

        Probabilities are clipped to [0.001, 0.999] so that certain cells have
        finite log-odds (about ±6.9); 0.5 gives log-odds exactly 0.

        Parameters
        ----------
        probabilities : array_like, shape (rows, cols)
            Occupancy probability of each cell, ``[row, col]`` with row 0 at the
            lowest y, in [0, 1]; at most :attr:`MAX_CELLS` cells.
        resolution : float
            Cell size, m, in [1e-6, 1e6].
        origin : Pose2D or array_like [x, y, yaw], optional
            World pose of the lower-left corner, x and y within ±1e9 m.
        occupied_thresh, free_thresh : float
            Default thresholds of the views,
            ``0 <= free_thresh < occupied_thresh <= 1``.

        Returns
        -------
        OccupancyGrid
            Log-odds ``log(p / (1 - p))`` of the clipped probabilities.

        Raises
        ------
        TypeError, ValueError
            Non-numeric or non-finite probabilities, values outside [0, 1], or
            another argument outside its range.

        Examples
        --------
        >>> grid = OccupancyGrid.from_probabilities([[0.0, 0.5, 1.0]], resolution=0.1)
        >>> grid.occupied().tolist(), grid.unknown().tolist()
        ([[False, False, True]], [[False, True, False]])
        """
        p = as_float_array(probabilities, "probabilities", ndim=2)
        if p.shape[0] == 0 or p.shape[1] == 0:
            raise ValueError(f"probabilities must not be empty, got shape {p.shape}")
        check_cell_count(float(p.size), "probabilities")
        if p.size and (p.min() < 0.0 or p.max() > 1.0):
            lo, hi = float(p.min()), float(p.max())
            hint = ""
            if lo >= -1.0 and hi <= 100.0 and bool(np.all(p == np.round(p))):
                # The ROS nav_msgs/OccupancyGrid encoding: whole percent (int8), -1 for
                # unknown. Fractions out of range (log-odds, rounding) are not it, and
                # dividing them by 100 would make a wrong map silently.
                hint = (
                    "; this looks like ROS OccupancyGrid data (0..100 percent, -1 unknown): "
                    "read the message with navkit.mapping.io.grid_from_msg, or convert it "
                    "with np.where(data < 0, 0.5, data / 100)"
                )
            # Exact, not :g alone: a value just above 1 (1.0000001, from arithmetic)
            # must not print as 1 in the range it is refused for.
            lo_text = f"{lo:g}" if float(f"{lo:g}") == lo else repr(lo)
            hi_text = f"{hi:g}" if float(f"{hi:g}") == hi else repr(hi)
            raise ValueError(f"probabilities must lie in [0, 1], got [{lo_text}, {hi_text}]{hint}")
        return _owned_grid(
            cls,
            _probability_logodds(p),
            resolution=resolution,
            origin=origin,
            occupied_thresh=occupied_thresh,
            free_thresh=free_thresh,
        )

    @classmethod
    def from_occupancy(
        cls,
        occupied: ArrayLike,
        *,
        resolution: float,
        origin: Pose2D | ArrayLike = _IDENTITY,
        unknown: ArrayLike | None = None,
    ) -> OccupancyGrid:
        """Grid from a boolean obstacle mask: True occupied, False free.

        Parameters
        ----------
        occupied : array_like of bool, shape (rows, cols)
            Obstacle cells, ``[row, col]`` with row 0 at the lowest y.
        resolution : float
            Cell size, m.
        origin : Pose2D or array_like [x, y, yaw], optional
            World pose of the lower-left corner.
        unknown : array_like of bool, shape (rows, cols), optional
            Cells to mark unknown instead (must not overlap ``occupied``).

        Returns
        -------
        OccupancyGrid
            Occupied cells at probability 0.999, free ones at 0.001, unknown
            ones at 0.5 (log-odds 0), with the default thresholds.

        Raises
        ------
        TypeError
            A mask that is not boolean.
        ValueError
            Masks of different or empty shapes, overlapping masks, or another
            argument outside its range.

        Examples
        --------
        >>> grid = OccupancyGrid.from_occupancy(np.eye(3, dtype=bool), resolution=1.0)
        >>> grid.traversal_costs()
        array([[inf,  1.,  1.],
               [ 1., inf,  1.],
               [ 1.,  1., inf]])
        """
        occ = _bool_grid(occupied, "occupied")
        check_cell_count(float(occ.size), "occupied")
        # The log-odds of from_probabilities for p = 0, 1 and 0.5, written straight
        # into float32: no float64 probability grid (8 bytes a cell) in between.
        free_l, occupied_l, unknown_l = _probability_logodds(np.array([[0.0, 1.0, 0.5]]))[0]
        logodds = np.where(occ, occupied_l, free_l)
        if unknown is not None:
            unk = _bool_grid(unknown, "unknown")
            if unk.shape != occ.shape:
                raise ValueError(
                    f"unknown must have the shape of occupied {occ.shape}, got {unk.shape}"
                )
            if (unk & occ).any():
                raise ValueError("unknown and occupied must not overlap")
            logodds[unk] = unknown_l
        return _owned_grid(cls, logodds, resolution=resolution, origin=origin)

    @classmethod
    def from_polygons(
        cls, geometries: Any, *, bounds: ArrayLike, resolution: float
    ) -> OccupancyGrid:
        """Rasterise shapely obstacles; see :func:`navkit.mapping.rasterize_polygons`.

        A cell is occupied when its closed square touches an obstacle.

        Parameters
        ----------
        geometries : shapely geometry or iterable of them
            Obstacles in world coordinates (m), finite.
        bounds : array_like (xmin, ymin, xmax, ymax)
            Area to cover, m, within ±1e9 m; the grid's origin is
            ``(xmin, ymin)``.
        resolution : float
            Cell size, m, in [1e-6, 1e6].

        Returns
        -------
        OccupancyGrid
            The axis-aligned grid, rounded up to whole cells; every cell
            occupied or free.

        Raises
        ------
        TypeError, ValueError
            As :func:`navkit.mapping.rasterize_polygons`.

        Examples
        --------
        >>> from shapely.geometry import box
        >>> grid = OccupancyGrid.from_polygons(
        ...     box(1.2, 0.2, 1.8, 0.8), bounds=(0, 0, 3, 1), resolution=0.5)
        >>> grid.occupied().astype(int)
        array([[0, 0, 1, 1, 0, 0],
               [0, 0, 1, 1, 0, 0]])
        """
        # Imported here: the function modules build on this class.
        from navkit.mapping._rasterize import rasterize_polygons

        return cls._built_as(rasterize_polygons(geometries, bounds=bounds, resolution=resolution))

    # ------------------------------------------------------------------ files
    @classmethod
    def load(cls, path: str | os.PathLike[str]) -> OccupancyGrid:
        """Load a ROS map_server map; see :func:`navkit.mapping.io.read_map`.

        Parameters
        ----------
        path : str or path-like
            The map's YAML file; a relative ``image`` is found beside it.

        Returns
        -------
        OccupancyGrid
            The map, the image's top row as the last grid row, with the YAML's
            thresholds.

        Raises
        ------
        TypeError, FileNotFoundError, ValueError, ImportError, OSError
            As :func:`navkit.mapping.io.read_map` (TypeError: a ``path`` that is
            not a str or path-like).

        Examples
        --------
        >>> import tempfile
        >>> with tempfile.TemporaryDirectory() as folder:
        ...     image = OccupancyGrid.empty(width=1.0, height=1.0, resolution=0.5).save(
        ...         Path(folder) / "map.yaml")
        ...     OccupancyGrid.load(Path(folder) / "map.yaml").shape
        (2, 2)
        """
        from navkit.mapping.io import read_map

        return cls._built_as(read_map(path))

    @classmethod
    def _built_as(cls, grid: OccupancyGrid) -> OccupancyGrid:
        """``grid`` as an instance of ``cls``: itself, or rebuilt through ``cls``'s constructor.

        The functions behind :meth:`from_polygons` and :meth:`load` build an
        ``OccupancyGrid``; a user's subclass calling them got one too, where
        the other constructors (:meth:`from_occupancy`, ...) give the subclass.
        """
        if type(grid) is cls:
            return grid
        return cls(
            grid._logodds,
            resolution=grid._resolution,
            origin=grid._origin,
            occupied_thresh=grid._occupied_thresh,
            free_thresh=grid._free_thresh,
        )

    def save(self, path: str | os.PathLike[str], *, mode: MapMode = "trinary") -> Path:
        """Save as a ROS map_server map; see :func:`navkit.mapping.io.write_map`.

        Both files are written atomically (temporary file, then ``os.replace``).
        Re-saving a map in the other mode removes the previous mode's image
        once the new map is in place, but only when the replaced YAML proves it
        is that map's own image (see :func:`navkit.mapping.io.write_map`).

        Parameters
        ----------
        path : str or path-like
            YAML file to write; the image is the same name with suffix ``.pgm``
            (trinary) or ``.png`` (scale, with alpha for unknown cells; needs Pillow).
        mode : {"trinary", "scale"}, default "trinary"
            Pixel encoding of the image (keyword-only; see
            :func:`navkit.mapping.io.write_map`).

        Returns
        -------
        Path
            The path of the image written beside the YAML ``path``.

        Raises
        ------
        TypeError, ValueError, ImportError, OSError
            As :func:`navkit.mapping.io.write_map`: a ``path`` that is not a
            str or path-like, a ``mode`` that is not a str (TypeError); an
            unknown ``mode`` or a ``path`` ending in an image suffix
            (ValueError); ``"scale"`` without Pillow (ImportError); a missing
            folder (``FileNotFoundError``) or another failure to write (OSError).

        Examples
        --------
        >>> import tempfile
        >>> with tempfile.TemporaryDirectory() as folder:
        ...     OccupancyGrid.empty(width=1.0, height=1.0, resolution=0.5).save(
        ...         Path(folder) / "map.yaml").name
        'map.pgm'
        """
        from navkit.mapping.io import write_map

        return write_map(self, path, mode=mode)

    # ------------------------------------------------------------ coordinates
    @overload
    def world_to_cell(
        self, points_xy: ArrayLike, *, continuous: Literal[False] = False
    ) -> IntArray: ...

    @overload
    def world_to_cell(self, points_xy: ArrayLike, *, continuous: Literal[True]) -> FloatArray: ...

    @overload
    def world_to_cell(self, points_xy: ArrayLike, *, continuous: bool) -> IntArray | FloatArray: ...

    def world_to_cell(
        self, points_xy: ArrayLike, *, continuous: bool = False
    ) -> IntArray | FloatArray:
        """Grid coordinates ``(row, col)`` of world points ``(x, y)``.

        Parameters
        ----------
        points_xy : array_like, shape (N, 2) or (2,)
            World points, m.
        continuous : bool, default False
            False: the int64 cell containing each point. True: float continuous
            coordinates, integers at cell centres (the cell is their
            round-half-up, except within a rounding error of a cell edge:
            subtracting the half cell rounds, so a point a hair below an edge,
            e.g. at -1e-17 m, has cell -1 but continuous -0.5).

        Returns
        -------
        ndarray, shape (N, 2), or (2,) for one point given as shape (2,)
            Not clipped to the map: points outside it give indices outside
            ``[0, rows) × [0, cols)``; use :meth:`contains` to test. Points
            more than 2**62 cells away get ±2**62 (so that no int64
            overflows). Vectorised in a numba kernel (10^6 points take
            milliseconds).

        Raises
        ------
        TypeError
            Non-numeric ``points_xy``; a ``continuous`` that is not a bool.
        ValueError
            ``points_xy`` of another shape or with NaN or inf.

        Examples
        --------
        >>> grid = OccupancyGrid.empty(width=2.0, height=2.0, resolution=0.5)
        >>> grid.world_to_cell([0.6, 0.1])
        array([0, 1])
        >>> grid.world_to_cell([0.6, 0.1], continuous=True)
        array([-0.3,  0.7])
        """
        if continuous is False:
            # Fast path: one compiled call takes points_xy as it is and, if it is
            # an ndarray (no subclass) of C-contiguous (N, 2) native float64, aligned
            # or not, makes the cells as np.empty does and fills them with the
            # kernel the general path ends in; for any other object, or points not
            # all finite, it returns None and the general path below converts,
            # validates and raises (issue 17: 0.25 µs against 0.50 µs for Python's
            # type, dtype, stride and shape tests, np.empty and the kernel's entry,
            # ten points; navkit.mapping._new_cells_kernel).
            cells = _NEW_CELLS(
                points_xy, self._origin_x, self._origin_y, self._origin_yaw, self._resolution
            )
            if cells is not None:
                return cells
        if continuous is True and type(points_xy) in _ONE_PAIR_TYPES:
            # One point as plain floats: the single-point arithmetic below, without
            # the array conversion and checks (1.1 µs against 5.8 µs).
            pair = _one_pair(points_xy, False)
            if pair is not None:
                row, col = self._grid_frame(pair[0], pair[1])
                return np.array(
                    [min(max(row - 0.5, -CELL_LIMIT), CELL_LIMIT),
                     min(max(col - 0.5, -CELL_LIMIT), CELL_LIMIT)]
                )  # fmt: skip
        pts, single = as_pairs(points_xy, "points_xy")
        out: IntArray | FloatArray
        if as_bool(continuous, "continuous"):
            if pts.shape[0] == 1:
                row, col = self._grid_frame(float(pts[0, 0]), float(pts[0, 1]))
                out = np.array(
                    [[min(max(row - 0.5, -CELL_LIMIT), CELL_LIMIT),
                      min(max(col - 0.5, -CELL_LIMIT), CELL_LIMIT)]]
                )  # fmt: skip
                return one_or_many(out, single)
            # Writable too: read-only points would compile the kernel a second time
            # (0.1-0.2 s), in whichever call first passed them.
            pts = np.require(pts, np.float64, ("C", "W"))
            out = np.empty((pts.shape[0], 2), dtype=np.float64)
            world_to_continuous_kernel(
                pts, self._origin_x, self._origin_y, self._origin_yaw, self._resolution, out
            )
        else:
            out = self._cells(pts)
        return one_or_many(out, single)

    def _grid_frame(self, x: float, y: float) -> tuple[float, float]:
        """Unclamped ``(row, col)`` grid-frame coordinates of one world point, in cells.

        The arithmetic of :func:`world_to_cell_kernel`, operation for operation,
        so that one point gives the kernel's answer bit for bit.
        """
        inv_res = 1.0 / self._resolution
        c = math.cos(self._origin_yaw)
        s = math.sin(self._origin_yaw)
        dx = x - self._origin_x
        dy = y - self._origin_y
        return (-s * dx + c * dy) * inv_res, (c * dx + s * dy) * inv_res

    def _cells(self, pts: FloatArray) -> IntArray:
        """Cells of validated (N, 2) points (the numba kernel; one point in Python)."""
        if pts.shape[0] == 1:
            # One point (a start, a goal, a sensor pose) in Python, as the kernel
            # computes it: a first call then compiles no kernel (about 0.3 s).
            row, col = self._grid_frame(float(pts[0, 0]), float(pts[0, 1]))
            return np.array(
                [[math.floor(min(max(row, -CELL_LIMIT), CELL_LIMIT)),
                  math.floor(min(max(col, -CELL_LIMIT), CELL_LIMIT))]],
                dtype=np.int64,
            )  # fmt: skip
        # ascontiguousarray keeps a misaligned buffer as it is: the entry reads it.
        pts = np.ascontiguousarray(pts)
        out = np.empty((pts.shape[0], 2), dtype=np.int64)
        # The fast path's compiled entry, so that read-only points compile no
        # second signature (the points are finite float64 here: validated).
        (_CELLS_ENTRY or _cells_entry())(
            pts, self._origin_x, self._origin_y, self._origin_yaw, self._resolution, out
        )
        return out

    def cell_to_world(self, cells: ArrayLike) -> FloatArray:
        """World points ``(x, y)`` of grid coordinates ``(row, col)``.

        Parameters
        ----------
        cells : array_like, shape (N, 2) or (2,)
            Integer cells or continuous coordinates (integers at cell centres, so
            an integer cell gives its centre), within ±2**62.

        Returns
        -------
        ndarray, shape (N, 2), or (2,) for one cell given as shape (2,)
            New array of world points ``(x, y)``, m.

        Raises
        ------
        TypeError
            Non-numeric ``cells``.
        ValueError
            Another shape, NaN or inf, or cells beyond ±2**62.

        Examples
        --------
        >>> grid = OccupancyGrid.empty(width=2.0, height=2.0, resolution=0.5)
        >>> grid.cell_to_world([[0, 1], [1, 0]])
        array([[0.75, 0.25],
               [0.25, 0.75]])
        >>> grid.cell_to_world([0.5, 0.0])
        array([0.25, 0.5 ])
        """
        if (
            type(cells) is _ndarray
            and ((dtype := cells.dtype) is _FLOAT64 or dtype is _INT64)
            and cells.strides == _PAIR_STRIDES
            and (shape := cells.shape)[1] == 2
        ):
            # Fast path: C-contiguous (N, 2) float64 or int64 cells straight to the
            # compiled kernel (0.6 µs against 14 µs for 10 cells); a cell beyond
            # ±2**62, NaN or inf sends them the general way, which raises.
            out = _empty(shape, _FLOAT64)
            entry = _POINTS_ENTRIES.get(dtype) or _points_entry(dtype)
            theta = self._origin_yaw
            if entry(
                cells, self._origin_x, self._origin_y, math.cos(theta), math.sin(theta),
                self._resolution, out,
            ):  # fmt: skip
                return out
        elif type(cells) in _ONE_PAIR_TYPES:
            pair = _one_pair(cells, True)
            if (
                pair is not None
                and abs(pair[0]) <= CELL_INDEX_LIMIT
                and abs(pair[1]) <= CELL_INDEX_LIMIT
            ):
                # One cell (a path's goal, a planner's answer): the kernel's
                # arithmetic in Python floats (0.9 µs against 16 µs).
                row, col = pair
                c = math.cos(self._origin_yaw)
                s = math.sin(self._origin_yaw)
                px = (col + 0.5) * self._resolution
                py = (row + 0.5) * self._resolution
                wx = px * c - py * s + self._origin_x
                wy = px * s + py * c + self._origin_y
                if wx - wx == 0.0 and wy - wy == 0.0:
                    return np.array([wx, wy])
        arr, single = as_pairs(cells, "cells")
        check_cell_range(arr)
        local = (arr[:, ::-1] + 0.5) * self._resolution
        out = self._origin.transform_points(local)
        return one_or_many(out, single)

    def contains(self, points_xy: ArrayLike) -> BoolArray:
        """Whether each world point ``(x, y)`` lies inside the map.

        Parameters
        ----------
        points_xy : array_like, shape (N, 2) or (2,)
            World points, m.

        Returns
        -------
        ndarray of bool, shape (N,), or 0-d for one point given as shape (2,)
            True where the point's cell (:meth:`world_to_cell`) is inside
            ``[0, rows) × [0, cols)``.

        Raises
        ------
        TypeError, ValueError
            ``points_xy`` not finite real pairs.

        Examples
        --------
        >>> grid = OccupancyGrid.empty(width=2.0, height=2.0, resolution=0.5)
        >>> grid.contains([[0.5, 0.5], [2.5, 0.5]])
        array([ True, False])
        >>> bool(grid.contains([0.5, 0.5]))
        True
        """
        pts, single = as_pairs(points_xy, "points_xy")
        return one_or_many(inside(self._cells(pts), self.shape), single)

    # ------------------------------------------------------------------ views
    def probability(self) -> FloatArray:
        """Occupancy probability ``1 - 1 / (1 + exp(l))`` of every cell, shape (rows, cols).

        Returns
        -------
        ndarray, shape (rows, cols)
            New float64 array of probabilities in [0, 1] (0.5 unknown).

        Examples
        --------
        >>> OccupancyGrid.empty(width=1.0, height=0.5, resolution=0.5).probability()
        array([[0.5, 0.5]])
        """
        # In place on the one float64 array: the expression's temporaries doubled
        # the peak (review 28: 268 MB against 134 MB for 4096 x 4096 cells).
        out = self._logodds.astype(np.float64)
        np.negative(out, out=out)
        # exp(1e6) = inf gives p = 0, as it should; exp(-1e3) = 0 gives p = 1, whatever
        # the caller's np.seterr (underflow is no error here). The division too: a
        # log-odds near -709 gives a subnormal p (review 31).
        with np.errstate(over="ignore", under="ignore"):
            np.exp(out, out=out)
            np.add(out, 1.0, out=out)
            np.divide(1.0, out, out=out)
        return out

    def occupied(self, threshold: float | None = None) -> BoolArray:
        """Cells with ``p > threshold`` (default: the grid's ``occupied_thresh``).

        Parameters
        ----------
        threshold : float, optional
            Probability in [0, 1]; None uses :attr:`occupied_thresh`.

        Returns
        -------
        ndarray of bool, shape (rows, cols)
            New mask, True where the cell's occupancy probability exceeds
            ``threshold``.

        Raises
        ------
        TypeError, ValueError
            ``threshold`` not a real number in [0, 1].

        Examples
        --------
        >>> grid = OccupancyGrid.from_probabilities([[0.7, 0.9]], resolution=1.0)
        >>> grid.occupied().tolist(), grid.occupied(0.8).tolist()
        ([[True, True]], [[False, True]])
        """
        th = _threshold(threshold, self._occupied_thresh, "threshold")
        return np.asarray(self._logodds > logit_bound(th))

    def free(self, threshold: float | None = None) -> BoolArray:
        """Cells with ``p < threshold`` (default: the grid's ``free_thresh``).

        Parameters
        ----------
        threshold : float, optional
            Probability in [0, 1]; None uses :attr:`free_thresh`.

        Returns
        -------
        ndarray of bool, shape (rows, cols)
            New mask, True where the cell's occupancy probability is below
            ``threshold``.

        Raises
        ------
        TypeError, ValueError
            ``threshold`` not a real number in [0, 1].

        Examples
        --------
        >>> grid = OccupancyGrid.from_probabilities([[0.1, 0.3]], resolution=1.0)
        >>> grid.free().tolist(), grid.free(0.5).tolist()
        ([[True, False]], [[True, True]])
        """
        th = _threshold(threshold, self._free_thresh, "threshold")
        return np.asarray(self._logodds < logit_bound(th))

    def unknown(
        self, *, occupied_thresh: float | None = None, free_thresh: float | None = None
    ) -> BoolArray:
        """Cells neither occupied nor free under the given (or the grid's) thresholds.

        Parameters
        ----------
        occupied_thresh, free_thresh : float, optional
            Probabilities in [0, 1] (keyword-only); None uses the grid's
            :attr:`occupied_thresh` / :attr:`free_thresh`.

        Returns
        -------
        ndarray of bool, shape (rows, cols)
            New mask, True where ``free_thresh <= p <= occupied_thresh``.

        Raises
        ------
        TypeError
            A threshold that is not a real number.
        ValueError
            Unless ``0 <= free_thresh < occupied_thresh <= 1`` (after filling
            in the grid's own value for a threshold not given).

        Examples
        --------
        >>> grid = OccupancyGrid.from_probabilities([[0.1, 0.3, 0.5]], resolution=1.0)
        >>> grid.unknown().tolist(), grid.unknown(free_thresh=0.4).tolist()
        ([[False, True, True]], [[False, False, True]])
        """
        occ = _threshold(occupied_thresh, self._occupied_thresh, "occupied_thresh")
        free = _threshold(free_thresh, self._free_thresh, "free_thresh")
        _thresholds(occ, free, own_occupied=occupied_thresh is None, own_free=free_thresh is None)
        return ~(self._logodds > logit_bound(occ)) & ~(self._logodds < logit_bound(free))

    # --------------------------------------------------------------- inflation
    def obstacle_distance(self, *, occupied_thresh: float | None = None) -> FloatArray:
        """Distance (m) from each cell's centre to the nearest occupied cell's centre.

        The exact Euclidean distance transform of the occupied cells that
        :meth:`inflate`, :meth:`costmap` and :meth:`traversal_costs` grow
        obstacles by: 0 on an occupied cell, a multiple of ``resolution`` by
        ``sqrt(drow**2 + dcol**2)`` elsewhere, ``inf`` everywhere when no
        cell is occupied. Unknown cells are not obstacles here (pass
        ``occupied_thresh`` to count more cells as occupied).

        Parameters
        ----------
        occupied_thresh : float, optional
            Probability in [0, 1] (keyword-only): a cell is an obstacle when
            ``p > occupied_thresh``, as for :meth:`occupied`; None uses the
            grid's :attr:`occupied_thresh`.

        Returns
        -------
        ndarray of float64, shape (rows, cols)
            New array of distances, m: bit for bit
            ``scipy.ndimage.distance_transform_edt(~grid.occupied()) * grid.resolution``.

        Raises
        ------
        TypeError, ValueError
            ``occupied_thresh`` not a real number in [0, 1].

        Notes
        -----
        Memory: the result (8 bytes a cell), the occupied mask (1 byte a
        cell) and one band's work of about 2**21 cells (16 MiB) at a time:
        10.0 bytes a cell on 4096 x 4096 cells, where SciPy's transform times
        the resolution peaked at 34. A grid much wider than tall goes by bands
        of columns of its mask transposed (1 more byte a cell, and a band of
        about 32 MiB: 12.0 bytes a cell on 16 x 2**20 cells). The transform is
        a compiled kernel that lets other threads run (compiled on first use,
        then cached).

        Examples
        --------
        >>> occ = np.array([[True, False, False], [False, False, False]])
        >>> grid = OccupancyGrid.from_occupancy(occ, resolution=0.5)
        >>> grid.obstacle_distance().round(3)
        array([[0.   , 0.5  , 1.   ],
               [0.5  , 0.707, 1.118]])
        >>> OccupancyGrid.empty(width=1.0, height=0.5, resolution=0.5).obstacle_distance()
        array([[inf, inf]])
        """
        th = _threshold(occupied_thresh, self._occupied_thresh, "occupied_thresh")
        out = obstacle_distance(self.occupied(th))
        # In place: the same float64 products as SciPy's distances * resolution.
        np.multiply(out, self._resolution, out=out)
        return out

    def inflate(self, robot_radius: float) -> BoolArray:
        """Occupied cells grown by ``robot_radius``: a boolean mask, shape (rows, cols).

        A cell is in the mask when its centre lies within ``robot_radius`` (m) of
        the centre of an occupied cell (exact Euclidean distance transform): the
        cells where a robot of that inscribed radius centred there would touch an
        obstacle. Unknown cells are not obstacles here. A radius that is a whole
        number of cells reaches the cells at that distance (with 1e-9 of a cell
        of slack), also where the resolution is a float32, as in a map from a
        ROS message: 0.15 m on its 0.05000000074505806 m cells is taken as 3
        cells, as on the 0.05 m map of its YAML.

        Parameters
        ----------
        robot_radius : float
            Inflation radius, m, in [0, 1e6].

        Returns
        -------
        ndarray of bool, shape (rows, cols)
            New mask of the occupied cells and every cell whose centre lies
            within ``robot_radius`` of an occupied cell's centre.

        Raises
        ------
        TypeError, ValueError
            ``robot_radius`` not a real number in [0, 1e6].

        Examples
        --------
        >>> occ = np.zeros((5, 5), dtype=bool)
        >>> occ[2, 2] = True
        >>> OccupancyGrid.from_occupancy(occ, resolution=0.5).inflate(0.5).astype(int)
        array([[0, 0, 0, 0, 0],
               [0, 0, 1, 0, 0],
               [0, 1, 1, 1, 0],
               [0, 0, 1, 0, 0],
               [0, 0, 0, 0, 0]])
        """
        radius = bounded_float(robot_radius, "robot_radius", 0.0, RADIUS_LIMIT, "m")
        occupied = self.occupied()
        reach = reach_cells(radius, self._resolution)
        # Band by band: the peak is the mask and a band, not a float64 grid.
        out = np.empty(occupied.shape, dtype=np.bool_)
        for where, dist in obstacle_distance_bands(occupied):
            np.less_equal(dist, reach, out=out[where])
            del dist  # before the generator makes the next band: one band alive
        return out

    def cells_near(self, points_xy: ArrayLike, *, robot_radius: float) -> IntArray:
        """Cells ``(row, col)`` within ``robot_radius`` of world points' cells, as inflated.

        What :meth:`inflate` marks around an occupied cell, for the cells
        containing ``points_xy`` (LiDAR hits, say): every cell whose centre lies
        within ``robot_radius`` (m) of the centre of a point's cell, by the same
        rule and rounding as :meth:`inflate`. So ``robot_radius=0`` gives each
        point's own cell, and the cells near the hits are the cells that marking
        the hits' cells occupied and inflating would block, as the map's own
        obstacles are grown by :meth:`traversal_costs`. The result feeds
        ``FieldDStar.update_costs(cells, np.inf)`` or indexes a cost grid:
        ``costs[cells[:, 0], cells[:, 1]] = np.inf``.

        Parameters
        ----------
        points_xy : array_like, shape (N, 2) or (2,)
            World points, m; finite. Points outside the map contribute the
            cells of the map near them; empty input gives no cells.
        robot_radius : float
            Growth radius, m, in [0, 1e6] (keyword-only): the robot's
            inscribed radius, as for :meth:`inflate` and :meth:`traversal_costs`.

        Returns
        -------
        ndarray of int64, shape (K, 2)
            New array of distinct cells inside the map, sorted row-major (by
            row, then column); ``(0, 2)`` when none is near. At most the map's
            cell count (16 bytes a cell).

        Raises
        ------
        TypeError, ValueError
            ``points_xy`` not finite real pairs; ``robot_radius`` not a real
            number in [0, 1e6].

        Notes
        -----
        A cell that only overlaps the disc around a point, without its centre
        inside, is not near: the rule of inflation, so that a newly seen
        obstacle blocks the same cells as one already in the map. A point is
        first moved to its cell's centre (up to half a cell diagonal): add
        that to ``robot_radius`` for a bound on the true distance.

        Time grows with the rows of the points' discs inside the map (points
        × disc diameter) and, in each of those rows, with the columns between
        the first and last cell found there, never with a disc's area; points
        in one cell count once. Memory: the result, the points' cells and a
        row of the map. The kernel compiles on first use (about 0.35 s of CPU,
        then cached).

        Examples
        --------
        >>> grid = OccupancyGrid.empty(width=1.0, height=1.0, resolution=0.2)
        >>> grid.cells_near([0.5, 0.5], robot_radius=0.2).tolist()
        [[1, 2], [2, 1], [2, 2], [2, 3], [3, 2]]
        >>> grid.cells_near([[0.5, 0.5], [0.55, 0.45]], robot_radius=0.0).tolist()
        [[2, 2]]
        >>> grid.cells_near([-0.1, 0.5], robot_radius=0.2).tolist()  # left of the map
        [[2, 0]]

        Block the cells near new LiDAR hits for a planner and replan:

        >>> from navkit.planning import FieldDStar
        >>> room = OccupancyGrid.from_occupancy(np.zeros((10, 20), dtype=bool), resolution=0.1)
        >>> fd = FieldDStar(room.traversal_costs(), resolution=0.1, origin=room.origin)
        >>> first = fd.plan_world((0.15, 0.55), (1.85, 0.55))
        >>> hits = np.array([[1.0, 0.45], [1.0, 0.55]])
        >>> fd.update_costs(room.cells_near(hits, robot_radius=0.2), np.inf)
        >>> bool(fd.replan_world().length > first.length)
        True
        """
        pts, _ = as_pairs(points_xy, "points_xy")
        radius = bounded_float(robot_radius, "robot_radius", 0.0, RADIUS_LIMIT, "m")
        if pts.shape[0] == 0:
            return np.empty((0, 2), dtype=np.int64)
        # The inflation's reach in cells, computed as inflate() computes it.
        reach = reach_cells(radius, self._resolution)
        k = math.floor(reach)
        rows, cols = self.shape
        cells = self._cells(pts)
        # Only points whose discs reach the map, each cell once, sorted by row.
        keep = (
            (cells[:, 0] >= -k) & (cells[:, 0] < rows + k)
            & (cells[:, 1] >= -k) & (cells[:, 1] < cols + k)
        )  # fmt: skip
        cells = cells[keep]
        if cells.shape[0] == 0:
            return np.empty((0, 2), dtype=np.int64)
        cells = cells[np.lexsort((cells[:, 1], cells[:, 0]))]
        distinct = np.ones(cells.shape[0], dtype=bool)
        distinct[1:] = np.any(cells[1:] != cells[:-1], axis=1)
        cells = np.ascontiguousarray(cells[distinct])
        edges = np.zeros(cols + 1, dtype=np.int64)
        # Count, then fill an array of exactly that size: no list of every
        # disc's cells, whose size could reach points × map cells.
        out = np.empty((0, 2), dtype=np.int64)
        count = cells_near_kernel(cells, rows, cols, reach, k, edges, out, False)
        out = np.empty((count, 2), dtype=np.int64)
        if count:
            cells_near_kernel(cells, rows, cols, reach, k, edges, out, True)
        return out

    def costmap(
        self,
        *,
        robot_radius: float,
        inflation_radius: float,
        cost_scaling_factor: float = 10.0,
        inflate_unknown: bool = False,
        inflate_around_unknown: bool = False,
    ) -> NDArray[np.uint8]:
        """ROS 2 Nav2 costs of this grid; see :func:`navkit.mapping.costmap`.

        Parameters
        ----------
        robot_radius : float
            Radius of the robot's inscribed circle, m, in [0, 1e6].
        inflation_radius : float
            Distance up to which costs decay, m, in [``robot_radius``, 1e6].
        cost_scaling_factor : float, default 10.0
            Exponential decay rate, 1/m, in (0, 1e12].
        inflate_unknown : bool, default False
            Whether an unknown cell takes any inflated cost > 0 (Nav2's
            ``inflate_unknown``).
        inflate_around_unknown : bool, default False
            Whether unknown cells are inflation sources (Nav2's
            ``inflate_around_unknown``).

        Returns
        -------
        ndarray of uint8, shape (rows, cols)
            254 lethal, 253 inscribed, 0..252 decaying inflation cost, 255
            unknown.

        Raises
        ------
        TypeError, ValueError
            As :func:`navkit.mapping.costmap`.

        Examples
        --------
        >>> grid = OccupancyGrid.from_occupancy(np.array([[True, False, False]]), resolution=0.1)
        >>> grid.costmap(robot_radius=0.1, inflation_radius=0.1)
        array([[254, 253,   0]], dtype=uint8)
        """
        from navkit.mapping._costs import costmap

        return costmap(
            self,
            robot_radius=robot_radius,
            inflation_radius=inflation_radius,
            cost_scaling_factor=cost_scaling_factor,
            inflate_unknown=inflate_unknown,
            inflate_around_unknown=inflate_around_unknown,
        )

    def traversal_costs(
        self,
        *,
        robot_radius: float = 0.0,
        inflation_radius: float | None = None,
        cost_scaling_factor: float = 10.0,
        cost_weight: float = 4.0,
        unknown_cost: float = math.inf,
        inflate_unknown: bool | None = None,
    ) -> FloatArray:
        """Per-cell costs for the grid planners; see :func:`navkit.mapping.traversal_costs`.

        With the default ``inflate_unknown=None`` unknown space is inflated like
        obstacles whenever it is impassable (``unknown_cost=inf``), so the
        robot's body keeps ``robot_radius`` clear of it.

        Parameters
        ----------
        robot_radius : float, default 0.0
            Robot's inscribed radius, m, in [0, 1e6]; 0 treats it as a point.
        inflation_radius : float, optional
            Decay distance, m, in [``robot_radius``, 1e6]; defaults to
            ``robot_radius``.
        cost_scaling_factor : float, default 10.0
            Decay rate of the inflation cost, 1/m, in (0, 1e12].
        cost_weight : float, default 4.0
            Extra cost of a cell next to the inscribed zone, in [0, 1e9].
        unknown_cost : float, default inf
            Cost of unknown cells: ``inf`` (impassable) or a value in [1, 1e9].
        inflate_unknown : bool or None, default None
            Whether unknown cells count as obstacles when inflating; None means
            ``unknown_cost == inf``.

        Returns
        -------
        ndarray, shape (rows, cols)
            New float64 costs per unit length: 1 in free space, up to
            ``1 + cost_weight`` near obstacles, ``inf`` impassable (passes
            :func:`navkit.mapping.validate_costs`).

        Raises
        ------
        TypeError, ValueError
            As :func:`navkit.mapping.traversal_costs`.

        Examples
        --------
        >>> grid = OccupancyGrid.from_occupancy(np.array([[True, False, False]]), resolution=0.1)
        >>> grid.traversal_costs(robot_radius=0.1)
        array([[inf, inf,  1.]])
        """
        from navkit.mapping._costs import traversal_costs

        return traversal_costs(
            self,
            robot_radius=robot_radius,
            inflation_radius=inflation_radius,
            cost_scaling_factor=cost_scaling_factor,
            cost_weight=cost_weight,
            unknown_cost=unknown_cost,
            inflate_unknown=inflate_unknown,
        )

    # --------------------------------------------------------------- mapping
    def integrate_scan(
        self,
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
        """Ray-cast one scan into this grid in place; see :func:`navkit.mapping.integrate_scan`.

        Parameters
        ----------
        scan : LaserScan
            The scan, beam angles in the sensor frame.
        pose : Pose2D or array_like [x, y, theta]
            World pose of the sensor (m, m, rad).
        hit, miss : float
            Log-odds increments, ``hit`` in [0, 1e6] and ``miss`` in [-1e6, 0]
            (defaults OctoMap's ``logit(0.7)`` and ``logit(0.4)``).
        clamp : (float, float)
            Log-odds bounds ``low < high``, both within ±1e6.
        range_max : float, optional
            Cap on ``scan.range_max``, m (> 0).
        exact : bool, default False
            Exact grid traversal (Amanatides–Woo) instead of Bresenham lines.

        Returns
        -------
        int
            Number of cells updated.

        Other Parameters
        ----------------
        max_range : float, optional
            Deprecated name of `range_max`.

        Raises
        ------
        TypeError, ValueError
            As :func:`navkit.mapping.integrate_scan`.

        Examples
        --------
        >>> from navkit.mapping import LaserScan
        >>> grid = OccupancyGrid.empty(width=2.0, height=0.5, resolution=0.5)
        >>> scan = LaserScan([1.4], angle_min=0.0, angle_increment=0.1,
        ...                  range_min=0.1, range_max=3.0)
        >>> grid.integrate_scan(scan, (0.25, 0.25, 0.0))
        4
        >>> grid.occupied().astype(int)
        array([[0, 0, 0, 1]])
        """
        from navkit.mapping._raycast import integrate_scan

        if max_range is not None:
            # Checked here, so that its errors name the keyword the caller wrote.
            range_max = renamed_keyword("max_range", max_range, "range_max", range_max, None)
            range_max = bounded_float(range_max, "max_range", 0.0, math.inf, "m", low_open=True)
        return integrate_scan(
            self,
            scan,
            pose,
            hit=hit,
            miss=miss,
            clamp=clamp,
            range_max=range_max,
            exact=exact,
        )
