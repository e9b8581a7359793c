"""The robot-centred local occupancy grid of the TurtleBot3 obstacle-avoidance paper."""

from __future__ import annotations

import math
from dataclasses import KW_ONLY, dataclass
from typing import TYPE_CHECKING, Any, Literal, overload

import numpy as np
from numpy.typing import ArrayLike

from navkit._shared.float32 import length_in_cells
from navkit._shared.frozen import frozen_setattr, reduce_record, restore_read_only
from navkit._shared.grid_coords import as_pairs, inside, one_or_many, round_half_up
from navkit._shared.types import BoolArray, FloatArray, IntArray
from navkit._shared.validation import as_array, as_bool, as_points
from navkit.mapping._limits import (
    CELL_INDEX_LIMIT,
    RADIUS_LIMIT,
    bounded_float,
    check_cell_count,
    check_cell_range,
    resolution_float,
)

__all__ = ["LocalGrid"]

# Relative rounding of ``half_width / resolution`` for a half width given as a
# decimal multiple of half a cell (two roundings of half an ulp, a factor 4 to spare).
_HALF_ULPS = 4.0 * 2.0**-52


@frozen_setattr
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

    The conversions have the names of :class:`~navkit.mapping.OccupancyGrid`'s;
    here the "world" of :meth:`world_to_cell` and :meth:`cell_to_world` is the
    robot frame. Continuous coordinates put integers at cell centres, as there.

    Parameters
    ----------
    occupied : array_like of bool, shape (n, n)
        True where at least one obstacle point falls in the cell; ``n`` is odd.
        Stored as a read-only copy (the caller's array is neither kept nor
        frozen).
    resolution : float
        Cell size in metres, in [1e-6, 1e6].
    half_width : float
        Distance in metres from the robot to the centre of the outermost cells;
        must equal ``(n - 1) / 2 * resolution``.

    Raises
    ------
    TypeError
        ``occupied`` is not boolean; a number is not a real number.
    ValueError
        ``occupied`` not square with an odd side, a number outside its range
        or inconsistent with the shape.

    Examples
    --------
    >>> grid = LocalGrid.from_points([[0.5, -0.2]], half_width=1.0, resolution=0.1)
    >>> grid.occupied.shape
    (21, 21)
    >>> grid.world_to_cell([0.5, -0.2])
    array([ 8, 15])
    >>> bool(grid.occupied[8, 15])
    True
    >>> grid.cell_to_world([10, 10])
    array([0., 0.])
    """

    occupied: BoolArray
    _: KW_ONLY
    resolution: float
    half_width: float

    if TYPE_CHECKING:
        # The generated ``__init__`` takes ``occupied`` as array_like (``__post_init__``
        # converts it); this signature tells type checkers so, at no runtime cost.
        def __init__(
            self, occupied: ArrayLike, *, resolution: float, half_width: float
        ) -> None: ...

    def __post_init__(self) -> None:
        occ = np.array(as_array(self.occupied, "occupied"), copy=True)
        if occ.dtype != np.bool_:
            raise TypeError(f"occupied must be a boolean array, got dtype {occ.dtype}")
        if occ.ndim != 2 or occ.shape[0] != occ.shape[1] or occ.shape[0] % 2 == 0:
            raise ValueError(f"occupied must be a square (n, n) array with n odd, got {occ.shape}")
        res = resolution_float(self.resolution)
        half = bounded_float(self.half_width, "half_width", 0.0, RADIUS_LIMIT, "m")
        half_cells = (occ.shape[0] - 1) // 2
        if not math.isclose(half, half_cells * res, rel_tol=1e-9, abs_tol=1e-12):
            raise ValueError(
                f"half_width must be (n - 1) / 2 * resolution = {half_cells * res} for an "
                f"{occ.shape[0]} x {occ.shape[0]} grid, got {half}"
            )
        occ.flags.writeable = False
        object.__setattr__(self, "occupied", occ)
        object.__setattr__(self, "resolution", res)
        object.__setattr__(self, "half_width", half)

    def __reduce__(self) -> tuple[Any, ...]:
        """Copy and pickle support: the arrays read-only again, also in subclasses' copies."""
        return reduce_record(self, ("occupied",))

    def __setstate__(self, state: list[Any]) -> None:
        """Restore from an older pickle, the arrays read-only again."""
        restore_read_only(self, state, ("occupied",))

    @property
    def size(self) -> int:
        """Number of cells ``n`` along each side.

        Examples
        --------
        >>> LocalGrid.from_points([], half_width=0.2, resolution=0.1).size
        5
        """
        return int(self.occupied.shape[0])

    @classmethod
    def from_points(
        cls, points_xy: ArrayLike, *, half_width: float = 1.0, resolution: float = 0.1
    ) -> LocalGrid:
        """Grid with the cells of the given robot-frame points set.

        Parameters
        ----------
        points_xy : array_like, shape (N, 2) or (2,)
            Obstacle points ``(x, y)`` in metres in the robot frame; points outside
            the grid are ignored.
        half_width : float, default 1.0
            Half the side of the grid in metres, in [0, 1e6]. It is snapped to
            the nearest multiple of ``resolution`` (halfway rounds up, as
            cells do) so that the robot sits on a cell centre.
        resolution : float, default 0.1
            Cell size in metres, in [1e-6, 1e6].

        Returns
        -------
        LocalGrid
            A grid of ``n = 2 * k + 1`` cells per side, ``k`` being
            ``half_width / resolution`` rounded half up (a ratio within 1e-9
            cells of a half counts as a half, so a decimal 0.15 m at 0.1 m
            gives 2), with ``half_width`` snapped to ``k * resolution``. A
            float32 ``resolution`` (as a ROS message carries it) counts ``k``
            in cells of the decimal it stands for: 0.25 m at
            ``float(np.float32(0.1))`` gives 3, as at 0.1 (a ``half_width``
            of whole or half cells of the float32 itself, ``2.5 *
            resolution``, in those: 3).

        Raises
        ------
        TypeError
            Non-numeric ``points_xy``; ``half_width`` or ``resolution`` not a
            real number (a bool included).
        ValueError
            ``points_xy`` of another shape or with NaN or inf, a number outside
            its range, or a grid of more than ``2**28`` cells (``2 * k + 1``
            per side; the message says how many it would need). Nothing is
            allocated then.

        Examples
        --------
        >>> grid = LocalGrid.from_points([[0.1, 0.0], [5.0, 0.0]], half_width=0.2)
        >>> grid.occupied.astype(int)
        array([[0, 0, 0, 0, 0],
               [0, 0, 0, 0, 0],
               [0, 0, 0, 1, 0],
               [0, 0, 0, 0, 0],
               [0, 0, 0, 0, 0]])
        """
        res = resolution_float(resolution)
        half = bounded_float(half_width, "half_width", 0.0, RADIUS_LIMIT, "m")
        # Half up, as cells round: round() goes to even, so 1.5 and 2.5 cells
        # both gave 2 and half a cell gave none. At most 1e12: exact in a float.
        # A ratio within 1e-9 cells (or its float rounding) of halfway counts as
        # halfway: 0.15 / 0.1 is 1.4999999999999998, and 0.15 m must round up
        # as 0.25 m (2.5 cells) does.
        # In cells of the decimal a float32 resolution stands for: 0.25 m is 2.4999999627
        # cells of float32 0.1 and gave 2 (review 53); but whole or half cells of the
        # float32 itself in those: 2.5 times float32 0.01 gave 2 (review 54).
        ratio = length_in_cells(half, res, halves=True)
        half_cells = math.floor(ratio)
        if ratio - half_cells >= 0.5 - (1e-9 + _HALF_ULPS * ratio):
            half_cells += 1
        side = 2.0 * half_cells + 1.0  # a float: compared before any allocation
        check_cell_count(
            side * side,
            f"a local grid of half_width {half:g} m at resolution {res:g} m",
            bytes_per_cell=1,
            dtype="bool",
        )
        pts = as_points(points_xy, "points_xy")
        n = 2 * half_cells + 1
        occ = np.zeros((n, n), dtype=np.bool_)
        snapped = half_cells * res
        with np.errstate(over="ignore"):  # far points become ±inf and are dropped next
            scaled = (pts[:, ::-1] + snapped) / res
        # Cells are kept by comparing floats, so far points never reach an int cast.
        keep = np.all((scaled >= -0.5) & (scaled < n - 0.5), axis=1)
        cells = round_half_up(scaled[keep])
        occ[cells[:, 0], cells[:, 1]] = True
        return cls(occ, resolution=res, half_width=snapped)

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
        """Grid coordinates ``(row i, col j)`` of robot-frame points ``(x, y)``.

        Parameters
        ----------
        points_xy : array_like, shape (N, 2) or (2,)
            Points in metres in the robot frame (this grid's "world").
        continuous : bool, default False
            False: the int64 cell of each point (round half up). True: float
            continuous coordinates, integers at cell centres.

        Returns
        -------
        ndarray, shape (N, 2), or (2,) for one point given as shape (2,)
            Not clipped to the grid: points outside it fall outside ``[0, n)``
            (use :meth:`contains` to test); points more than 2**62 cells away
            get ±2**62.

        Raises
        ------
        TypeError
            Non-numeric ``points_xy``; a ``continuous`` that is not a bool.
        ValueError
            ``points_xy`` of another shape or with NaN or inf.

        Examples
        --------
        >>> grid = LocalGrid.from_points([])
        >>> grid.world_to_cell([[0.0, 0.0], [0.26, -0.5]])
        array([[10, 10],
               [ 5, 13]])
        >>> grid.world_to_cell([0.26, -0.5], continuous=True).round(12)
        array([ 5. , 12.6])
        """
        pts, single = as_pairs(points_xy, "points_xy")
        with np.errstate(over="ignore"):  # overflow to ±inf is clamped next
            scaled = (pts[:, ::-1] + self.half_width) / self.resolution
        np.clip(scaled, -CELL_INDEX_LIMIT, CELL_INDEX_LIMIT, out=scaled)
        out = scaled if as_bool(continuous, "continuous") else round_half_up(scaled)
        return one_or_many(out, single)

    def cell_to_world(self, cells: ArrayLike) -> FloatArray:
        """Robot-frame points ``(x, y)`` in metres of grid coordinates ``(row, col)``.

        Parameters
        ----------
        cells : array_like, shape (N, 2) or (2,)
            Grid coordinates ``(row, col)``: integer cells give their centres;
            continuous coordinates (integers at cell centres, within ±2**62) are
            accepted.

        Returns
        -------
        ndarray, shape (N, 2), or (2,) for one cell given as shape (2,)
            New array of robot-frame points ``(x, y)``, metres. Cells outside
            the grid are converted too.

        Raises
        ------
        TypeError, ValueError
            ``cells`` not finite real pairs, or beyond ±2**62.

        Examples
        --------
        >>> grid = LocalGrid.from_points([])
        >>> grid.cell_to_world([[10, 15], [3, 10]])
        array([[ 0.5,  0. ],
               [ 0. , -0.7]])
        >>> grid.cell_to_world([10.5, 10.0])
        array([0.  , 0.05])
        """
        arr, single = as_pairs(cells, "cells")
        check_cell_range(arr)
        out = arr[:, ::-1] * self.resolution - self.half_width
        return one_or_many(out, single)

    def contains(self, points_xy: ArrayLike) -> BoolArray:
        """Whether each robot-frame point ``(x, y)`` falls in a cell of the grid.

        Parameters
        ----------
        points_xy : array_like, shape (N, 2) or (2,)
            Points ``(x, y)`` in metres in the robot frame.

        Returns
        -------
        ndarray of bool, shape (N,), or 0-d for one point given as shape (2,)
            True where the point's cell (:meth:`world_to_cell`) is inside the
            ``n × n`` grid.

        Raises
        ------
        TypeError, ValueError
            ``points_xy`` not finite real pairs.

        Examples
        --------
        >>> grid = LocalGrid.from_points([])
        >>> grid.contains([[0.0, 1.04], [0.0, 1.06]])
        array([ True, False])
        >>> bool(grid.contains([0.0, 0.0]))
        True
        """
        pts, single = as_pairs(points_xy, "points_xy")
        cells = self.world_to_cell(pts)
        return one_or_many(inside(cells, (self.size, self.size)), single)
