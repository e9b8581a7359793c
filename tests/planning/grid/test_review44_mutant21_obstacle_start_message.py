"""A start in an obstacle is refused as such, with no escape tried (review 44, MUTANT21).

``start_tolerance`` escapes a start only from the robot_radius band; a start
in an obstacle (or in impassable unknown space) is refused with that reason
alone. A mutant that let such a start reach the escape search gave the same
ValueError with a misleading tail ("and no passable cell centre within
start_tolerance can be reached ..."): the tests matched the reason only and
it survived. The whole message is checked here.
"""

from __future__ import annotations

import numpy as np
import pytest

from navkit.mapping import OccupancyGrid
from navkit.planning import MapPlanner


@pytest.mark.parametrize("planner", ["astar", "field_dstar"])
def test_a_start_in_an_obstacle_or_unknown_space_is_refused_without_an_escape(
    planner: str,
) -> None:
    occupied = np.zeros((7, 9), dtype=bool)
    occupied[3, 4] = True
    unknown = np.zeros((7, 9), dtype=bool)
    unknown[5, 1] = True
    grid = OccupancyGrid.from_occupancy(occupied, resolution=1.0, unknown=unknown)
    mp = MapPlanner(grid, robot_radius=1.0, planner=planner)  # type: ignore[arg-type]
    with pytest.raises(ValueError) as info:
        mp.plan((4.5, 3.5), (8.5, 0.5), start_tolerance=3.0)
    assert str(info.value) == "start (4.5, 3.5) (cell (3, 4)) is in an obstacle"
    with pytest.raises(ValueError) as info:
        mp.plan((1.5, 5.5), (8.5, 0.5), start_tolerance=3.0)
    assert str(info.value) == (
        "start (1.5, 5.5) (cell (5, 1)) is in unknown space (unknown_cost is inf)"
    )
