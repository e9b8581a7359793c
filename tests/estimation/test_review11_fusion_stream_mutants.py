"""MeasurementLog.from_streams gives each odometry component its own variance (mutation testing).

Every earlier test passed equal speed and yaw-rate variances (or read only one
of them), so reading ``odometry_variance[0]`` for both went unnoticed.
"""

from __future__ import annotations

from typing import Any

import numpy as np
import pytest

from navkit.estimation import MeasurementLog


def test_speed_and_yaw_rate_rows_carry_their_own_variances() -> None:
    times = np.array([0.0, 0.1, 0.2])
    v_var, omega_var = 0.01, 2.5
    log = MeasurementLog.from_streams(
        odometry=(times, np.ones(3), np.full(3, 0.2)), odometry_variance=(v_var, omega_var)
    )
    # Columns [theta, v, omega, a]: v and omega observed on every row.
    assert log.observed[:, 1].all() and log.observed[:, 2].all()
    assert log.variances[:, 1].tolist() == [v_var] * 3
    assert log.variances[:, 2].tolist() == [omega_var] * 3


def test_per_row_yaw_rate_variances_follow_their_rows() -> None:
    times = np.array([0.3, 0.1, 0.2])  # unsorted: the log sorts the rows by time
    omega_var = np.array([3.0, 1.0, 2.0])
    log = MeasurementLog.from_streams(
        odometry=(times, np.zeros(3), np.zeros(3)), odometry_variance=(1e-3, omega_var)
    )
    order = np.argsort(times)
    assert log.variances[:, 2].tolist() == omega_var[order].tolist()
    assert log.variances[:, 1].tolist() == [1e-3] * 3


@pytest.mark.parametrize(
    ("stream", "parts", "want"),
    [("odometry", 4, "2 or 3"), ("yaw", 3, "2"), ("yaw_rate", 3, "2"), ("acceleration", 3, "2")],
)
def test_a_stream_with_too_many_arrays_is_refused_naming_it(
    stream: str, parts: int, want: str
) -> None:
    # The documented widths: odometry (t, v[, omega]), every other stream (t, value).
    t = np.array([0.0, 1.0])
    message = rf"^{stream} must be a tuple of {want} arrays, got {parts}"
    with pytest.raises(ValueError, match=message):
        kwargs: dict[str, Any] = {stream: (t,) * parts}
        MeasurementLog.from_streams(**kwargs)
