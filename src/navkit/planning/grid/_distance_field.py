"""Exact cost-to-go fields on cost grids (Dijkstra to exhaustion), one-shot."""

from __future__ import annotations

from typing import Any

from numpy.typing import ArrayLike

from navkit._shared.costs import validate_costs_lowest
from navkit._shared.types import FloatArray
from navkit.planning.grid._astar import AStarPlanner

__all__ = ["distance_field"]


def distance_field(
    costs: ArrayLike,
    goal_cell: Any,
    *,
    connectivity: int = 8,
    corner_cutting: bool = False,
) -> FloatArray:
    """Least cost from every cell to ``goal_cell`` (a navigation function), one-shot.

    Runs the search kernel of :func:`astar` with a zero heuristic from
    ``goal_cell`` until every reachable cell is expanded. Move costs are
    symmetric (``step * (c_u + c_v) / 2``), so the cost from the goal to a cell
    is that cell's cost-to-go. :meth:`AStarPlanner.distance_field` is the
    prepared form.

    Parameters
    ----------
    costs : array_like, shape (rows, cols)
        Per-cell traversal cost: finite values >= 1 traversable, ``np.inf``
        impassable. Integer or float dtype; NaN, values below 1, booleans,
        empty arrays or other dimensions raise ``ValueError``. Not modified.
    goal_cell : (int, int)
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
        Invalid ``costs``, ``goal_cell`` outside the grid or impassable, bad
        ``connectivity``.
    TypeError
        Non-integer ``goal_cell`` or connectivity, non-bool ``corner_cutting``.

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
    grid, lowest = validate_costs_lowest(costs)
    planner = AStarPlanner._borrowing(grid, lowest, connectivity, corner_cutting, 1.0)
    return planner.distance_field(goal_cell)
