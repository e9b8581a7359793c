"""World-coordinate path planning on an :class:`~navkit.mapping.OccupancyGrid`."""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from navkit._shared.validation import as_float_array, positive_float
from navkit.mapping import OccupancyGrid
from navkit.planning.grid._astar import astar
from navkit.planning.grid._field_dstar import field_dstar_cells

__all__ = ["WorldPath", "plan_path"]

# A cell planner maps (costs, start cell, goal cell, **options) to
# (points (K, 2) as continuous (row, col) with integers at cell centres,
#  cost in cost units x cells, number of expansions).
CellPlanner = Callable[..., tuple[NDArray[np.float64], float, int]]


def _astar_cells(
    costs: NDArray[np.float64], start: tuple[int, int], goal: tuple[int, int], **options: Any
) -> tuple[NDArray[np.float64], float, int]:
    path = astar(costs, start, goal, **options)
    return path.cells.astype(np.float64), path.cost, path.expanded


# Planners available to plan_path by name; another planner joins with one entry.
PLANNERS: dict[str, CellPlanner] = {"astar": _astar_cells, "field_dstar": field_dstar_cells}


@dataclass(frozen=True, eq=False)
class WorldPath:
    """A path in world coordinates, as returned by :func:`plan_path`.

    Attributes
    ----------
    points : ndarray of float64, shape (K, 2)
        World points ``(x, y)`` in m from start to goal (read-only). For
        ``planner="astar"`` these are the centres of the path's cells, from the
        cell containing the start to the cell containing the goal.
    cost : float
        Path cost in cost-weighted metres: the planner's cost (traversal cost ×
        cells) times the resolution, so it equals ``length`` in free space.
    length : float
        Euclidean length of the polyline through ``points``, m.
    expanded : int
        Number of search expansions.
    """

    points: NDArray[np.float64]
    cost: float
    length: float
    expanded: int

    def __post_init__(self) -> None:
        self.points.flags.writeable = False


def _endpoint_cell(
    grid: OccupancyGrid, costs: NDArray[np.float64], value: ArrayLike, name: str
) -> tuple[int, int]:
    point = as_float_array(value, name, shape=(2,))
    row, col = (int(v) for v in grid.world_to_cell(point)[0])
    rows, cols = costs.shape
    if not (0 <= row < rows and 0 <= col < cols):
        raise ValueError(f"{name} {tuple(point.tolist())} is outside the map")
    if not math.isfinite(costs[row, col]):
        raise ValueError(
            f"{name} {tuple(point.tolist())} (cell {(row, col)}) is in an obstacle, within "
            "robot_radius of one, or in unknown space with unknown_cost=inf"
        )
    return row, col


def plan_path(
    grid: OccupancyGrid,
    start_xy: ArrayLike,
    goal_xy: ArrayLike,
    *,
    robot_radius: float = 0.0,
    inflation_radius: float | None = None,
    unknown_cost: float = math.inf,
    planner: str = "astar",
    options: Mapping[str, Any] | None = None,
) -> WorldPath:
    """Plan a collision-free path between two world points on an occupancy grid.

    The grid is turned into traversal costs with
    :meth:`OccupancyGrid.traversal_costs`: occupied cells and every cell whose
    centre lies within ``robot_radius`` of an occupied cell are impassable (the
    robot's centre may not go there), free cells cost 1, and with
    ``inflation_radius > robot_radius`` cells near obstacles cost more (Nav2's
    exponential inflation decay). The chosen cell planner then runs on those
    costs and its path is mapped back to world coordinates.

    For many queries on the same map, compute ``grid.traversal_costs(...)`` once
    and call :func:`astar` directly; this function recomputes it every call.

    Parameters
    ----------
    grid : OccupancyGrid
        The map (cells ``(row, col)``, row 0 at the lowest y).
    start_xy, goal_xy : array_like, shape (2,)
        World points ``(x, y)`` in m.
    robot_radius : float, default 0.0
        Inflation radius in m (>= 0): the robot's inscribed radius.
    inflation_radius : float, optional
        Distance in m up to which costs decay; default ``robot_radius``.
    unknown_cost : float, default inf
        Cost of unknown cells: ``inf`` (impassable) or a value >= 1.
    planner : str, default "astar"
        Name of the cell planner, a key of ``navkit.planning.grid._map_planner.PLANNERS``:
        ``"astar"`` or ``"field_dstar"`` (any-angle, see :func:`field_dstar`).
    options : mapping, optional
        Keyword arguments for the planner, e.g. ``{"heuristic_weight": 1.5}``
        or ``{"corner_cutting": True}`` for ``"astar"``.

    Returns
    -------
    WorldPath
        World points, cost, length (m) and expansions.

    Raises
    ------
    ValueError
        Unknown ``planner``; ``start_xy`` or ``goal_xy`` outside the map or on an
        impassable cell; invalid radii or ``unknown_cost``.
    TypeError
        ``grid`` is not an OccupancyGrid.
    navkit.NoPathError
        No collision-free path exists.

    Examples
    --------
    >>> import numpy as np
    >>> from navkit.mapping import OccupancyGrid
    >>> occupied = np.zeros((20, 30), dtype=bool)
    >>> occupied[:15, 14:16] = True
    >>> grid = OccupancyGrid.from_occupancy(occupied, 0.1)
    >>> path = plan_path(grid, (0.55, 0.55), (2.55, 0.55), robot_radius=0.2)
    >>> path.points[0].tolist(), path.points[-1].tolist()
    ([0.55, 0.55], [2.55, 0.55])
    >>> bool(path.points[:, 1].max() > 1.7)
    True
    """
    if not isinstance(grid, OccupancyGrid):
        raise TypeError(f"grid must be an OccupancyGrid, got {type(grid).__name__}")
    if planner not in PLANNERS:
        raise ValueError(f"planner must be one of {sorted(PLANNERS)}, got {planner!r}")
    radius = positive_float(robot_radius, "robot_radius", allow_zero=True)
    costs = grid.traversal_costs(radius, inflation_radius, unknown_cost=unknown_cost)
    start = _endpoint_cell(grid, costs, start_xy, "start_xy")
    goal = _endpoint_cell(grid, costs, goal_xy, "goal_xy")
    cells, cost, expanded = PLANNERS[planner](costs, start, goal, **dict(options or {}))
    # Continuous (row, col) -> local (x, y) of the point in the grid frame.
    local = (cells[:, ::-1] + 0.5) * grid.resolution
    points = grid.origin.transform_points(local)
    length = float(np.hypot(*np.diff(points, axis=0).T).sum())
    return WorldPath(
        points=points, cost=cost * grid.resolution, length=length, expanded=int(expanded)
    )
