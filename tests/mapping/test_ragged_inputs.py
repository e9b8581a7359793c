"""Ragged nested sequences given as arrays to navkit.mapping: a ValueError naming the argument."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy as np
import pytest

from navkit.geometry import Pose2D
from navkit.mapping import (
    LaserScan,
    LocalGrid,
    OccupancyGrid,
    ScanMatchResult,
    rasterize_polygons,
)

RAGGED = ([[1, 2], [3]], [1, [2, 3]], [[1, 2], [3, 4, 5]], [[[1, 2]], [[3]]])


def scan(ranges: Any = (1.0, 2.0), intensities: Any = None) -> LaserScan:
    return LaserScan(
        ranges,
        angle_min=0.0,
        angle_increment=0.1,
        range_min=0.1,
        range_max=3.0,
        intensities=intensities,
    )


GRID = OccupancyGrid.empty(width=2.0, height=2.0, resolution=0.5)
LOCAL = LocalGrid.from_points([], half_width=0.2, resolution=0.1)

CALLS: dict[str, tuple[str, Callable[[Any], object]]] = {
    "OccupancyGrid.world_to_cell": ("points_xy", GRID.world_to_cell),
    "world_to_cell continuous": (
        "points_xy",
        lambda v: GRID.world_to_cell(v, continuous=True),
    ),
    "OccupancyGrid.cell_to_world": ("cells", GRID.cell_to_world),
    "OccupancyGrid.contains": ("points_xy", GRID.contains),
    "OccupancyGrid": ("logodds", lambda v: OccupancyGrid(v, resolution=1.0)),
    "from_probabilities": (
        "probabilities",
        lambda v: OccupancyGrid.from_probabilities(v, resolution=1.0),
    ),
    "LocalGrid.from_points": ("points_xy", lambda v: LocalGrid.from_points(v)),
    "LocalGrid.world_to_cell": ("points_xy", LOCAL.world_to_cell),
    "LocalGrid.cell_to_world": ("cells", LOCAL.cell_to_world),
    "LocalGrid.contains": ("points_xy", LOCAL.contains),
    "LaserScan ranges": ("ranges", scan),
    "LaserScan intensities": ("intensities", lambda v: scan(intensities=v)),
    "ScanMatchResult": (
        "covariance",
        lambda v: ScanMatchResult(Pose2D(0.0, 0.0, 0.0), v, 1, 0.5, True, "converged"),
    ),
    "rasterize_polygons": ("bounds", lambda v: rasterize_polygons([], bounds=v, resolution=1.0)),
}


@pytest.mark.parametrize("value", RAGGED)
@pytest.mark.parametrize("call", sorted(CALLS))
def test_ragged_numbers_are_a_value_error_naming_the_argument(call: str, value: Any) -> None:
    # The issue: world_to_cell([[1, 2], [3]]) raised TypeError ("numeric array-like").
    name, function = CALLS[call]
    with pytest.raises(ValueError, match=rf"^{name} must be a rectangular array.*ragged"):
        function(value)


@pytest.mark.parametrize(
    ("name", "function"),
    [
        ("occupied", lambda v: OccupancyGrid.from_occupancy(v, resolution=1.0)),
        ("unknown", lambda v: OccupancyGrid.from_occupancy([[True, False]], resolution=1.0,
                                                           unknown=v)),
        ("occupied", lambda v: LocalGrid(v, resolution=0.1, half_width=0.1)),
    ],
)  # fmt: skip
def test_ragged_masks_are_a_value_error_naming_the_argument(
    name: str, function: Callable[[Any], object]
) -> None:
    with pytest.raises(ValueError, match=rf"^{name} must be a rectangular array"):
        function([[True, False], [True]])


@pytest.mark.parametrize(
    "value", [[[1, 2], ["a", "b"]], [[1, 2], "ab"], [[1, 2], [3, None]], [[1, 2], [3j, 4]]]
)
def test_wrong_element_types_stay_a_type_error(value: Any) -> None:
    with pytest.raises(TypeError, match="points_xy"):
        GRID.world_to_cell(value)


def test_regular_input_is_unaffected() -> None:
    assert GRID.world_to_cell([[0.1, 1.9], [1.9, 0.1]]).tolist() == [[3, 0], [0, 3]]
    arrays = [np.array([0.1, 1.9]), np.array([1.9, 0.1])]
    assert GRID.world_to_cell(arrays).tolist() == [[3, 0], [0, 3]]
