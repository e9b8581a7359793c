"""A map read from a ROS message is inflated as far as the same map read from its YAML.

Nav2's inflation reaches ``ceil(inflation_radius / resolution)`` cells. With the
float32 resolution of a ``nav_msgs/OccupancyGrid`` (0.01 m arrives as
0.00999999977 m), 0.1 m was 11 cells instead of 10, and cells sqrt(101) cells
from an obstacle, 0.1005 m away, got costs (85-92) that the YAML map's leave free:
aa45556 took only the inscribed radius in cells of the decimal (review 52, FRESH).
"""

from __future__ import annotations

import numpy as np
import pytest

from navkit.mapping import OccupancyGrid, costmap

RESOLUTIONS = (0.01, 0.02, 0.025, 0.05, 0.1, 0.15, 0.2, 0.3)


def _occupied() -> np.ndarray:
    occ = np.zeros((50, 50), dtype=bool)
    occ[25, 25] = True
    occ[5:7, 10:40] = True
    occ[32:47, 12] = True
    return occ


@pytest.mark.parametrize("resolution", RESOLUTIONS)
def test_the_message_map_costs_equal_the_yaml_maps(resolution: float) -> None:
    occ = _occupied()
    from_yaml = OccupancyGrid.from_occupancy(occ, resolution=resolution)
    from_msg = OccupancyGrid.from_occupancy(occ, resolution=float(np.float32(resolution)))
    for radius_cells in range(0, 9):
        for inflation_cells in range(radius_cells, radius_cells + 6):
            kwargs = {
                "robot_radius": radius_cells * resolution,
                "inflation_radius": inflation_cells * resolution,
            }
            np.testing.assert_array_equal(
                costmap(from_msg, **kwargs), costmap(from_yaml, **kwargs), err_msg=str(kwargs)
            )


def test_the_inflation_stops_at_its_radius_on_a_message_map() -> None:
    occ = np.zeros((31, 31), dtype=bool)
    occ[15, 15] = True
    grid = OccupancyGrid.from_occupancy(occ, resolution=float(np.float32(0.01)))
    cost = costmap(grid, robot_radius=0.0, inflation_radius=0.1)
    rows, cols = np.nonzero(cost)
    # Every inflated cell lies within 10 cells (0.1 m of the decimal 0.01 m).
    assert int(((rows - 15) ** 2 + (cols - 15) ** 2).max()) == 100
