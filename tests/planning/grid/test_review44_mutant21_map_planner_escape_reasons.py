"""``MapPlanner.plan``'s escape into the goal's own cell, and why an unknown cell is blocked.

Review 44, MUTANT21's surviving mutants of ``_map_planner.py``:

* A start escaped (``start_tolerance``) into the very cell that holds the goal
  must still leave by the escape segment to that cell's centre: the straight
  segment from the start to the goal may cross the impassable cells around
  the start. A mutant that took the one-cell shortcut (start straight to the
  goal) whenever the two cells matched, escape or not, survived.
* An unknown cell with a finite ``unknown_cost`` is blocked only by an
  obstacle's robot_radius: the refusal must say so, not "is in unknown space
  (unknown_cost is inf)" (a mutant dropping the ``unknown_cost`` test survived).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from navkit.mapping import OccupancyGrid
from navkit.planning import MapPlanner


def _one_obstacle(unknown: np.ndarray | None = None) -> OccupancyGrid:
    occupied = np.zeros((7, 9), dtype=bool)
    occupied[3, 4] = True
    return OccupancyGrid.from_occupancy(occupied, resolution=1.0, unknown=unknown)


@pytest.mark.parametrize("planner", ["astar", "field_dstar"])
def test_an_escape_into_the_goals_cell_still_passes_its_centre(planner: str) -> None:
    grid = _one_obstacle()
    mp = MapPlanner(grid, robot_radius=1.0, planner=planner)  # type: ignore[arg-type]
    start = np.array([3.4, 3.2])  # cell (3, 3), next to the obstacle: blocked
    assert not math.isfinite(mp.costs[3, 3])
    centre = np.array([3.5, 2.5])  # cell (2, 3): the nearest passable centre
    goal = np.array([3.7, 2.6])  # in cell (2, 3) too
    escape = mp.plan(start, centre, start_tolerance=2.0)
    np.testing.assert_array_equal(escape.points, [start, centre])
    path = mp.plan(start, goal, start_tolerance=2.0)
    np.testing.assert_array_equal(path.points, [start, centre, goal])
    link = math.hypot(*(goal - centre)) * float(mp.costs[2, 3])
    assert path.cost == pytest.approx(escape.cost + link, rel=1e-12)
    assert path.length == pytest.approx(escape.length + math.hypot(*(goal - centre)), rel=1e-12)


def test_an_unknown_cell_of_finite_cost_is_blocked_by_the_radius_not_as_unknown() -> None:
    unknown = np.zeros((7, 9), dtype=bool)
    unknown[3, 5] = True  # beside the obstacle
    mp = MapPlanner(_one_obstacle(unknown), robot_radius=1.0, unknown_cost=5.0)
    with pytest.raises(ValueError, match=r"is within robot_radius \(1.0 m\) of an obstacle$"):
        mp.plan((0.5, 0.5), (5.5, 3.5))
