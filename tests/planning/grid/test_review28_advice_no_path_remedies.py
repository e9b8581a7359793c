"""``MapPlanner``'s ``NoPathError`` offers only remedies that can open the way.

It said "a smaller robot_radius or a finite unknown_cost may open one" whatever
had closed the way: at ``robot_radius=0`` (no smaller radius exists) and on
maps without unknown cells (where ``unknown_cost`` changes nothing). Each
remedy is now named with its cause; following every one named opens the way.
"""

from __future__ import annotations

import re

import numpy as np
import pytest

from navkit.errors import NoPathError
from navkit.mapping import OccupancyGrid
from navkit.planning import MapPlanner

START, GOAL = (0.5, 2.5), (8.5, 2.5)


def _corridor(gap: float) -> OccupancyGrid:
    """A wall at column 4 with a gap of 3 cells of occupancy probability ``gap``."""
    p = np.zeros((6, 10))
    p[:, 4] = 1.0
    p[1:4, 4] = gap
    return OccupancyGrid.from_probabilities(p, resolution=1.0)


def _remedies(grid: OccupancyGrid, radius: float, planner: str) -> list[str]:
    with pytest.raises(NoPathError) as info:
        MapPlanner(grid, robot_radius=radius, planner=planner).plan(START, GOAL)
    found = re.search(r"; (.+) may open one$", str(info.value))
    assert found, str(info.value)
    return found.group(1).split(" or ")


@pytest.mark.parametrize("planner", ["astar", "field_dstar"])
@pytest.mark.parametrize(
    ("gap", "radius", "named"),
    [
        (0.5, 0.0, ["a finite unknown_cost"]),  # unknown gap, no radius to shrink
        (0.0, 2.1, ["a smaller robot_radius"]),  # free gap, no unknown cells
        (0.5, 0.6, ["a smaller robot_radius", "a finite unknown_cost"]),
    ],
)
def test_the_remedies_named_are_the_ones_that_apply_and_open_the_way(
    planner: str, gap: float, radius: float, named: list[str]
) -> None:
    grid = _corridor(gap)
    assert _remedies(grid, radius, planner) == named
    # Following them: every remedy named, together, opens the way.
    options = {"robot_radius": 0.4 if "a smaller robot_radius" in named else radius}
    if "a finite unknown_cost" in named:
        options["unknown_cost"] = 5.0
    route = MapPlanner(grid, planner=planner, **options).plan(START, GOAL)
    assert route.length >= 8.0
