"""An unknown cell beyond every obstacle's reach stays 255 with ``inflate_unknown`` (review 33).

``costmap`` documents Nav2's rule: an unknown cell takes an inflated cost only
when it is >= 253, or > 0 with ``inflate_unknown``. The suite's
``inflate_unknown=True`` grids put their unknown cells inside the inflation band,
so the mutant ``FREE_SPACE = 1`` (the cost compared with to keep an unknown
cell's 255) passed it: an unknown cell 0.5 m from the only obstacle, beyond the
0.3 m inflation radius, came out 0 (free) instead of 255 (unknown). Oracle: the
documented rule, and Nav2's cost values (255 no information, 0 free space).
Checked: fails on that mutant of ``_costs.py``, passes on HEAD.
"""

from __future__ import annotations

import numpy as np

from navkit.mapping import OccupancyGrid, costmap


def test_a_far_unknown_cell_stays_unknown_when_unknown_cells_inflate() -> None:
    occupied = np.zeros((1, 12), dtype=bool)
    occupied[0, 0] = True
    unknown = np.zeros_like(occupied)
    unknown[0, 10] = True  # 0.5 m from the obstacle; inflation reaches 0.3 m
    grid = OccupancyGrid.from_occupancy(occupied, resolution=0.05, unknown=unknown)
    for inflate_unknown in (False, True):
        cost = costmap(
            grid, robot_radius=0.1, inflation_radius=0.3, inflate_unknown=inflate_unknown
        )
        assert cost[0, 10] == 255
        assert cost[0, 9] == cost[0, 11] == 0  # its known neighbours: free space
