"""A beam whose reading ends exactly on the map's far edge line (mutation review, session 37).

Cells are half-open, so an end point on the line ``u == cols`` (or ``v == rows``)
lies in the cell just outside the map: the beam marks no hit, and every map cell
it crossed, the last one included, takes the miss. Hand-built oracle: a beam
along a row from the centre of cell 0 to the edge at 4 m crosses cells 0-3.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from navkit.geometry import Pose2D
from navkit.mapping import LaserScan, OccupancyGrid, integrate_scan

HIT = 0.85
MISS = -0.4


@pytest.mark.parametrize("exact", [False, True])
@pytest.mark.parametrize("along_rows", [False, True])
def test_beam_ending_on_the_far_edge_misses_every_cell_it_crossed(
    along_rows: bool, exact: bool
) -> None:
    # 4 cells of 1 m in a line; the sensor sits at the centre of the first one.
    width, height = (1.0, 4.0) if along_rows else (4.0, 1.0)
    grid = OccupancyGrid.empty(width=width, height=height, resolution=1.0, origin=Pose2D(0, 0, 0))
    # sin(pi/2) and cos(0) are exactly 1: the end point is exactly 0.5 + 3.5 = 4.0.
    pose = Pose2D(0.5, 0.5, math.pi / 2 if along_rows else 0.0)
    scan = LaserScan(
        np.array([3.5]), angle_min=0.0, angle_increment=0.1, range_min=0.1, range_max=10.0
    )
    n = integrate_scan(grid, scan, pose, hit=HIT, miss=MISS, exact=exact)
    assert n == 4
    np.testing.assert_array_equal(grid.logodds.ravel(), np.full(4, MISS, dtype=np.float32))
