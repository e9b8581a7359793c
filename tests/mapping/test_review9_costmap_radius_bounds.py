"""Review 9: costmap's documented range of ``inflation_radius`` at its lower bound.

``inflation_radius`` is "in [robot_radius, 1e6]": the existing test only tried
a radius a third of ``robot_radius``, so a check that let radii between half
of ``robot_radius`` and ``robot_radius`` through went unnoticed (mutation testing).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from navkit.mapping import OccupancyGrid, costmap, traversal_costs


def _grid() -> OccupancyGrid:
    return OccupancyGrid.from_occupancy(np.array([[True] + [False] * 7]), resolution=0.1)


@pytest.mark.parametrize("robot_radius", [0.3, 2.0, 1e6])
def test_an_inflation_radius_just_below_robot_radius_is_refused(robot_radius: float) -> None:
    below = math.nextafter(robot_radius, 0.0)
    for radius in (below, 0.9 * robot_radius, 0.5 * robot_radius):
        with pytest.raises(ValueError, match="inflation_radius"):
            costmap(_grid(), robot_radius=robot_radius, inflation_radius=radius)
        with pytest.raises(ValueError, match="inflation_radius"):
            traversal_costs(_grid(), robot_radius=robot_radius, inflation_radius=radius)


def test_an_inflation_radius_equal_to_robot_radius_is_accepted() -> None:
    # The bound itself is in the range: cells within robot_radius are inscribed
    # (253), nothing decays beyond (0).
    cost = costmap(_grid(), robot_radius=0.3, inflation_radius=0.3)
    assert cost[0].tolist() == [254, 253, 253, 253, 0, 0, 0, 0]
