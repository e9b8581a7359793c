"""Users' grid mistakes get a message that names the likely cause and the fix.

An occupancy array, a boolean mask, a Nav2 costmap or an ``OccupancyGrid``
passed where a cost grid is wanted; world metres or ``(x, y)`` passed where a
``(row, col)`` cell is wanted; world points outside a map whose ``origin`` was
taken for its centre.
"""

from __future__ import annotations

from typing import Any

import numpy as np
import pytest

from navkit.geometry import Pose2D
from navkit.mapping import OccupancyGrid, validate_costs
from navkit.planning import AStarPlanner, MapPlanner, astar, distance_field


def _occupied() -> np.ndarray:
    occupied = np.zeros((4, 9), dtype=bool)
    occupied[:3, 4] = True
    return occupied


def test_an_occupancy_array_as_costs_names_the_conversion() -> None:
    with pytest.raises(ValueError, match="costs") as err:
        astar(_occupied().astype(float), (0, 0), (0, 8))
    assert "traversal_costs" in str(err.value)
    assert "np.where(occupied, np.inf, 1.0)" in str(err.value)


def test_a_nav2_costmap_as_costs_names_the_conversion() -> None:
    grid = OccupancyGrid.from_occupancy(_occupied(), resolution=0.1)
    nav2 = grid.costmap(robot_radius=0.05, inflation_radius=0.2)
    with pytest.raises(ValueError, match="costs") as err:
        AStarPlanner(nav2)
    assert "costmap" in str(err.value)


def test_a_boolean_mask_as_costs_names_the_conversion() -> None:
    with pytest.raises(ValueError, match="costs") as err:
        distance_field(_occupied(), (0, 0))
    assert "np.where(occupied, np.inf, 1.0)" in str(err.value)


def test_an_occupancy_grid_as_costs_names_traversal_costs() -> None:
    grid = OccupancyGrid.from_occupancy(_occupied(), resolution=0.1)
    wrong: Any = grid  # the mistake under test: not an array
    for call in (lambda: astar(wrong, (0, 0), (0, 8)), lambda: validate_costs(wrong)):
        with pytest.raises(ValueError, match="costs") as err:
            call()
        assert "OccupancyGrid" in str(err.value)
        assert "traversal_costs" in str(err.value)


def test_negative_costs_get_no_free_is_zero_hint() -> None:
    with pytest.raises(ValueError, match="costs") as err:
        validate_costs(np.full((2, 2), -3.0))
    assert "Nav2" not in str(err.value)


def test_world_metres_as_a_cell_say_how_to_convert() -> None:
    with pytest.raises(TypeError, match="start_cell") as err:
        astar(np.ones((4, 9)), (0.25, 0.75), (0, 8))  # type: ignore[arg-type]
    assert "world_to_cell" in str(err.value)
    assert "(row, col)" in str(err.value)


def test_a_cell_given_as_x_y_says_the_swapped_pair_fits() -> None:
    # (x, y) = (col, row) = (8, 1) on a 4-row, 9-column grid: only (1, 8) is inside.
    with pytest.raises(ValueError, match="goal_cell") as err:
        astar(np.ones((4, 9)), (0, 0), (8, 1))
    assert "(1, 8) is inside" in str(err.value)


def test_a_cell_outside_both_ways_gets_no_swap_hint() -> None:
    with pytest.raises(ValueError, match="goal_cell") as err:
        astar(np.ones((4, 9)), (0, 0), (9, 9))
    assert "(x, y)" not in str(err.value)


def test_a_point_outside_the_map_shows_the_map_extent() -> None:
    # A 0.9 m x 0.4 m map whose origin was taken for its centre: (0.05, 0.05)
    # would be inside the user's idea of the map, and is not.
    grid = OccupancyGrid.from_occupancy(
        np.zeros((4, 9), dtype=bool), resolution=0.1, origin=(0.45, 0.2, 0.0)
    )
    with pytest.raises(ValueError, match="start") as err:
        MapPlanner(grid).plan(Pose2D(0.05, 0.05, 0.0), (1.0, 0.5))
    text = str(err.value)
    assert "x in [0.45, 1.35] m" in text
    assert "y in [0.2, 0.6] m" in text
    assert "lower-left corner" in text


def test_the_extent_of_a_rotated_map_bounds_all_its_corners() -> None:
    grid = OccupancyGrid.from_occupancy(
        np.zeros((2, 4), dtype=bool), resolution=1.0, origin=(0.0, 0.0, np.pi / 2)
    )
    with pytest.raises(ValueError, match="goal") as err:
        MapPlanner(grid).plan((-0.5, 0.5), (5.0, 5.0))
    assert "x in [-2, 0] m" in str(err.value)
    assert "y in [0, 4] m" in str(err.value)
