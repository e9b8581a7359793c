"""Review 33 (FIXUPS): a bare array of per-sample odometry variances gets a usable hint.

``MeasurementLog.from_streams(odometry=(t, v), odometry_variance=array)`` said
"odometry_variance must be a pair (v_variance, omega_variance), got 3060": not
what to give instead. Checked: against ``_fusion.py`` of HEAD both message
tests fail; the last runs the advice given.
"""

from __future__ import annotations

import numpy as np
import pytest

from navkit.estimation import MeasurementLog

_T = np.arange(5) * 0.1
_V = np.ones(5)


def test_odometry_without_yaw_rates_is_told_the_second_variance_is_not_read() -> None:
    with pytest.raises(ValueError) as info:
        MeasurementLog.from_streams(odometry=(_T, _V), odometry_variance=np.full(5, 0.01))  # type: ignore[arg-type]
    assert str(info.value) == (
        "odometry_variance must be a pair (v_variance, omega_variance), got 5 items; for one "
        "variance per sample give (v_variances, 1.0): the second is not read, the odometry "
        "having no yaw rates"
    )


def test_odometry_with_yaw_rates_is_told_to_give_two_arrays() -> None:
    with pytest.raises(ValueError) as info:
        MeasurementLog.from_streams(odometry=(_T, _V, _V), odometry_variance=np.full(5, 0.01))  # type: ignore[arg-type]
    assert str(info.value) == (
        "odometry_variance must be a pair (v_variance, omega_variance), got 5 items; for one "
        "variance per sample give a pair of arrays, (v_variances, omega_variances)"
    )


def test_the_advice_works() -> None:
    variances = np.linspace(0.01, 0.05, 5)
    log = MeasurementLog.from_streams(odometry=(_T, _V), odometry_variance=(variances, 1.0))
    np.testing.assert_array_equal(log.variances[:, 1], variances)
    np.testing.assert_array_equal(log.observed[:, 2], False)
