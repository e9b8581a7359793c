"""A variance of 0, a ROS covariance of all zeros ("unknown"), is refused with a hint (review 28).

``sensor_msgs/Imu`` marks a covariance unknown by all zeros, and REP 145's "not
given" row (-1 first) holds 0 at the yaw entry a planar user reads: the last
release's hint named only -1, so both kinds of row were refused with no word on
why the data held 0.
"""

from __future__ import annotations

import numpy as np
import pytest

from navkit.estimation import MeasurementLog, PlanarFusion

HINT = "0 may be a ROS message's covariance of all zeros, which marks it unknown"
T = np.array([0.0, 0.1])


def test_a_stream_variance_of_zero_is_refused_with_the_hint() -> None:
    with pytest.raises(ValueError, match="yaw_variance must be in") as info:
        MeasurementLog.from_streams(yaw=(T, np.zeros(2)), yaw_variance=np.array([1e-3, 0.0]))
    assert HINT in str(info.value)


def test_a_log_variance_of_zero_where_observed_is_refused_with_the_hint() -> None:
    variances = np.full((1, 4), 1e-3)
    variances[0, 2] = 0.0
    observed = np.array([[False, False, True, False]])
    with pytest.raises(ValueError, match="variances must be in") as info:
        MeasurementLog([0.0], np.zeros((1, 4)), variances, observed)
    assert HINT in str(info.value)


def test_a_zero_where_not_observed_is_no_error() -> None:
    variances = np.zeros((1, 4))
    variances[0, 2] = 1e-3
    observed = np.array([[False, False, True, False]])
    log = MeasurementLog([0.0], np.zeros((1, 4)), variances, observed)
    assert log.variances[0, 2] == 1e-3


def test_a_single_variance_of_zero_is_refused_with_the_hint() -> None:
    fusion = PlanarFusion(t0=0.0)
    with pytest.raises(ValueError, match=r"variance must be in .*, got 0\.0") as info:
        fusion.update_yaw(0.1, 0.0, variance=0.0)
    assert HINT in str(info.value)
    assert fusion.t == 0.0


def test_minus_one_keeps_its_own_hint() -> None:
    with pytest.raises(ValueError, match="REP 145") as info:
        PlanarFusion(t0=0.0).update_yaw(0.1, 0.0, variance=-1.0)
    assert HINT not in str(info.value)


@pytest.mark.parametrize("bad", [-2.0, 1e-101, 1e101])
def test_other_out_of_range_variances_get_no_hint(bad: float) -> None:
    with pytest.raises(ValueError, match="variance must be in") as info:
        PlanarFusion(t0=0.0).update_yaw(0.1, 0.0, variance=bad)
    assert "ROS" not in str(info.value)
