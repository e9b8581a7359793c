"""Two rules of the indoor scenarios' end-point snap left open by mutation testing.

* "within :data:`SNAP_DISTANCE`" includes a centre at exactly that distance (as
  the brute-force reference of ``test_review10_snap_walls`` reads it).
* The point's own obstacle is its 8-connected blob among the cells within
  ``ceil(SNAP_DISTANCE / resolution) + 1`` rows and columns (the reference's
  window): two arms of one wall joined only through that outer ring are one
  obstacle, so a step may cross the other arm.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from test_review10_snap_walls import reference_snap

from navkit.mapping import OccupancyGrid
from navkit.planning import MapPlanner
from navkit.sim.scenarios._indoor_nav_mapping import SNAP_DISTANCE, _passable


def wall_block() -> tuple[MapPlanner, tuple[float, float]]:
    """Columns 0-2 of a 3 x 10 map occupied (0.1 m cells), and the centre of free cell (1, 3)."""
    occupied = np.zeros((3, 10), dtype=bool)
    occupied[:, :3] = True
    grid = OccupancyGrid.from_occupancy(occupied, resolution=0.1)
    centre = tuple(float(v) for v in grid.cell_to_world(np.array([1, 3])))
    return MapPlanner(grid, robot_radius=0.0), (centre[0], centre[1])


def test_a_centre_exactly_snap_distance_away_is_taken() -> None:
    planner, centre = wall_block()
    point = (centre[0] - SNAP_DISTANCE, centre[1])  # in the wall, cell (1, 0)
    # Exactly SNAP_DISTANCE apart in float64, as any distance formula computes it.
    assert centre[0] - point[0] == SNAP_DISTANCE
    assert math.dist(point, centre) == SNAP_DISTANCE
    assert tuple(int(v) for v in planner.grid.world_to_cell(np.array(point))) == (1, 0)
    # Every other passable centre is farther (cell (1, 4): 0.4 m; (0, 3), (2, 3): 0.316 m).
    found, _ = reference_snap(planner, point)
    assert [c for _, c in found] == [pytest.approx(centre, abs=0.0)]
    assert _passable(planner, point) == centre


def test_a_centre_just_beyond_snap_distance_is_not_taken() -> None:
    planner, centre = wall_block()
    point = (centre[0] - SNAP_DISTANCE - 1e-9, centre[1])
    assert math.dist(point, centre) > SNAP_DISTANCE
    assert _passable(planner, point) == point


# 0.05 m cells, row 0 first; the point is in wall cell (13, 7), robot radius 0.05 m.
RING_MAP = [
    "###.#..##..#.#",
    "..#.#.#.#..#.#",
    "#.#.....#..#..",
    "####.###......",
    ".##.....#.#.##",
    ".##..#...#.##.",
    ".#######..####",
    "#...#..#.###..",
    ".##...##.#....",
    "##..###.#..#..",
    "##.....#..###.",
    "..#.#.##.....#",
    "#..##...##....",
    ".#.#..####.#.#",
]
RING_POINT = (0.36002933871065523, 0.655992220825089)


def test_the_points_obstacle_is_its_blob_within_one_ring_beyond_the_snap_window() -> None:
    occupied = np.array([[ch == "#" for ch in row] for row in RING_MAP])
    grid = OccupancyGrid.from_occupancy(occupied, resolution=0.05)
    planner = MapPlanner(grid, robot_radius=0.05)
    assert tuple(int(v) for v in grid.world_to_cell(np.array(RING_POINT))) == (13, 7)
    found, clear_cut = reference_snap(planner, RING_POINT)
    assert clear_cut and found
    nearest, centre = min(found)
    snapped = _passable(planner, RING_POINT)
    assert math.dist(RING_POINT, snapped) == pytest.approx(nearest, abs=1e-12)
    assert snapped == pytest.approx(centre, abs=1e-12)
