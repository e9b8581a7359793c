"""Exact cost-to-go fields on cost grids (Dijkstra to exhaustion), one-shot."""

from __future__ import annotations

from typing import Any

from numpy.typing import ArrayLike

from navkit._shared.types import FloatArray
from navkit.planning.grid._astar import AStarPlanner
from navkit.planning.grid._limits import checked_costs

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
        Per-cell traversal cost: finite values in ``[1, 1e12]`` traversable,
        ``np.inf`` impassable; at most ``2**31 - 1`` cells. Integer or float
        dtype; booleans, complex numbers, strings, NaN, values below 1 or
        finite values above 1e12, empty arrays or other dimensions raise
        ``ValueError``. Not modified. (1e12 is every grid planner's
        maximum: sums of such costs over any grid stay far from overflow, and
        it leaves Field D*, whose path costs must stay below ``2**52``, see
        :class:`FieldDStar`, paths of 4,500 cells at that cost.)
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
        ``goal_cell`` not a pair of integers, non-integer connectivity,
        non-bool ``corner_cutting``.

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
    grid, lowest = checked_costs(costs)
    planner = AStarPlanner._borrowing(grid, lowest, connectivity, corner_cutting, 1.0)
    return planner.distance_field(goal_cell)
