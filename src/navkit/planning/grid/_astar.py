"""A* (and weighted A*, Dijkstra) shortest paths on cost grids: one-shot and prepared."""

from __future__ import annotations

from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from navkit._shared.types import FloatArray
from navkit._shared.validation import as_bool
from navkit.errors import NoPathError
from navkit.planning.grid._arguments import (
    check_connectivity,
    check_search_size,
    traversable_cell,
)
from navkit.planning.grid._astar_kernels import grid_search, trace_path
from navkit.planning.grid._limits import MAX_HEURISTIC_WEIGHT, bounded_float, checked_costs
from navkit.planning.grid._path import Path2D
from navkit.planning.grid._workspace import workspace

__all__ = ["AStarPlanner", "astar"]


class AStarPlanner:
    """A* on one cost grid, validated once, answering many queries.

    The constructor does every O(cells) step once: it validates the grid,
    converts it to C-contiguous float64 (integer and float32 grids included),
    and finds its smallest cost for the heuristic. :meth:`plan` and
    :meth:`distance_field` then only check their cells and run the search
    kernel, so a short query costs microseconds however large the grid (as
    tcod's ``Pathfinder`` does). A class with ``__slots__`` rather than a
    frozen dataclass because it owns a private working copy of the grid.

    The grid model and the search are those of :func:`astar`: a move between
    neighbouring traversable cells u, v costs ``step * (c_u + c_v) / 2``
    (``step`` 1 orthogonal, sqrt(2) diagonal); the heuristic is the octile
    distance (Manhattan for ``connectivity=4``) times the smallest cell cost,
    so the paths are optimal for ``heuristic_weight <= 1``.

    Parameters
    ----------
    costs : array_like, shape (rows, cols)
        Per-cell traversal cost (per cell length): finite values in
        ``[1, 1e12]`` are traversable, ``np.inf`` is impassable; at most
        ``2**31 - 1`` cells. Copied: later changes to the caller's array do not
        reach the planner.
    connectivity : {8, 4}, default 8
        8 allows diagonal moves, 4 only orthogonal ones.
    corner_cutting : bool, default False
        With False a diagonal move also needs both cells it passes beside to be
        traversable (MovingAI convention, no squeezing past obstacle corners).
        With True only its two end cells matter (scikit-image ``MCP_Geometric``).
        Ignored when ``connectivity=4``.
    heuristic_weight : float, default 1.0
        Multiplies the heuristic, in ``[0, 1e6]``. 1 (or anything in [0, 1])
        gives optimal paths; 0 is Dijkstra's algorithm. A weight w > 1 is
        weighted A*: it usually expands far fewer cells and returns a path
        costing at most w times the optimum (the heuristic is consistent and no
        cell is expanded twice; Likhachev, Gordon & Thrun, "ARA*", NIPS 2003,
        Theorem 1).

    Raises
    ------
    ValueError
        Invalid ``costs`` (see :func:`navkit.planning.distance_field`), bad
        ``connectivity`` or ``heuristic_weight`` outside ``[0, 1e6]``.
    TypeError
        Non-integer connectivity, non-bool ``corner_cutting``, non-real
        ``heuristic_weight``.

    Notes
    -----
    Queries are thread-safe: the planner is not modified by them and the
    search's scratch arrays (33 bytes per cell, see :func:`astar`) are kept per
    thread.

    Examples
    --------
    >>> import numpy as np
    >>> costs = np.ones((3, 4))
    >>> costs[1, 1:3] = np.inf
    >>> planner = AStarPlanner(costs)
    >>> planner.plan((2, 0), (0, 3)).cells.tolist()
    [[2, 0], [2, 1], [2, 2], [2, 3], [1, 3], [0, 3]]
    >>> planner.plan((0, 0), (2, 3)).cost
    5.0
    >>> planner.distance_field((0, 0))[2].tolist()
    [2.0, 3.0, 4.0, 5.0]
    """

    __slots__ = ("_costs", "_cutting", "_eight", "_flat", "_scale", "_weight")

    _costs: FloatArray
    _flat: FloatArray
    _eight: bool
    _cutting: bool
    _weight: float
    _scale: float

    def __init__(
        self,
        costs: ArrayLike,
        *,
        connectivity: int = 8,
        corner_cutting: bool = False,
        heuristic_weight: float = 1.0,
    ) -> None:
        grid, lowest = checked_costs(costs)
        # Validation converts only when needed: copy whenever the result may
        # still be (a view of) the caller's array.
        if grid is costs or grid.base is not None:
            grid = grid.copy()
        self._setup(grid, lowest, connectivity, corner_cutting, heuristic_weight)

    @classmethod
    def _borrowing(
        cls,
        grid: FloatArray,
        lowest: float,
        connectivity: Any,
        corner_cutting: Any,
        heuristic_weight: Any,
    ) -> AStarPlanner:
        """A planner on an already validated grid, without copying it.

        For the one-shot functions, whose planner lives for one query while the
        caller's array cannot change, and for owners of a private grid.
        """
        planner = cls.__new__(cls)
        planner._setup(grid, lowest, connectivity, corner_cutting, heuristic_weight)
        return planner

    def _setup(
        self,
        grid: FloatArray,
        lowest: float,
        connectivity: Any,
        corner_cutting: Any,
        heuristic_weight: Any,
    ) -> None:
        check_search_size(grid)
        self._eight = check_connectivity(connectivity)
        self._cutting = as_bool(corner_cutting, "corner_cutting")
        self._weight = bounded_float(
            heuristic_weight, "heuristic_weight", 0.0, MAX_HEURISTIC_WEIGHT
        )
        # The smallest cost is finite whenever a query can run (its start is
        # traversable), so the scale is finite then.
        self._scale = self._weight * lowest
        self._costs = grid
        self._flat = grid.ravel()

    @property
    def costs(self) -> FloatArray:
        """The validated float64 cost grid, shape (rows, cols); a read-only view."""
        view: FloatArray = self._costs.view()
        view.flags.writeable = False
        return view

    @property
    def shape(self) -> tuple[int, int]:
        """Grid shape ``(rows, cols)``."""
        rows, cols = self._costs.shape
        return int(rows), int(cols)

    @property
    def connectivity(self) -> int:
        """8 or 4."""
        return 8 if self._eight else 4

    @property
    def corner_cutting(self) -> bool:
        """Whether diagonal moves may pass beside impassable cells."""
        return self._cutting

    @property
    def heuristic_weight(self) -> float:
        """Weight of the heuristic (1 is A*, 0 Dijkstra, > 1 weighted A*)."""
        return self._weight

    def __repr__(self) -> str:
        rows, cols = self.shape
        return (
            f"AStarPlanner(<{rows}x{cols} costs>, connectivity={self.connectivity}, "
            f"corner_cutting={self._cutting}, heuristic_weight={self._weight})"
        )

    def plan(self, start_cell: Any, goal_cell: Any) -> Path2D:
        """Least-cost path between two cells.

        Parameters
        ----------
        start_cell, goal_cell : (int, int)
            Cells ``(row, col)``; both inside the grid and traversable.

        Returns
        -------
        Path2D
            ``"grid"`` path through the cell centres from ``start_cell`` to
            ``goal_cell`` (:attr:`Path2D.cells` gives them as integers), its
            cost (sum of the move costs), length in cells (orthogonal steps 1,
            diagonal sqrt(2)) and the number of cells expanded.

        Raises
        ------
        ValueError
            A cell outside the grid or on an impassable cell.
        TypeError
            Non-integer cells.
        navkit.NoPathError
            ``goal_cell`` is unreachable from ``start_cell``; ``expanded`` holds
            the number of cells expanded.
        """
        grid = self._costs
        s = traversable_cell(grid, start_cell, "start_cell")
        t = traversable_cell(grid, goal_cell, "goal_cell")
        rows, cols = grid.shape
        goal_index = t[0] * cols + t[1]
        g, parent, mark, heap, pos, size, stamp = workspace(rows * cols)
        expanded, found = grid_search(
            self._flat, rows, cols, s[0] * cols + s[1], goal_index, self._eight, self._cutting,
            self._scale, g, parent, mark, heap, pos, size, stamp,
        )
        if not found:
            raise NoPathError(
                f"no path from start_cell {s} to goal_cell {t} (expanded {expanded} cells)",
                expanded=expanded,
            )
        cells, length = trace_path(parent, cols, goal_index)
        # trace_path's array is new and only ours: hand it over without a copy.
        return Path2D._owned(
            cells.astype(np.float64), "grid", float(g[goal_index]), length, expanded
        )

    def distance_field(self, goal_cell: Any) -> FloatArray:
        """Least cost from every cell to ``goal_cell`` (Dijkstra to exhaustion).

        Ignores ``heuristic_weight``; see :func:`navkit.planning.distance_field`.

        Parameters
        ----------
        goal_cell : (int, int)
            Goal cell ``(row, col)``; inside the grid and traversable.

        Returns
        -------
        ndarray of float64, shape (rows, cols)
            Cost-to-go of each cell; 0 at the goal and ``np.inf`` where the goal
            is unreachable (including impassable cells).
        """
        grid = self._costs
        t = traversable_cell(grid, goal_cell, "goal_cell")
        rows, cols = grid.shape
        n = rows * cols
        g, parent, mark, heap, pos, size, stamp = workspace(n)
        grid_search(
            self._flat, rows, cols, t[0] * cols + t[1], -1, self._eight, self._cutting, 0.0,
            g, parent, mark, heap, pos, size, stamp,
        )
        # Exhaustion closes every reachable cell; g is stale everywhere else.
        closed = mark[:n] == stamp + 1
        out: FloatArray = np.where(closed, g[:n], np.inf).reshape(rows, cols)
        return out


