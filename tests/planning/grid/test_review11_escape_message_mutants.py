"""The refused escape's message names what blocks the way (mutation testing).

``MapPlanner.plan`` refuses a start in the inflated band with no passable cell
centre within ``start_tolerance`` reachable in a straight line. With
``unknown_cost=inf`` unknown cells block escape segments as occupied ones do, so
the message must say so; with a finite ``unknown_cost`` only obstacles block.
"""

from __future__ import annotations

import numpy as np
import pytest

from navkit.mapping import OccupancyGrid
from navkit.planning import MapPlanner

# Columns 7 and 11 of a 5 x 20 map (0.1 m cells); the start in column 9 between them.
WALLS = np.zeros((5, 20), dtype=bool)
WALLS[:, [7, 11]] = True
START, GOAL = (0.95, 0.25), (1.85, 0.25)


def test_an_escape_walled_in_by_unknown_space_says_unknown_space() -> None:
    grid = OccupancyGrid.from_occupancy(np.zeros_like(WALLS), resolution=0.1, unknown=WALLS)
    planner = MapPlanner(grid, robot_radius=0.25)
    # Passable centres 0.5 m away on both sides, each behind an unknown column.
    assert np.flatnonzero(np.isfinite(planner.costs[2])).tolist() == [0, 1, 2, 3, 4, *range(14, 20)]
    with pytest.raises(ValueError, match=r"without crossing an obstacle or unknown space$"):
        planner.plan(START, GOAL, start_tolerance=0.6)


def test_an_escape_walled_in_by_obstacles_with_finite_unknown_cost_names_obstacles_only() -> None:
    grid = OccupancyGrid.from_occupancy(WALLS, resolution=0.1)
    planner = MapPlanner(grid, robot_radius=0.25, unknown_cost=1.0)
    with pytest.raises(ValueError, match=r"without crossing an obstacle$") as info:
        planner.plan(START, GOAL, start_tolerance=0.6)
    assert "unknown" not in str(info.value)
