"""How ``MapPlanner.plan`` links its ends, at any resolution (review 44, MUTANT21).

A goal within a millionth of a cell of its cell's centre takes the centre's
place (the rounding of ``cell_to_world``); farther away it is linked to the
centre by a segment of its own. The threshold is in cells, so it scales with
the map's resolution: mutants that made it a millionth of a metre, or a
thousandth of a cell, gave the same paths on every map the tests used
(resolutions near 1 m, offsets of a good part of a cell) and survived.
"""

from __future__ import annotations

import numpy as np
import pytest

from navkit.mapping import OccupancyGrid
from navkit.planning import MapPlanner


@pytest.mark.parametrize(
    ("resolution", "offset_cells", "linked"),
    [(0.05, 1e-5, True), (0.05, 5e-7, False), (10.0, 5e-7, False), (10.0, 2e-6, True)],
)
def test_a_goal_is_linked_only_beyond_a_millionth_of_a_cell_from_its_centre(
    resolution: float, offset_cells: float, linked: bool
) -> None:
    grid = OccupancyGrid.from_occupancy(np.zeros((4, 6), dtype=bool), resolution=resolution)
    planner = MapPlanner(grid)
    start = np.asarray(grid.cell_to_world((1, 0)), dtype=np.float64).reshape(2)
    centre = np.asarray(grid.cell_to_world((1, 4)), dtype=np.float64).reshape(2)
    goal = centre + np.array([offset_cells * resolution, 0.0])
    at_centre = planner.plan(start, centre)
    path = planner.plan(start, goal)
    np.testing.assert_array_equal(path.points[-1], goal)  # ends at the goal either way
    assert len(path.points) == len(at_centre.points) + int(linked)
    np.testing.assert_array_equal(path.points[:-1], at_centre.points[: len(path.points) - 1])
    step = offset_cells * resolution if linked else 0.0
    assert path.cost == pytest.approx(at_centre.cost + step, rel=1e-12, abs=1e-15)
