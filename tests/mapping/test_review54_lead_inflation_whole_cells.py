"""A radius of whole cells of a ROS message's float32 resolution inflates that many cells.

Nav2 reaches ``ceil(inflation_radius / resolution)`` cells with the message's
resolution as a double: 3 cells of float32 0.05 m (0.0500000007 m each) are 3
cells. Review 52 counted the radius in cells of the decimal 0.05 m instead (so
that 0.1 m on a 0.01 m map is 10 cells from the message as from the YAML), and
3 x 0.0500000007 m was 4 cells: cells sqrt(10) cells away got costs. Whole
cells of the resolution itself now count as those (review 54, FRESH2's finding).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from navkit.mapping import OccupancyGrid, costmap


def _single_obstacle(resolution: float) -> OccupancyGrid:
    occ = np.zeros((41, 41), dtype=bool)
    occ[20, 20] = True
    return OccupancyGrid.from_occupancy(occ, resolution=resolution)


@pytest.mark.parametrize("decimal", [0.025, 0.05, 0.1, 0.3, 0.01, 0.03, 0.7])
@pytest.mark.parametrize("cells", [1, 2, 3, 5, 8])
def test_whole_cells_of_a_float32_resolution_reach_as_in_nav2(decimal: float, cells: int) -> None:
    resolution = float(np.float32(decimal))
    inflation_radius = cells * resolution
    nav2_cells = math.ceil(inflation_radius / resolution)  # Nav2's cellDistance, in doubles
    assert nav2_cells == cells
    cost = costmap(
        _single_obstacle(resolution),
        robot_radius=0.0,
        inflation_radius=inflation_radius,
        cost_scaling_factor=0.1,
    )
    rows, cols = np.nonzero(cost)
    squared = (rows - 20) ** 2 + (cols - 20) ** 2
    # The band ends at the radius: every cell of it inflated, none beyond.
    assert int(squared.max()) == nav2_cells**2


def test_a_decimal_radius_still_counts_in_the_decimals_cells() -> None:
    # 0.1 m on a message's 0.01 m map: 10 cells as from the YAML (review 52), not
    # Nav2's 11 of 0.00999999977 m.
    resolution = float(np.float32(0.01))
    cost = costmap(_single_obstacle(resolution), robot_radius=0.0, inflation_radius=0.1)
    rows, cols = np.nonzero(cost)
    assert int(((rows - 20) ** 2 + (cols - 20) ** 2).max()) == 100