def astar(
    costs: ArrayLike,
    start_cell: Any,
    goal_cell: Any,
    *,
    connectivity: int = 8,
    corner_cutting: bool = False,
    heuristic_weight: float = 1.0,
) -> Path2D:
    """Least-cost path between two cells of a cost grid (A*), one-shot.

    The grid is a graph whose nodes are the traversable cells. A move between
    neighbouring cells u, v costs ``step * (c_u + c_v) / 2``, where ``step`` is 1
    for an orthogonal and sqrt(2) for a diagonal move, so an all-ones grid gives
    octile distances (the MovingAI benchmark model).

    The heuristic is the octile distance (Manhattan for ``connectivity=4``) times
    the smallest cell cost in the grid, which is admissible and consistent: each
    move changes it by at most ``step * min(costs)`` while costing at least that.
    Queue ties in f = g + h are broken towards smaller h (nearer the goal).

    Every call validates the whole grid (O(cells)); for many queries on one
    grid build an :class:`AStarPlanner` once, which gives the same answers.

    Parameters
    ----------
    costs : array_like, shape (rows, cols)
        Per-cell traversal cost (per cell length): finite values in
        ``[1, 1e12]`` are traversable, ``np.inf`` is impassable; at most
        ``2**31 - 1`` cells. Not modified.
    start_cell, goal_cell : (int, int)
        Cells ``(row, col)``; both must be inside the grid and traversable.
    connectivity : {8, 4}, default 8
        8 allows diagonal moves, 4 only orthogonal ones.
    corner_cutting : bool, default False
        As in :class:`AStarPlanner`.
    heuristic_weight : float, default 1.0
        As in :class:`AStarPlanner`, in ``[0, 1e6]``: 1 is A*, 0 Dijkstra,
        w > 1 weighted A* (path cost at most w times the optimum).

    Returns
    -------
    Path2D
        ``"grid"`` path through the cell centres from ``start_cell`` to
        ``goal_cell`` (:attr:`Path2D.cells` gives them as integers) with cost,
        length in cells and expansion count.

    Notes
    -----
    The search runs in a numba kernel over flat arrays with an indexed 4-ary
    heap (:mod:`navkit.planning.grid._search_heap`); memory is O(cells). Its scratch
    arrays (33 bytes per cell) are kept per thread and reused by later calls on
    grids of the same or smaller size, so repeated queries pay no allocation.
    Grids may have at most 2**31 - 1 cells. Ties among equal f are broken by the
    heuristic (to 1/16 cell), then by cell index, so results are deterministic.

    Raises
    ------
    ValueError
        Invalid ``costs`` (see :func:`navkit.planning.distance_field`), ``start_cell`` or
        ``goal_cell`` outside the grid or on an impassable cell, bad
        ``connectivity`` or ``heuristic_weight`` outside ``[0, 1e6]``.
    TypeError
        Cells that are not pairs of integers (booleans, mappings and strings
        included); non-integer connectivity; non-bool ``corner_cutting``.
    navkit.NoPathError
        ``goal_cell`` is unreachable from ``start_cell``; ``expanded`` holds the
        number of cells expanded.

    Examples
    --------
    >>> import numpy as np
    >>> costs = np.ones((3, 4))
    >>> costs[1, 1:3] = np.inf
    >>> path = astar(costs, (2, 0), (0, 3))
    >>> path.cells.tolist()
    [[2, 0], [2, 1], [2, 2], [2, 3], [1, 3], [0, 3]]
    >>> path.frame, path.cost, path.length
    ('grid', 5.0, 5.0)
    >>> round(astar(costs, (2, 0), (0, 3), corner_cutting=True).cost, 6)
    4.414214
    """
    grid, lowest = checked_costs(costs)
    planner = AStarPlanner._borrowing(
        grid, lowest, connectivity, corner_cutting, heuristic_weight
    )
    return planner.plan(start_cell, goal_cell)

