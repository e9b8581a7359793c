"""plan_path between neighbouring cells and between equal points, every planner (review 50, FOUND2).

Documented in :meth:`MapPlanner.plan`: a start and goal in one cell are joined
straight (one point when equal); in two neighbouring cells, however close, they
are joined through both centres. Checked here for every planner ``plan_path``
offers: ``"astar"``, ``"field_dstar"`` and :class:`CellPlanner` callables
(A* with corner cutting, jump point search).
"""

from __future__ import annotations

import math
from functools import partial
from typing import Any

import numpy as np
import pytest

from navkit.mapping import OccupancyGrid
from navkit.planning import astar, plan_path

_PLANNERS: dict[str, Any] = {
    "astar": "astar",
    "field_dstar": "field_dstar",
    "astar-corner-cutting": partial(astar, corner_cutting=True),
    "jps": partial(astar, method="jps"),
}
_RES = 0.1


def _grid() -> OccupancyGrid:
    occupied = np.zeros((6, 6), dtype=bool)
    occupied[0, 0] = True
    return OccupancyGrid.from_occupancy(occupied, resolution=_RES)


def _polyline(points: np.ndarray) -> float:
    return float(np.hypot(*np.diff(points, axis=0).T).sum()) if len(points) > 1 else 0.0


@pytest.mark.parametrize("planner", list(_PLANNERS))
@pytest.mark.parametrize(
    ("start", "goal", "centres"),
    [
        # 2 µm apart across the border x = 0.3 of cells (2, 2) and (2, 3).
        ((0.299999, 0.25), (0.300001, 0.25), [(0.25, 0.25), (0.35, 0.25)]),
        # Diagonal neighbours (2, 2) and (3, 3), 1e-4 m apart near their corner.
        ((0.2999, 0.2999), (0.3001, 0.3001), [(0.25, 0.25), (0.35, 0.35)]),
        # Vertical neighbours, the points on their centres.
        ((0.35, 0.25), (0.35, 0.35), [(0.35, 0.25), (0.35, 0.35)]),
    ],
)
def test_neighbouring_cells_are_joined_through_both_centres(
    planner: str, start: tuple[float, float], goal: tuple[float, float], centres: list[Any]
) -> None:
    path = plan_path(_grid(), start, goal, planner=_PLANNERS[planner])
    expected = [start, *centres, goal]
    # A point on its centre takes the centre's place (no repeated point).
    deduplicated = [p for i, p in enumerate(expected) if i == 0 or p != expected[i - 1]]
    np.testing.assert_allclose(path.points, deduplicated, rtol=0.0, atol=1e-12)
    assert path.points[0].tolist() == list(start) and path.points[-1].tolist() == list(goal)
    assert path.length == pytest.approx(_polyline(path.points), rel=1e-12)
    # Free space: the cost is the length.
    assert path.cost == pytest.approx(path.length, rel=1e-9)
    gap = math.dist(centres[0], centres[1])
    assert path.length >= gap - 1e-12


@pytest.mark.parametrize("planner", list(_PLANNERS))
@pytest.mark.parametrize(
    ("start", "goal"),
    [((0.25, 0.25), (0.25, 0.25)), ((0.21, 0.23), (0.21, 0.23)), ((0.21, 0.23), (0.29, 0.28))],
)
def test_one_cell_is_joined_straight(
    planner: str, start: tuple[float, float], goal: tuple[float, float]
) -> None:
    path = plan_path(_grid(), start, goal, planner=_PLANNERS[planner])
    if start == goal:
        assert path.points.tolist() == [list(start)]
        assert path.length == 0.0 and path.cost == 0.0
    else:
        assert path.points.tolist() == [list(start), list(goal)]
        assert path.length == pytest.approx(math.dist(start, goal), rel=1e-12)
        assert path.cost == pytest.approx(path.length, rel=1e-9)
