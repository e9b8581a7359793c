"""A* (and weighted A*, Dijkstra) shortest paths on cost grids."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from navkit._shared.costs import validate_costs_lowest
from navkit._shared.validation import as_bool, positive_float
from navkit.errors import NoPathError
from navkit.planning.grid._arguments import (
    check_connectivity,
    check_search_size,
    traversable_cell,
)
from navkit.planning.grid._astar_kernels import grid_search, trace_path
from navkit.planning.grid._workspace import workspace

__all__ = ["GridPath", "astar"]


@dataclass(frozen=True, eq=False)
class GridPath:
    """A path through a cost grid, as returned by :func:`astar`.

    Attributes
    ----------
    cells : ndarray of int64, shape (K, 2)
        Cells ``(row, col)`` (indexing ``costs[row, col]``) from start to goal
        inclusive; consecutive cells are neighbours. Read-only.
    cost : float
        Sum of the move costs ``step * (c_u + c_v) / 2`` along the path
        (``step`` 1 or sqrt(2)); equals the geometric length on an all-ones grid.
    expanded : int
        Number of cells the search expanded (closed).
    length : float
        Geometric length in cells: orthogonal steps count 1, diagonal sqrt(2).
    """

    cells: NDArray[np.int64]
    cost: float
    expanded: int
    length: float

    def __post_init__(self) -> None:
        self.cells.flags.writeable = False


def astar(
    costs: ArrayLike,
    start: Any,
    goal: Any,
    *,
    connectivity: int = 8,
    corner_cutting: bool = False,
    heuristic_weight: float = 1.0,
) -> GridPath:
    """Least-cost path between two cells of a cost grid (A*).

    The grid is a graph whose nodes are the traversable cells. A move between
    neighbouring cells u, v costs ``step * (c_u + c_v) / 2``, where ``step`` is 1
    for an orthogonal and sqrt(2) for a diagonal move, so an all-ones grid gives
    octile distances (the MovingAI benchmark model).

    The heuristic is the octile distance (Manhattan for ``connectivity=4``) times
    the smallest cell cost in the grid, which is admissible and consistent: each
    move changes it by at most ``step * min(costs)`` while costing at least that.
    Queue ties in f = g + h are broken towards smaller h (nearer the goal).

    Parameters
    ----------
    costs : array_like, shape (rows, cols)
        Per-cell traversal cost (per cell length): finite values >= 1 are
        traversable, ``np.inf`` is impassable. Not modified.
    start, goal : (int, int)
        Cells ``(row, col)``; both must be inside the grid and traversable.
    connectivity : {8, 4}, default 8
        8 allows diagonal moves, 4 only orthogonal ones.
    corner_cutting : bool, default False
        With False a diagonal move also needs both cells it passes beside to be
        traversable (MovingAI convention, no squeezing past obstacle corners).
        With True only its two end cells matter (scikit-image ``MCP_Geometric``).
        Ignored when ``connectivity=4``.
    heuristic_weight : float, default 1.0
        Multiplies the heuristic. 1 (or anything in [0, 1]) gives optimal paths;
        0 is Dijkstra's algorithm. A weight w > 1 is weighted A*: it usually
        expands far fewer cells and returns a path costing at most w times the
        optimum (the heuristic is consistent and no cell is expanded twice;
        Likhachev, Gordon & Thrun, "ARA*", NIPS 2003, Theorem 1).

    Returns
    -------
    GridPath
        Cells from ``start`` to ``goal`` with cost, length and expansion count.

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
        Invalid ``costs`` (see :func:`distance_field`), ``start`` or ``goal``
        outside the grid or on an impassable cell, bad ``connectivity`` or a
        negative ``heuristic_weight``.
    TypeError
        Non-integer cells, connectivity or non-bool ``corner_cutting``.
    navkit.NoPathError
        ``goal`` is unreachable from ``start``; ``explored`` holds the number of
        cells expanded.

    Examples
    --------
    >>> import numpy as np
    >>> costs = np.ones((3, 4))
    >>> costs[1, 1:3] = np.inf
    >>> path = astar(costs, (2, 0), (0, 3))
    >>> path.cells.tolist()
    [[2, 0], [2, 1], [2, 2], [2, 3], [1, 3], [0, 3]]
    >>> path.cost, path.length
    (5.0, 5.0)
    >>> round(astar(costs, (2, 0), (0, 3), corner_cutting=True).cost, 6)
    4.414214
    """
    grid, lowest = validate_costs_lowest(costs)
    check_search_size(grid)
    eight = check_connectivity(connectivity)
    cutting = as_bool(corner_cutting, "corner_cutting")
    weight = positive_float(heuristic_weight, "heuristic_weight", allow_zero=True)
    s = traversable_cell(grid, start, "start")
    t = traversable_cell(grid, goal, "goal")
    rows, cols = grid.shape
    # The smallest cost is finite because start is traversable.
    scale = weight * lowest
    goal_index = t[0] * cols + t[1]
    ws = workspace(rows * cols)
    expanded, found = grid_search(
        grid.ravel(), rows, cols, s[0] * cols + s[1], goal_index, eight, cutting, scale,
        ws.g, ws.parent, ws.mark, ws.heap, ws.pos, ws.size, ws.stamp,
    )
    if not found:
        raise NoPathError(
            f"no path from start {s} to goal {t} (explored {expanded} cells)",
            explored=expanded,
        )
    cells, length = trace_path(ws.parent, cols, goal_index)
    return GridPath(
        cells=cells, cost=float(ws.g[goal_index]), expanded=int(expanded), length=float(length)
    )
