"""ScanMatcher on grids at the ends of the documented ranges (sixth review)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from navkit.mapping import LaserScan, OccupancyGrid, ScanMatcher


@pytest.mark.parametrize("resolution", [1e6, 6e5, 2.5e5])
def test_pyramid_stops_below_the_largest_resolution(resolution: float) -> None:
    # A grid at up to 1e6 m is valid, but doubling it past 1e6 m raised a
    # ValueError about a "resolution" the caller never gave.
    grid = OccupancyGrid(np.zeros((8, 8)), resolution=resolution)
    levels = ScanMatcher(levels=4).pyramid(grid)
    expected = [resolution * 2**k for k in range(4) if resolution * 2**k <= 1e6]
    assert [g.resolution for g in levels] == expected
    assert levels[0] is grid


def test_match_on_a_coarse_grid_gives_a_result() -> None:
    logodds = np.full((8, 8), -2.0)
    logodds[0, :] = logodds[:, 0] = logodds[-1, :] = logodds[:, -1] = 4.0
    grid = OccupancyGrid(logodds, resolution=1e6)
    scan = LaserScan(
        np.full(8, 3.0e6),
        angle_min=-math.pi,
        angle_increment=math.pi / 4,
        range_min=1.0,
        range_max=1e9,
    )
    result = ScanMatcher().match(grid, scan, (4.0e6, 4.0e6, 0.0))
    assert np.isfinite([result.pose.x, result.pose.y, result.pose.theta]).all()
    assert 0.0 <= result.score <= 1.0
