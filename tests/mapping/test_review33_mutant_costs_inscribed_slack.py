"""``costmap``'s inscribed test has a slack of 1e-9 cells, not more (review 33, mutants).

A radius that is an exact multiple of the resolution includes the cells at that
distance, up to ``CELL_EPS`` = 1e-9 *cells* of slack. The suite's radii are
exact multiples, so the mutant ``CELL_EPS / resolution`` (a slack of 2e-8 m at
5 cm cells, 400 times the documented 5e-11 m) passed it: a robot 1 nm smaller
than 0.1 m marked the cell centred 0.1 m from an obstacle inscribed (253).
Oracle: the documented slack and Nav2's rule ``int(252 * exp(-k (d - r)))``
outside the inscribed radius. Checked: fails on that mutant of ``_costs.py``,
passes on HEAD.
"""

from __future__ import annotations

import math

import numpy as np

from navkit.mapping import OccupancyGrid, costmap


def _costs(robot_radius: float) -> list[int]:
    occupied = np.zeros((1, 8), dtype=bool)
    occupied[0, 0] = True
    grid = OccupancyGrid.from_occupancy(occupied, resolution=0.05)
    cost = costmap(grid, robot_radius=robot_radius, inflation_radius=0.3)
    return [int(c) for c in cost[0]]


def test_a_cell_1nm_beyond_the_radius_is_not_inscribed() -> None:
    radius = 0.1 - 1e-9  # 2e-8 cells short of the cell 2 cells away: beyond the slack
    assert _costs(radius)[2] == int(252 * math.exp(-10.0 * (0.1 - radius))) == 251


def test_a_radius_within_the_slack_includes_the_cell() -> None:
    assert _costs(0.1 - 1e-12)[2] == 253  # 2e-11 cells short: within 1e-9 cells
    assert _costs(0.1)[2] == 253
