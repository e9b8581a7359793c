"""A zero reading stays "no return" when the dtype rounds range_min to 0 (review 53, FRESH2).

bcb53cd reads a float32 (or float16) reading equal to ``range_min`` rounded
to that dtype as ``range_min``. A ``range_min`` the dtype cannot hold rounds to
0: float16 ranges with ``range_min=2e-8`` (or float32 with 1e-46) had every zero
reading, the "no return" of drivers that write 0 (LaserScan's docstring asks
them for a ``range_min > 0``), made a valid return at the sensor, and a reading
at both limits' common rounding (float16's 1000.1 and 1000.2 m, both 1000) a
return at ``range_min``.
"""

from __future__ import annotations

import numpy as np
import pytest

from navkit.mapping import LaserScan

ANGLES = {"angle_min": -0.5, "angle_increment": 0.1}


@pytest.mark.parametrize(
    ("dtype", "range_min"), [(np.float16, 2e-8), (np.float16, 1e-9), (np.float32, 1e-46)]
)
def test_a_zero_reading_stays_no_return(dtype: type[np.floating], range_min: float) -> None:
    assert float(dtype(range_min)) == 0.0  # the premise: the dtype rounds it to 0
    ranges = np.array([0.0, 1.0, 0.0], dtype=dtype)
    scan = LaserScan(ranges, range_min=range_min, range_max=5.0, **ANGLES)
    assert scan.valid_mask().tolist() == [False, True, False]
    assert scan.ranges.tolist() == [0.0, 1.0, 0.0]


def test_a_reading_at_both_rounded_limits_stays_no_return() -> None:
    ranges = np.array([1000.0, 500.0], dtype=np.float16)
    assert float(np.float16(1000.1)) == float(np.float16(1000.2)) == 1000.0
    scan = LaserScan(ranges, range_min=1000.1, range_max=1000.2, **ANGLES)
    assert not scan.valid_mask().any()
    assert scan.ranges[0] == 1000.2


def test_a_subnormal_rounded_range_min_still_reads_as_range_min() -> None:
    # float16 holds 1e-7 as 1.19e-7 (subnormal, not 0): the reading at it is range_min.
    ranges = np.array([np.float16(1e-7), 1.0], dtype=np.float16)
    scan = LaserScan(ranges, range_min=1e-7, range_max=5.0, **ANGLES)
    assert scan.ranges[0] == 1e-7
    assert scan.valid_mask().tolist() == [True, True]
