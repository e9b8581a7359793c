"""Review 54 (MUTANT34): LaserScan changes only float32 readings equal to a rounded limit.

Review 53 stores a float32 (or float16) reading equal to ``range_max`` (or
``range_min``) rounded to that dtype as the limit itself. Two mutants of it
passed the tests: readings *beyond* the rounded ``range_max`` made
``range_max`` too (``>=`` for ``==``), and integer ranges taken as a narrow
float dtype (int32 ``5.6`` is 5, so a reading of 5 m became "no return").
"""

from __future__ import annotations

import numpy as np
import pytest

from navkit.mapping import LaserScan


def _scan(ranges: np.ndarray) -> LaserScan:
    return LaserScan(
        ranges=ranges, angle_min=0.0, angle_increment=0.1, range_min=0.7, range_max=5.6
    )


@pytest.mark.parametrize("dtype", [np.float32, np.float16])
def test_readings_beyond_the_rounded_range_max_are_kept_as_read(dtype: type) -> None:
    ranges: np.ndarray = np.array([5.6, 7.0, np.inf, 30.0, 3.0, np.nan], dtype=dtype)
    scan = _scan(ranges)
    # Only the reading at range_max (rounded) becomes range_max; the others are kept.
    assert scan.ranges[0] == 5.6
    expected = ranges[1:].astype(np.float64)
    np.testing.assert_array_equal(scan.ranges[1:], expected)
    assert scan.valid_mask().tolist() == [False, False, False, False, True, False]


@pytest.mark.parametrize("dtype", [np.int32, np.int16, np.int64, np.uint8])
def test_integer_ranges_are_read_as_they_are(dtype: type) -> None:
    # Integers are exact: a reading of 5 m is a return below a range_max of 5.6 m
    # (int32 of 5.6 is 5: an integer dtype is no float rounding of the limit).
    ranges: np.ndarray = np.array([5, 3, 0, 6], dtype=dtype)
    scan = _scan(ranges)
    assert scan.ranges.tolist() == [5.0, 3.0, 0.0, 6.0]
    assert scan.valid_mask().tolist() == [True, True, False, False]
