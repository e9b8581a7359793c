"""Review 34 (integrator lens): a planner's Path2D or a LaserScan passed where points are wanted.

A node that checks its route against the live map writes
``grid.world_to_cell(route)``, or turns a scan into a local grid with
``LocalGrid.from_points(scan)``: the objects themselves, not their points.
Both were refused as "points_xy must hold real numbers, got an element of
type Path2D" (or LaserScan) alone, where a Pose2D's refusal already says what
to pass; these now say it too.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

import numpy as np
import pytest

from navkit.geometry import Pose2D
from navkit.mapping import LaserScan, LocalGrid, OccupancyGrid
from navkit.planning import MapPlanner

GRID = OccupancyGrid.from_occupancy(np.zeros((30, 40), dtype=bool), resolution=0.1)
ROUTE = MapPlanner(GRID).plan((0.55, 0.55), (3.05, 2.05))
SCAN = LaserScan([1.0, 1.5], angle_min=-0.5, angle_increment=1.0, range_min=0.1, range_max=5.0)
POSE = Pose2D(1.0, 1.0, 0.5)

PATH_CALLS: dict[str, Callable[[Any], object]] = {
    "world_to_cell": GRID.world_to_cell,
    "contains": GRID.contains,
    "cells_near": lambda p: GRID.cells_near(p, robot_radius=0.2),
    "transform_points": POSE.transform_points,
}


@pytest.mark.parametrize("call", sorted(PATH_CALLS))
def test_a_path_says_to_pass_its_points(call: str) -> None:
    with pytest.raises(TypeError) as info:
        PATH_CALLS[call](ROUTE)
    message = str(info.value)
    assert "points_xy must hold real numbers, got an element of type Path2D" in message
    assert "path.points" in message and "frame" in message


@pytest.mark.parametrize(
    "call",
    [LocalGrid.from_points, GRID.world_to_cell, POSE.transform_points],
    ids=["LocalGrid.from_points", "world_to_cell", "transform_points"],
)
def test_a_scan_says_to_pass_its_end_points(call: Callable[[Any], object]) -> None:
    with pytest.raises(TypeError) as info:
        call(SCAN)
    message = str(info.value)
    assert "got an element of type LaserScan" in message
    assert "scan.to_points(" in message


def test_what_the_messages_name_is_accepted() -> None:
    cells = GRID.world_to_cell(ROUTE.points)
    assert cells.shape == (len(ROUTE.points), 2)
    local = LocalGrid.from_points(SCAN.to_points(), half_width=2.0)
    hits = local.occupied.sum()
    assert hits == 2
    moved = POSE.transform_points(SCAN.to_points())
    assert np.allclose(moved, SCAN.to_points(POSE), rtol=0, atol=1e-12)
    assert math.isfinite(float(moved.sum()))
