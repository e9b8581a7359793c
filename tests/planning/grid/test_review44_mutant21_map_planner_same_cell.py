"""A cell planner's path between one cell and itself is kept as planned (review 44, MUTANT21).

``MapPlanner.plan`` draws the straight segment from the start to the goal
only when the cell planner's path is that one cell; a caller's planner may
answer a query from a cell to itself with a longer path (a detour it needs,
say to turn on the spot elsewhere), which must be kept, with its cost, as
every other path is. A mutant taking the straight segment whenever the two
cells were the same survived (navkit's planners answer with the one cell).
"""

from __future__ import annotations

import numpy as np
import pytest
from numpy.typing import NDArray

from navkit.mapping import OccupancyGrid
from navkit.planning import MapPlanner, Path2D


def _detour(
    costs: NDArray[np.float64], start_cell: tuple[int, int], goal_cell: tuple[int, int]
) -> Path2D:
    row, col = start_cell
    cells = np.array([start_cell, (row, col + 1), goal_cell], dtype=np.float64)
    return Path2D(cells, "grid", cost=7.0, length=2.0, expanded=3)


def test_a_cell_planners_detour_from_a_cell_to_itself_is_kept() -> None:
    grid = OccupancyGrid.from_occupancy(np.zeros((4, 5), dtype=bool), resolution=0.5)
    planner = MapPlanner(grid, planner=_detour)
    start, goal = np.array([0.6, 0.6]), np.array([0.9, 0.8])  # both in cell (1, 1)
    path = planner.plan(start, goal)
    centre = np.array([0.75, 0.75])
    want = np.array([start, centre, [1.25, 0.75], centre, goal])
    np.testing.assert_allclose(path.points, want)
    links = np.hypot(*(centre - start)) + np.hypot(*(goal - centre))
    assert path.cost == pytest.approx(7.0 * 0.5 + links * float(planner.costs[1, 1]))
    assert path.length == pytest.approx(2.0 * 0.5 + links)
    assert path.expanded == 3
