"""A scan match's covariance does not depend on the caller's ``np.seterr`` (review 31).

The covariance scales the Hessian by the scan points' RMS distance, whose
squares underflow for a coordinate below about 1e-154 (a beam at angle 1e-200
rad gives a point 1e-200 m off the axis): ``FloatingPointError`` after a
caller's ``np.seterr(all="raise")`` or ``under="raise"``.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from navkit.mapping import LaserScan, OccupancyGrid, ScanMatcher


def _match() -> tuple[float, float, float, np.ndarray]:
    occupied = np.zeros((20, 20), dtype=bool)
    occupied[0, :] = occupied[-1, :] = occupied[:, 0] = occupied[:, -1] = True
    occupied[5:8, 12:15] = True
    room = OccupancyGrid.from_occupancy(occupied, resolution=0.1)
    ranges = np.array([0.85, 0.9, 1.1, 0.95, 0.9, 0.85, 0.9, 1.0, 1.2, 0.9, 0.95, 0.8])
    scan = LaserScan(
        ranges, angle_min=1e-200, angle_increment=math.pi / 6, range_min=0.05, range_max=5.0
    )
    matcher = ScanMatcher(levels=2, max_iterations=5, search_distance=0.2, search_angle=0.3)
    result = matcher.match(room, scan, [1.0, 1.0, 0.1])
    return result.pose.x, result.pose.y, result.pose.theta, result.covariance


@pytest.mark.parametrize("mode", ["all", "under"])
def test_the_same_match_whatever_numpys_error_state(mode: str) -> None:
    expected = _match()
    with np.errstate(**{mode: "raise"}):  # type: ignore[arg-type]
        got = _match()  # FloatingPointError before the fix
    assert got[:3] == expected[:3]
    assert np.array_equal(got[3], expected[3])
    assert np.isfinite(got[3]).all()  # a real match, not the unknown covariance
