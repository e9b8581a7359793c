"""The one path result of every navkit planner: :class:`Path2D`."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, Literal

import numpy as np
from numpy.typing import ArrayLike

from navkit._shared.frozen import frozen_setattr, reduce_record, restore_read_only
from navkit._shared.grid_coords import round_half_up
from navkit._shared.text import as_text
from navkit._shared.types import FloatArray, IntArray
from navkit._shared.validation import as_float_array, bounded_int, finite_float
from navkit.mapping import LocalGrid, OccupancyGrid
from navkit.planning.grid._limits import COORDINATE_LIMIT, check_range

__all__ = ["Path2D", "grid_to_world", "polyline_length"]

_FRAMES = ("grid", "world")
_INT64_MAX = 2**63 - 1
# Grid coordinates a map converts (as OccupancyGrid.cell_to_world: their world
# points could overflow beyond).
_CELL_LIMIT = float(2**62)


@frozen_setattr
@dataclass(frozen=True, slots=True, eq=False)
class Path2D:
    """A polyline path with its cost, as returned by every planner.

    One type for every planner; ``frame`` says what the points are:

    * ``"grid"``: continuous grid coordinates ``(row, col)`` with integers at
      cell centres (cell ``(r, c)`` covers ``[r-½, r+½) × [c-½, c+½)``). A* paths
      run through cell centres (integer points, see :attr:`cells`); Field D*
      paths through node − 0.5 and points on cell edges.
    * ``"world"``: world points ``(x, y)`` in metres.

    :meth:`to_world` and :meth:`to_grid` convert between the two on a map; a
    world path they return lies within ±1e9 m, the range of every world
    input (theirs and the trackers' included). They return a plain
    :class:`Path2D`, a subclass's too, as ``str`` methods return a ``str``:
    its own attributes may hold quantities of its frame (a tolerance in
    cells, say) that navkit cannot convert, so a subclass that wants itself
    back overrides them. Copies and pickles keep the subclass whole.

    Parameters
    ----------
    points : array_like, shape (K, 2)
        Vertices from start to goal (K >= 1), finite. Stored as a read-only
        float64 copy: the caller's array is neither kept nor frozen.
    frame : {"grid", "world"}
        Frame of ``points``.
    cost : float
        Path cost, finite, >= 0: traversal cost × cells for a ``"grid"``
        path, × metres for a ``"world"`` one (so it equals :attr:`length` in
        free space). Planners never return an infinite cost (no path is
        :class:`navkit.NoPathError`).
    length : float
        Length of the polyline: cells (``"grid"``) or metres (``"world"``),
        finite, >= 0. A ``"world"`` path navkit returns
        (:meth:`MapPlanner.plan`, :meth:`FieldDStar.plan_world` and
        ``replan_world``, :meth:`to_world`) holds the length of its own
        points, the sum of ``np.hypot`` of their differences as NumPy sums
        it, whatever the planner summed; a planner's ``"grid"`` path the
        length its search summed, equal to its points' up to that rounding
        (:meth:`to_grid` sums its points').
    expanded : int
        Number of search expansions the planner performed, in ``[0, 2**63 - 1]``.

    Raises
    ------
    ValueError
        Bad shape, non-finite points, unknown frame, a cost or length that is
        negative or not finite, expansions out of range.
    TypeError
        Non-numeric points (strings, complex numbers, booleans), a frame that
        is not a string, a cost or length that is not a real number (or is a
        bool), non-integer ``expanded``.

    Examples
    --------
    >>> path = Path2D([[0, 0], [1, 1], [1, 2]], "grid", cost=2.414, length=2.414, expanded=3)
    >>> path.cells.tolist()
    [[0, 0], [1, 1], [1, 2]]
    >>> path.points.flags.writeable
    False
    """

    points: FloatArray
    frame: Literal["grid", "world"]
    cost: float
    length: float
    expanded: int

    if TYPE_CHECKING:
        # The generated ``__init__`` takes the arrays as array_like (``__post_init__``
        # converts them); this signature tells type checkers so, at no runtime cost.
        def __init__(
            self,
            points: ArrayLike,
            frame: Literal["grid", "world"],
            cost: float,
            length: float,
            expanded: int,
        ) -> None: ...

    def __post_init__(self) -> None:
        pts = np.array(as_float_array(self.points, "points", shape=(None, 2)), copy=True)
        if pts.shape[0] == 0:
            raise ValueError("points must hold at least one vertex, got shape (0, 2)")
        pts.flags.writeable = False
        frame: Any = self.frame
        if not isinstance(frame, str):
            raise TypeError(f"frame must be 'grid' or 'world', got {type(frame).__name__}")
        # Plain str: an np.str_ printed as np.str_('grid') in the record's repr. Checked
        # as stored: a subclass's own == (case-blind, say) let "GRID" through.
        frame = as_text(frame, "frame")
        if frame not in _FRAMES:
            raise ValueError(f"frame must be 'grid' or 'world', got {frame!r}")
        object.__setattr__(self, "frame", frame)
        cost = _non_negative(self.cost, "cost")
        length = _non_negative(self.length, "length")
        expanded = bounded_int(self.expanded, "expanded", 0, _INT64_MAX)
        object.__setattr__(self, "points", pts)
        object.__setattr__(self, "cost", cost)
        object.__setattr__(self, "length", length)
        object.__setattr__(self, "expanded", expanded)

    @classmethod
    def _owned(
        cls,
        points: FloatArray,
        frame: Literal["grid", "world"],
        cost: float,
        length: float,
        expanded: int,
    ) -> Path2D:
        """A path on a fresh float64 (K, 2) array the planner built and hands over.

        Skips the checks and the copy of ``__post_init__`` (which cost more than
        a short prepared A* query itself); only for arrays nobody else refers to,
        which are made read-only here. Every field must already be valid.
        """
        path = object.__new__(cls)
        points.flags.writeable = False
        object.__setattr__(path, "points", points)
        object.__setattr__(path, "frame", frame)
        object.__setattr__(path, "cost", float(cost))
        object.__setattr__(path, "length", float(length))
        object.__setattr__(path, "expanded", int(expanded))
        return path

    def __reduce__(self) -> tuple[Any, ...]:
        """Copy and pickle support: the arrays read-only again, also in subclasses' copies."""
        return reduce_record(self, ("points",))

    def __setstate__(self, state: list[Any]) -> None:
        """Restore from an older pickle, ``points`` read-only again."""
        restore_read_only(self, state, ("points",))

    def to_world(self, grid: OccupancyGrid | LocalGrid) -> Path2D:
        """This ``"grid"`` path as a ``"world"`` one, on the map whose cells it is in.

        What :class:`MapPlanner` does with the path its cell planner returns:
        the points through ``grid.cell_to_world``, the cost times
        ``grid.resolution`` and the length of the world polyline, so a grid
        path planned on a map's costs between two cell centres converts to
        the world path :meth:`MapPlanner.plan` returns between those centres,
        bit for bit. ``expanded`` is kept.

        Parameters
        ----------
        grid : OccupancyGrid or LocalGrid
            The map whose cells the path's points are in (whose
            ``traversal_costs`` it was planned on). For a
            :class:`~navkit.mapping.LocalGrid` the world points are in the
            robot's frame, as its ``cell_to_world`` gives them.

        Returns
        -------
        Path2D
            A new ``"world"`` path (a plain :class:`Path2D`, for a subclass
            too): points ``(x, y)`` in m, cost in cost units × m, length in m.

        Raises
        ------
        TypeError
            ``grid`` is not an :class:`~navkit.mapping.OccupancyGrid` or a
            :class:`~navkit.mapping.LocalGrid`.
        ValueError
            The path is already in the ``"world"`` frame; its world points
            beyond ``±1e9`` m, the range :meth:`to_grid`, the trackers and
            every world input take (a point far outside the grid; points
            beyond ``±2**62`` cells are refused as such); its cost
            overflowing float64 once scaled.

        Examples
        --------
        >>> import numpy as np
        >>> from navkit.mapping import OccupancyGrid
        >>> from navkit.planning import astar
        >>> grid = OccupancyGrid.from_occupancy(np.zeros((4, 6), dtype=bool), resolution=0.5)
        >>> cells = astar(grid.traversal_costs(), (0, 0), (0, 3))
        >>> world = cells.to_world(grid)
        >>> world.frame, world.points[[0, -1]].tolist(), world.cost, world.length
        ('world', [[0.25, 0.25], [1.75, 0.25]], 1.5, 1.5)
        """
        _check_frame(self, "grid", "to_world")
        checked = _map_of(grid)
        check_range(self.points, _CELL_LIMIT, "points", "cells")
        points, cost = grid_to_world(self.points, self.cost, checked)
        # A world path navkit takes back: to_grid and the trackers refuse points
        # beyond ±1e9 m, which 2**62 cells reached (4.6e17 m at 0.1 m; review 54, FOUND7).
        if not float(np.abs(points).max()) <= COORDINATE_LIMIT:
            worst = float(points.reshape(-1)[int(np.argmax(np.abs(points)))])
            raise ValueError(
                f"points must map to world points within ±{COORDINATE_LIMIT:g} m (the range "
                f"to_grid and the trackers take), got a coordinate of {worst!r} m"
            )
        return Path2D(
            points, "world", cost=cost, length=polyline_length(points), expanded=self.expanded
        )

    def to_grid(self, grid: OccupancyGrid | LocalGrid) -> Path2D:
        """This ``"world"`` path as a ``"grid"`` one, on the map it runs through.

        The inverse of :meth:`to_world`: the points through
        ``grid.world_to_cell(..., continuous=True)`` (integers at cell
        centres), the cost divided by ``grid.resolution`` and the length of
        the grid polyline, in cells. Then :attr:`cells` gives the cell of each
        vertex. Paths whose links start or end off the cell centres (from
        :meth:`MapPlanner.plan`) keep them: the points are converted, not
        snapped to cells. ``expanded`` is kept.

        Parameters
        ----------
        grid : OccupancyGrid or LocalGrid
            The map the path runs through (robot-frame points for a
            :class:`~navkit.mapping.LocalGrid`).

        Returns
        -------
        Path2D
            A new ``"grid"`` path (a plain :class:`Path2D`, for a subclass
            too): continuous ``(row, col)``, cost in cost units × cells,
            length in cells.

        Raises
        ------
        TypeError
            ``grid`` is not an :class:`~navkit.mapping.OccupancyGrid` or a
            :class:`~navkit.mapping.LocalGrid`.
        ValueError
            The path is already in the ``"grid"`` frame; its points beyond
            ``±1e9`` m; its cost overflowing float64 once scaled.

        Examples
        --------
        >>> from navkit.mapping import OccupancyGrid
        >>> grid = OccupancyGrid.empty(width=3.0, height=2.0, resolution=0.5)
        >>> world = Path2D([[0.25, 0.25], [1.75, 0.25]], "world", cost=1.5, length=1.5, expanded=4)
        >>> cells = world.to_grid(grid)
        >>> cells.cells.tolist(), cells.cost, cells.length
        ([[0, 0], [0, 3]], 3.0, 3.0)
        """
        _check_frame(self, "world", "to_grid")
        checked = _map_of(grid)
        check_range(self.points, COORDINATE_LIMIT, "points", "m")
        points = np.asarray(
            checked.world_to_cell(self.points, continuous=True), dtype=np.float64
        ).reshape(-1, 2)
        # Divided, not times 1 / resolution (whose rounding came on top): a cost
        # 0.1 m made 8.1585 came back 81.58500000000001 (review 53, FRESH3).
        cost = _scaled(self.cost, checked.resolution, divide=True)
        return Path2D(
            points, "grid", cost=cost, length=polyline_length(points), expanded=self.expanded
        )

    @property
    def cells(self) -> IntArray:
        """Cell ``(row, col)`` containing each vertex, int64 (K, 2), read-only.

        Only for a ``"grid"`` path: each coordinate is rounded half up
        (``floor(v + 0.5)``), the cell whose square ``[r-½, r+½) × [c-½, c+½)``
        holds the vertex. For an A* path these are exactly its cells. A
        coordinate beyond ``±2**62`` (far outside every grid) gives ``±2**62``,
        not its own cell, which int64 cannot always hold.

        Raises
        ------
        ValueError
            The path is in the ``"world"`` frame.
        """
        if self.frame != "grid":
            raise ValueError(
                "cells is defined for 'grid' paths only; this path is in the 'world' frame "
                "(path.to_grid(grid).cells gives the cells of its points on that map)"
            )
        out: IntArray = round_half_up(self.points)
        out.flags.writeable = False
        return out


def _non_negative(value: Any, name: str) -> float:
    """A finite real number >= 0 as a float; bools, strings, NaN and infinities refused."""
    out = finite_float(value, name)
    if out < 0.0:
        raise ValueError(f"{name} must be >= 0, got {out}")
    return out


def grid_to_world(
    points: FloatArray, cost: float, grid: OccupancyGrid | LocalGrid
) -> tuple[FloatArray, float]:
    """World points and cost of a grid path's points and cost on ``grid``.

    The one conversion of :meth:`Path2D.to_world` and :meth:`MapPlanner.plan`:
    ``grid.cell_to_world`` of the points (a new (K, 2) float64 array) and the
    cost times the resolution (refused if that overflows).
    """
    world = np.asarray(grid.cell_to_world(points), dtype=np.float64).reshape(-1, 2)
    return world, _scaled(cost, grid.resolution)


def polyline_length(points: FloatArray) -> float:
    """Length of the polyline through ``points`` (K, 2), in their unit: the sum of its legs."""
    return float(np.hypot(*np.diff(points, axis=0).T).sum())


def _scaled(cost: float, factor: float, *, divide: bool = False) -> float:
    out = cost / factor if divide else cost * factor
    if not math.isfinite(out):
        how = "divided by" if divide else "multiplied by"
        raise ValueError(f"the path's cost {cost!r} overflows float64 {how} {factor!r}")
    return out


def _check_frame(path: Path2D, frame: str, method: str) -> None:
    if path.frame != frame:
        raise ValueError(
            f"{method} converts a {frame!r} path; this path is already in the {path.frame!r} frame"
        )


def _map_of(grid: Any) -> OccupancyGrid | LocalGrid:
    if not isinstance(grid, (OccupancyGrid, LocalGrid)):
        raise TypeError(
            f"grid must be an OccupancyGrid or a LocalGrid (the map whose cells the path is "
            f"in), got {type(grid).__name__}"
        )
    return grid
