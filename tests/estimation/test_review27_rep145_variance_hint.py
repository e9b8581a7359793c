"""A variance of -1, ROS's "covariance not given" (REP 145), is refused with a hint (review 27).

The bag readers keep an Imu's orientation covariance of -1 as recorded; passed on
as a variance, it was refused as out of range with no word on why a user's data
held -1.
"""

from __future__ import annotations

import numpy as np
import pytest

from navkit.estimation import MeasurementLog, PlanarFusion

HINT = "-1 marks a covariance not given in ROS messages, REP 145"
T = np.array([0.0, 0.1])


def test_a_stream_variance_of_minus_one_is_refused_with_the_hint() -> None:
    with pytest.raises(ValueError, match="yaw_variance must be in") as info:
        MeasurementLog.from_streams(yaw=(T, np.zeros(2)), yaw_variance=np.array([1e-3, -1.0]))
    assert HINT in str(info.value)


def test_a_log_variance_of_minus_one_is_refused_with_the_hint() -> None:
    values = np.zeros((1, 4))
    variances = np.full((1, 4), 1e-3)
    variances[0, 2] = -1.0
    observed = np.array([[False, False, True, False]])
    with pytest.raises(ValueError, match="variances must be in") as info:
        MeasurementLog([0.0], values, variances, observed)
    assert HINT in str(info.value)


def test_a_single_variance_of_minus_one_is_refused_with_the_hint() -> None:
    fusion = PlanarFusion(t0=0.0)
    with pytest.raises(ValueError, match=r"variance must be in .*, got -1\.0") as info:
        fusion.update_yaw(0.1, 0.0, variance=-1.0)
    assert HINT in str(info.value)
    assert fusion.t == 0.0


@pytest.mark.parametrize("bad", [-2.0, 0.0, 1e101])
def test_other_out_of_range_variances_get_no_hint(bad: float) -> None:
    with pytest.raises(ValueError, match="yaw_variance must be in") as info:
        MeasurementLog.from_streams(yaw=(T, np.zeros(2)), yaw_variance=bad)
    assert "REP 145" not in str(info.value)
    with pytest.raises(ValueError, match="variance must be in") as info:
        PlanarFusion(t0=0.0).update_yaw(0.1, 0.0, variance=bad)
    assert "REP 145" not in str(info.value)
