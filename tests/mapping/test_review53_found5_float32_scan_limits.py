"""Review 53 (FOUND5): float32 readings at range_max are "no return", as REP 117 has it.

A driver (or a user) filling a float32 ranges array writes ``range_max`` for
"no return" rounded to float32: 5.6 m is 5.599999904632568. A ``LaserScan``
built from that array with ``range_max=5.6`` (a Python float) read those
beams as returns 5.6 m away (``r < range_max``), and ``integrate_scan`` marked
an obstacle at each of their ends. Readings of a float32 (or float16) array
equal to ``range_max`` (or ``range_min``) in that precision are those limits
now; a ROS message's scan (both in float32) and float64 scans are unchanged.
"""

from __future__ import annotations

import array
import math

import numpy as np
import pytest

from navkit.mapping import LaserScan, OccupancyGrid, integrate_scan

ANGLES = {"angle_min": -0.5, "angle_increment": 0.1}


@pytest.mark.parametrize("range_max", [5.6, 3.3, 10.1, 29.9, 0.7])
def test_float32_readings_at_range_max_are_no_return(range_max: float) -> None:
    assert float(np.float32(range_max)) != range_max  # rounded: the case at stake
    ranges = np.array([range_max, 0.5 * range_max, range_max, np.inf], dtype=np.float32)
    scan = LaserScan(ranges, range_min=0.05, range_max=range_max, **ANGLES)
    assert scan.valid_mask().tolist() == [False, True, False, False]
    assert scan.ranges[0] == scan.ranges[2] == range_max
    assert scan.ranges[1] == float(np.float32(0.5 * range_max))  # other readings as given
    assert scan.to_points().shape == (1, 2)


def test_float32_readings_at_range_min_are_returns() -> None:
    ranges = np.array([0.7, 0.69, 2.0], dtype=np.float32)
    scan = LaserScan(ranges, range_min=0.7, range_max=5.6, **ANGLES)
    assert float(np.float32(0.7)) < 0.7
    assert scan.valid_mask().tolist() == [True, False, True]
    assert scan.ranges[0] == 0.7


@pytest.mark.parametrize(
    "given",
    [
        lambda v: np.array(v, dtype=np.float32),
        lambda v: [np.float32(r) for r in v],
        lambda v: array.array("f", v),  # rclpy's float32[] fields
    ],
)
def test_every_float32_container_is_read_so(given: object) -> None:
    assert callable(given)
    scan = LaserScan(given([5.6, 1.0]), range_min=0.1, range_max=5.6, **ANGLES)
    assert scan.valid_mask().tolist() == [False, True]


def test_a_max_range_beam_marks_no_obstacle() -> None:
    grid64 = OccupancyGrid.empty(width=14.0, height=14.0, resolution=0.05, origin=(-7, -7, 0))
    grid32 = OccupancyGrid.empty(width=14.0, height=14.0, resolution=0.05, origin=(-7, -7, 0))
    readings = [5.6] * 5 + [2.0] * 3 + [5.6] * 3
    scan64 = LaserScan(np.array(readings), range_min=0.1, range_max=5.6, **ANGLES)
    scan32 = LaserScan(np.array(readings, dtype=np.float32), range_min=0.1, range_max=5.6, **ANGLES)
    integrate_scan(grid64, scan64, (0.0, 0.0, 0.0))
    integrate_scan(grid32, scan32, (0.0, 0.0, 0.0))
    # The three 2 m returns mark cells; the eight max-range beams none, as in float64.
    assert 0 < int(grid32.occupied().sum()) <= 3
    assert np.array_equal(grid32.occupied(), grid64.occupied())
    far = grid32.world_to_cell([5.6 * math.cos(-0.5), 5.6 * math.sin(-0.5)])
    assert not grid32.occupied()[far[0], far[1]]


def test_message_and_float64_scans_are_unchanged() -> None:
    # A ROS message's range_max is a float32 too: its readings compare as they are.
    rmax = float(np.float32(5.6))
    ranges = np.array([5.6, 5.599999, 1.0], dtype=np.float32)
    scan = LaserScan(ranges, range_min=0.1, range_max=rmax, **ANGLES)
    assert np.array_equal(scan.ranges, ranges.astype(np.float64))
    assert scan.valid_mask().tolist() == [False, True, True]
    # float64 readings just below range_max are returns.
    scan = LaserScan([5.599999904632568, 5.6], range_min=0.1, range_max=5.6, **ANGLES)
    assert scan.valid_mask().tolist() == [True, False]


def test_float16_readings_and_limits_beyond_float16() -> None:
    scan = LaserScan(np.array([2.3, 1.0], dtype=np.float16), range_min=0.1, range_max=2.3, **ANGLES)
    assert scan.valid_mask().tolist() == [False, True]
    with np.errstate(all="raise"):  # range_max past float16's 65504: no overflow
        scan = LaserScan(np.array([1.0], dtype=np.float16), range_min=1e-9, range_max=1e8, **ANGLES)
    assert scan.valid_mask().tolist() == [True]


def test_the_callers_ranges_are_not_modified() -> None:
    ranges = np.array([5.6, 1.0], dtype=np.float32)
    before = ranges.copy()
    scan = LaserScan(ranges, range_min=0.1, range_max=5.6, **ANGLES)
    assert np.array_equal(ranges, before) and ranges.flags.writeable
    assert not scan.ranges.flags.writeable
