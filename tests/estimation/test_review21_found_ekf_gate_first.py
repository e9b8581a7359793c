"""The EKF gates an update whose computed S lost definiteness before trusting its update.

``finish_singular_s`` (an update whose computed S = H P Hᵀ + R is not positive
definite: a state measured twice, each far more precisely than it is known)
checked the information form's trust before the gate, so two readings 1e150
deviations apart, which any gate rejects, raised ``FilterError`` ("innovation
covariance S is not positive definite") where the information form's state
step was not trusted. The NIS it gates on is exact and needs no update: it is
now gated first (review 21, known defects).
"""

from __future__ import annotations

import math
import sys
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from navkit.estimation import ExtendedKalmanFilter, FusionStatus

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from exact_fractions import exact_update

pytestmark = pytest.mark.filterwarnings("error::RuntimeWarning")

_H = np.array([[1.0, 0.0], [1.0, 0.0]])  # state 0 measured twice


def _filter(x0: float) -> ExtendedKalmanFilter:
    return ExtendedKalmanFilter(np.array([x0, 0.0]), np.diag([1e100, 1.0]))


def test_readings_1e150_deviations_apart_are_gated() -> None:
    ekf = _filter(0.0)
    z = np.array([0.5, -0.5])  # 1e150 deviations of R = 1e-300 apart
    rr = np.diag([1e-300, 1e-300])
    result = ekf.update(z, lambda s: _H @ s, _H, rr, gate=9.0)
    assert result.status == FusionStatus.GATED and not result.accepted
    _, _, nis = exact_update(np.zeros(2), np.diag([1e100, 1.0]), _H, rr, z)
    assert result.nis == float(nis)  # the exact NIS, about 5e299
    assert result.reason == f"rejected by the gate: NIS {float(nis):.6g} > 9.0"
    np.testing.assert_array_equal(ekf.x, [0.0, 0.0])
    np.testing.assert_array_equal(ekf.P, np.diag([1e100, 1.0]))
    # Without a gate the same update is applied. The information form's state is not
    # trusted here (its bound is beyond a quarter deviation): the exact state, rounded
    # once, is committed with P⁺ (review 26; it was refused, "innovation covariance S
    # is not positive definite", the filter unchanged).
    x_exact, p_exact, _ = exact_update(np.zeros(2), np.diag([1e100, 1.0]), _H, rr, z)
    result = ekf.update(z, lambda s: _H @ s, _H, rr)
    assert result.accepted and result.nis == float(nis)
    np.testing.assert_array_equal(ekf.x, [float(v) for v in x_exact])
    np.testing.assert_allclose(ekf.P, [[float(v) for v in row] for row in p_exact], rtol=1e-12)


@settings(max_examples=40, deadline=None)
@given(
    x0=st.sampled_from([0.0, 1.0, -3.0, 1e10]),
    log_r=st.floats(-300.0, -120.0),
    half=st.floats(1e-3, 1e3),
    gate=st.floats(1.0, 1e6),
)
def test_a_gate_below_the_exact_nis_always_rejects(
    x0: float, log_r: float, half: float, gate: float
) -> None:
    # Whatever the information form would make of it: the NIS is exact (rational
    # arithmetic), so a gate below it rejects, leaving the filter unchanged.
    r = 10.0**log_r
    rr = np.diag([r, r])
    z = np.array([x0 + half, x0 - half])
    p0 = np.diag([1e100, 1.0])
    ekf = ExtendedKalmanFilter(np.array([x0, 0.0]), p0)
    _, _, nis = exact_update(np.array([x0, 0.0]), p0, _H, rr, z - _H @ np.array([x0, 0.0]))
    if not float(nis) > gate or not math.isfinite(float(nis)):
        return
    result = ekf.update(z, lambda s: _H @ s, _H, rr, gate=gate)
    assert result.status == FusionStatus.GATED
    assert result.nis == float(nis)
    np.testing.assert_array_equal(ekf.x, [x0, 0.0])
    np.testing.assert_array_equal(ekf.P, p0)
