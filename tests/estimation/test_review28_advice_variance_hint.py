"""The ROS "not given" hint of a refused variance says what to leave out, and that works.

A stream's variances with ROS's -1 ("not given") or 0 ("unknown") are refused
with "drop those rows"; one measurement's were refused with the same words,
though a scalar update has no rows: it now says "skip that reading".
"""

from __future__ import annotations

import numpy as np
import pytest

from navkit.estimation import MeasurementLog, PlanarFusion


@pytest.mark.parametrize("value", [-1.0, 0.0])
def test_one_reading_is_told_to_skip_it(value: float) -> None:
    fusion = PlanarFusion(t0=0.0)
    with pytest.raises(ValueError, match=r"variance must be in .*skip that reading\)$") as info:
        fusion.update_yaw(0.1, 0.2, variance=value)
    assert "rows" not in str(info.value)
    assert fusion.t == 0.0  # skipping it: the filter stays where it was


@pytest.mark.parametrize("value", [-1.0, 0.0])
def test_a_stream_is_told_to_drop_those_rows_and_that_works(value: float) -> None:
    t = np.array([0.1, 0.2, 0.3])
    yaw = np.array([0.0, 0.1, 0.2])
    var = np.array([1e-3, value, 2e-3])
    with pytest.raises(ValueError, match=r"yaw_variance must be in .*drop those rows\)$"):
        MeasurementLog.from_streams(yaw=(t, yaw), yaw_variance=var)
    keep = var > 0.0
    log = MeasurementLog.from_streams(yaw=(t[keep], yaw[keep]), yaw_variance=var[keep])
    np.testing.assert_array_equal(log.times, [0.1, 0.3])
