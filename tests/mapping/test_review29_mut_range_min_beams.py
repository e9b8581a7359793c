"""Review 29 (MUTATE): a reading exactly at ``range_min`` is a valid return.

``integrate_scan`` documents valid beams as ``range_min <= r < range_max``: such a
beam clears the cells it crosses and marks its end cell. The kernel tests the
interval twice (the hit pass and the miss pass). Made strict (``range_min < r``),
the miss pass's test passed the whole mapping suite and the hit pass's was caught
only by a chance hypothesis example: no test had a reading on ``range_min``
itself. The beam then marked its end without clearing the cells before it, or
cleared them without marking its end.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from navkit.geometry import Pose2D
from navkit.mapping import LaserScan, OccupancyGrid


def _expected(shape: tuple[int, int]) -> np.ndarray:
    # Sensor at (0.55, 0.55) looking along +x, 0.1 m cells from (0, 0): the beam of
    # 0.5 m starts in cell (5, 5) and ends in (5, 10) (x = 1.05, mid-cell): cells
    # 5-9 of row 5 are crossed, 10 is the hit; no cell boundary is near either end.
    want = np.zeros(shape, dtype=np.float32)
    want[5, 5:10] = -0.5
    want[5, 10] = 1.0
    return want


@pytest.mark.parametrize("exact", [False, True])
def test_a_reading_on_range_min_clears_its_cells_and_marks_its_end(exact: bool) -> None:
    grid = OccupancyGrid.empty(width=2.0, height=1.0, resolution=0.1)
    scan = LaserScan([0.5], angle_min=0.0, angle_increment=0.1, range_min=0.5, range_max=4.0)
    n = grid.integrate_scan(scan, Pose2D(0.55, 0.55, 0.0), hit=1.0, miss=-0.5, exact=exact)
    assert n == 6
    np.testing.assert_array_equal(grid.logodds, _expected(grid.shape))


@pytest.mark.parametrize("exact", [False, True])
def test_range_min_on_the_reading_maps_as_a_range_min_just_below_it(exact: bool) -> None:
    # The same reading with range_min one ulp lower is inside the interval by any
    # reading of it: the boundary case must map the same cells the same way.
    pose = Pose2D(0.55, 0.55, 0.0)
    grids = []
    for range_min in (0.5, math.nextafter(0.5, 0.0)):
        grid = OccupancyGrid.empty(width=2.0, height=1.0, resolution=0.1)
        scan = LaserScan(
            [0.5, 0.7], angle_min=0.0, angle_increment=0.5, range_min=range_min, range_max=4.0
        )
        grid.integrate_scan(scan, pose, hit=1.0, miss=-0.5, exact=exact)
        grids.append(grid.logodds)
    np.testing.assert_array_equal(grids[0], grids[1])
    assert (grids[0] == 1.0).sum() == 2
