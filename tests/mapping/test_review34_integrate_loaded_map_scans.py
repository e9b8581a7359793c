"""Review 34 (integrator lens): scans written into a loaded map_server map.

The mapping guide says how many scans a new obstacle in a loaded map's free
space needs before ``occupied()`` shows it (9 on the turtlebot3 map, whose
cells load as log-odds -6.9), and 4 once the loaded log-odds are clipped into
``integrate_scan``'s default clamp, which keeps every cell's class. These
tests hold the guide to those figures.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from navkit.mapping import LaserScan, OccupancyGrid

CLAMP = (math.log(0.12 / 0.88), math.log(0.97 / 0.03))
POSE = (-2.0, -0.5, 0.0)
SEEN = LaserScan([1.0], angle_min=0.0, angle_increment=0.01, range_min=0.1, range_max=3.5)


def _scans_until_occupied(grid: OccupancyGrid) -> int:
    cell = tuple(grid.world_to_cell([POSE[0] + 1.0, POSE[1]]))
    assert grid.free()[cell]
    count = 0
    while not grid.occupied()[cell]:
        grid.integrate_scan(SEEN, POSE)
        count += 1
        assert count < 100
    return count


def test_loaded_map_needs_nine_scans(shared_data: Path) -> None:
    grid = OccupancyGrid.load(shared_data / "ros-map-server-maps/turtlebot3_world/map.yaml")
    assert float(grid.logodds.min()) < CLAMP[0] and float(grid.logodds.max()) > CLAMP[1]
    assert _scans_until_occupied(grid) == 9


def test_clipped_map_keeps_its_classes_and_needs_four(shared_data: Path) -> None:
    grid = OccupancyGrid.load(shared_data / "ros-map-server-maps/turtlebot3_world/map.yaml")
    clipped = OccupancyGrid(
        np.clip(grid.logodds, *CLAMP), resolution=grid.resolution, origin=grid.origin
    )
    for view in ("occupied", "free", "unknown"):
        assert np.array_equal(getattr(clipped, view)(), getattr(grid, view)())
    assert _scans_until_occupied(clipped) == 4
