"""``PlanarFusion``: a measurement the gate rejects reports its innovation (mutation review).

``UpdateResult.residual`` is "the innovation y = z - h(x) with angle components
wrapped to (-π, π]; empty when it was never computed or overflowed float64". For a
gated measurement it is computed (its NIS is), but a mutant reporting it empty for
every finite residual, and keeping a non-finite one, survived the suite (review 38):
no test read a gated result's residual. Oracle: a copy of the filter predicted to the
measurement's time, whose state gives y and whose covariance gives S = H P Hᵀ + R,
and the chi-square gate's NIS yᵀ S⁻¹ y.
"""

from __future__ import annotations

import copy
import math

import numpy as np
import pytest

from navkit.estimation import FusionStatus, PlanarFusion


def _wrap(a: float) -> float:
    w = math.remainder(a, 2.0 * math.pi)
    return math.pi if w == -math.pi else w


def _filter(history: float | None) -> PlanarFusion:
    kwargs = {} if history is None else {"history": history}
    f = PlanarFusion(x0=[1.0, 2.0, 3.0, 0.5, 0.2, 0.0], t0=0.0, gate_probability=0.99, **kwargs)
    assert f.update_odometry(0.2, 0.5, 0.2, v_variance=1e-3, omega_variance=1e-3).accepted
    return f


@pytest.mark.parametrize("history", [None, 2.0])
def test_a_gated_yaw_reports_its_wrapped_innovation(history: float | None) -> None:
    f = _filter(history)
    predicted = copy.deepcopy(f)
    predicted.predict(0.7)
    z, var = -2.0, 1e-6  # across ±π from the predicted heading near 3.1
    y = _wrap(z - float(predicted.x[2]))
    result = f.update_yaw(0.7, z, variance=var)
    assert result.status is FusionStatus.GATED and not result.accepted
    assert result.residual.shape == (1,)
    assert result.residual[0] == pytest.approx(y, rel=1e-12)
    assert 1.0 < result.residual[0] < 1.3  # wrapped, not z - x's -5.1
    assert result.nis == pytest.approx(y * y / (predicted.P[2, 2] + var), rel=1e-9)


@pytest.mark.parametrize("history", [None, 2.0])
def test_a_gated_odometry_reports_both_innovations(history: float | None) -> None:
    f = _filter(history)
    predicted = copy.deepcopy(f)
    predicted.predict(0.7)
    v, omega, var = 9.0, -4.0, 1e-4
    y = np.array([v - predicted.x[3], omega - predicted.x[4]])
    s = predicted.P[3:5, 3:5] + var * np.eye(2)
    result = f.update_odometry(0.7, v, omega, v_variance=var, omega_variance=var)
    assert result.status is FusionStatus.GATED
    np.testing.assert_allclose(result.residual, y, rtol=1e-12)
    assert result.nis == pytest.approx(float(y @ np.linalg.solve(s, y)), rel=1e-9)
