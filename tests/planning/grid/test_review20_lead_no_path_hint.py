"""``MapPlanner``'s ``NoPathError`` says what may have closed every way (review 20).

A new user planning on a map built from scans met a bare "no collision-free
path": the robot's radius grows the walls and the unknown specks a scan map
keeps inside corridors, which are impassable by default. The message now names
those two settings when they apply, and the remedies it names open the way.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from navkit.errors import NoPathError
from navkit.mapping import OccupancyGrid
from navkit.planning import MapPlanner

START, GOAL = (0.5, 2.5), (8.5, 2.5)


def _corridor(unknown_gap: bool) -> OccupancyGrid:
    """A wall at column 4 with a gap of 3 cells; the gap unknown or free."""
    p = np.full((6, 10), 0.0)
    p[:, 4] = 1.0
    p[1:4, 4] = 0.5 if unknown_gap else 0.0
    return OccupancyGrid.from_probabilities(p, resolution=1.0)


@pytest.mark.parametrize("planner", ["astar", "field_dstar"])
def test_unknown_cells_and_the_radius_are_named_and_their_remedies_work(planner: str) -> None:
    grid = _corridor(unknown_gap=True)
    hint = r"unknown cells impassable with unknown_cost=inf may close every way; a finite"
    with pytest.raises(NoPathError, match=hint + r" unknown_cost may open one$"):
        MapPlanner(grid, planner=planner).plan(START, GOAL)
    with pytest.raises(NoPathError, match=r"obstacles grown by robot_radius=0\.6 m and unknown"
                       r" cells impassable \(and grown\) with unknown_cost=inf"):  # fmt: skip
        MapPlanner(grid, robot_radius=0.6, planner=planner).plan(START, GOAL)
    route = MapPlanner(grid, unknown_cost=5.0, planner=planner).plan(START, GOAL)
    assert route.length >= 8.0


@pytest.mark.parametrize("planner", ["astar", "field_dstar"])
def test_the_radius_alone_is_named_when_the_map_has_no_unknown_cells(planner: str) -> None:
    grid = _corridor(unknown_gap=False)
    with pytest.raises(NoPathError) as info:
        MapPlanner(grid, robot_radius=2.1, planner=planner).plan(START, GOAL)
    message = str(info.value)
    assert "obstacles grown by robot_radius=2.1 m may close every way" in message
    assert "unknown cells" not in message
    # The named remedy opens the way.
    assert MapPlanner(grid, robot_radius=0.4, planner=planner).plan(START, GOAL).length < math.inf


def test_a_finite_unknown_cost_is_not_blamed() -> None:
    p = np.zeros((6, 10))
    p[:, 4] = 1.0  # no gap
    p[0, 0] = 0.5  # an unknown cell, passable at unknown_cost=5
    closed = OccupancyGrid.from_probabilities(p, resolution=1.0)
    with pytest.raises(NoPathError) as info:
        MapPlanner(closed, unknown_cost=5.0).plan(START, GOAL)
    assert "may close every way" not in str(info.value)
    with pytest.raises(NoPathError, match="unknown cells impassable with unknown_cost=inf"):
        MapPlanner(closed).plan(START, GOAL)
