"""Exact cost-to-go fields on cost grids (Dijkstra to exhaustion)."""

from __future__ import annotations

from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from navkit._shared.costs import validate_costs
from navkit._shared.validation import as_bool
from navkit.planning.grid._arguments import (
    check_connectivity,
    check_search_size,
    traversable_cell,
)
from navkit.planning.grid._astar_kernels import grid_search
from navkit.planning.grid._workspace import workspace

__all__ = ["distance_field"]


def distance_field(
    costs: ArrayLike,
    goal: Any,
    *,
    connectivity: int = 8,
    corner_cutting: bool = False,
) -> NDArray[np.float64]:
    """Least cost from every cell to ``goal`` (a navigation function).

    Runs the search kernel of :func:`astar` with a zero heuristic from ``goal``
    until every reachable cell is expanded. Move costs are symmetric
    (``step * (c_u + c_v) / 2``), so the cost from the goal to a cell is that
    cell's cost-to-go.

    Parameters
    ----------
    costs : array_like, shape (rows, cols)
        Per-cell traversal cost: finite values >= 1 traversable, ``np.inf``
        impassable. Integer or float dtype; NaN, values below 1, booleans,
        empty arrays or other dimensions raise ``ValueError``. Not modified.
    goal : (int, int)
        Goal cell ``(row, col)``; inside the grid and traversable.
    connectivity : {8, 4}, default 8
        As in :func:`astar`.
    corner_cutting : bool, default False
        As in :func:`astar`.

    Returns
    -------
    ndarray of float64, shape (rows, cols)
        Cost-to-go of each cell (in the units of ``costs`` × cells); 0 at the
        goal and ``np.inf`` where the goal is unreachable (including impassable
        cells).

    Raises
    ------
    ValueError
        Invalid ``costs``, ``goal`` outside the grid or impassable, bad
        ``connectivity``.
    TypeError
        Non-integer ``goal`` or connectivity, non-bool ``corner_cutting``.

    Examples
    --------
    >>> import numpy as np
    >>> costs = np.ones((2, 3))
    >>> costs[0, 1] = np.inf
    >>> distance_field(costs, (0, 0))
    array([[ 0., inf,  4.],
           [ 1.,  2.,  3.]])
    >>> distance_field(costs, (0, 0), corner_cutting=True).round(4)
    array([[0.    ,    inf, 2.8284],
           [1.    , 1.4142, 2.4142]])
    """
    grid = validate_costs(costs)
    check_search_size(grid)
    eight = check_connectivity(connectivity)
    cutting = as_bool(corner_cutting, "corner_cutting")
    t = traversable_cell(grid, goal, "goal")
    rows, cols = grid.shape
    n = rows * cols
    ws = workspace(n)
    grid_search(
        grid.ravel(), rows, cols, t[0] * cols + t[1], -1, eight, cutting, 0.0,
        ws.g, ws.parent, ws.mark, ws.heap, ws.pos, ws.size, ws.stamp,
    )
    # Exhaustion closes every reachable cell; g is stale everywhere else.
    closed = ws.mark[:n] == ws.stamp + 1
    return np.where(closed, ws.g[:n], np.inf).reshape(rows, cols)
