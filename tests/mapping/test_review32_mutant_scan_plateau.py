"""A plateau match's score and rotation variance, on a map with an asymmetric origin (review 32).

Review 31's plateau test (every end point of a noise-free scan on the
two-cell-thick walls of a map drawn with walls on cell edges) checked the
score above 0.99 and the rotation variance between 0 and one cell's. Mutants
of ``ScanMatcher._plateau`` survived it: the score clamped with ``max`` for
``min`` (always 1), and the map's origin read as ``(y, x)`` (the test's map
had its corner at (-4.5, -4.5)). Oracles: on a plateau every end point sees the
occupied cells' probability (``grid.probability()``'s largest value), so the
score is that; the covariance is the documented uniform error over one cell,
``res² / 12`` per axis and ``res² / 12 / mean(r²)`` for the heading, ``r`` the
scan's ranges (the points' distances from the sensor). Checked: the test fails
on those two mutants of ``_scan_matcher.py`` and passes on HEAD.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from shapely.geometry import box

from navkit.geometry import Pose2D
from navkit.mapping import OccupancyGrid, ScanMatcher
from navkit.sim import Lidar, World


@pytest.mark.parametrize("bounds", [(-4.5, -4.5, 4.5, 4.5), (-4.5, -5.0, 4.5, 4.25)])
def test_a_plateau_match_scores_the_occupied_probability(
    bounds: tuple[float, float, float, float],
) -> None:
    res = 0.05
    room = [box(-4.0, -4.0, 4.0, 4.0).exterior, box(1.0, 1.0, 2.0, 1.5)]
    true = Pose2D(0.3, -0.2, 0.4)
    scan = Lidar(n_beams=180, noise=None, range_min=0.05, range_max=10.0).scan(World(room), true)
    grid = OccupancyGrid.from_polygons(room, bounds=bounds, resolution=res)
    found = ScanMatcher().match(grid, scan, true)
    assert found.converged and found.reason == "converged"
    assert math.hypot(found.pose.x - true.x, found.pose.y - true.y) < res
    occupied = float(np.max(grid.probability()))
    assert found.score == pytest.approx(occupied, rel=1e-6)  # the map holds float32
    ranges = np.asarray(scan.ranges)
    assert np.all(ranges < scan.range_max)  # every beam an end point
    spread = res**2 / 12.0
    np.testing.assert_allclose(
        np.diag(found.covariance),
        [spread, spread, spread / np.mean(ranges**2)],
        rtol=1e-12,
    )
