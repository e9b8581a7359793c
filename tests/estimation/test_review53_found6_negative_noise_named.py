"""A process noise taken as semi-definite to its rounding, named when its step fails (review 53).

``covariance(..., semidefinite=True)`` takes a float32 matrix as positive
semi-definite when its least eigenvalue is negative by at most 64 float32
epsilons of its largest entry (6a391e6): a float32 ``T Q Tᵀ`` of a noise of
lower rank is indefinite so, and a diagonal entry whose exact value is 0 comes
out negative in about half of them, as low as -62 epsilons of the largest
entry (measured: ``T`` with a row orthogonal to a rank-1 ``Q = v vᵀ``), so a
negative diagonal entry such as ``diag(-7.5, 1e6 + 0.0625)`` is not refused: by
its values it is such a product (review 54, FOUND7: ``diag(-7.5, 1e6)``, every
entry a short decimal, was typed, and is refused as not semi-definite, as a
float64 matrix is). Added to a covariance smaller than it, it left one
that is not positive definite, and the filter said "predicted covariance is not
positive definite" without naming ``Q``; the error now names it and its
eigenvalue (``process_noise`` for PlanarFusion).
"""

from __future__ import annotations

import numpy as np
import pytest

from navkit.errors import FilterError
from navkit.estimation import ExtendedKalmanFilter, PlanarFusion


def _rounded_products_with_a_negative_diagonal() -> list[np.ndarray]:
    """float32 ``T Q Tᵀ`` of a rank-1 Q with ``T``'s first row orthogonal to it, ``[0, 0]`` < 0."""
    rng = np.random.default_rng(3)
    found = []
    for _ in range(200):
        v = rng.normal(size=3)
        t = rng.normal(size=(3, 3))
        w = rng.normal(size=3)
        t[0] = w - (w @ v) / (v @ v) * v  # exactly: T[0] Q T[0]ᵀ = 0
        product = t.astype(np.float32) @ np.outer(v, v).astype(np.float32) @ t.T.astype(np.float32)
        if product[0, 0] < 0.0:
            found.append(product)
    return found


def test_rounded_products_with_a_negative_diagonal_entry_are_still_taken() -> None:
    products = _rounded_products_with_a_negative_diagonal()
    taken = 0
    for q in products:
        ekf = ExtendedKalmanFilter(np.zeros(3), np.eye(3))
        try:
            ekf.predict(lambda x: x, np.eye(3), q)
        except ValueError:
            continue  # beyond the tolerance (rare): refused naming Q, as before
        taken += 1
        np.testing.assert_allclose(ekf.P, np.eye(3) + q.astype(np.float64), rtol=0, atol=1e-6)
    assert taken >= 20


def test_the_ekf_names_q_when_its_negative_eigenvalue_fails_the_prediction() -> None:
    q = np.diag(np.float32([-7.5, 1e6 + 0.0625]))  # 1000000.0625: a float32 result's digits
    ekf = ExtendedKalmanFilter([0.0, 0.0], np.eye(2))
    with pytest.raises(
        FilterError, match=r"not positive definite \(Q, .* eigenvalue, -7\.5"
    ) as info:
        ekf.predict(lambda x: x, np.eye(2), q)
    assert "pass a positive semi-definite Q" in str(info.value)
    assert ekf.P.tolist() == np.eye(2).tolist()
    # Off the diagonal too: [[1e6, 1e6 + 7.5], [1e6 + 7.5, 1e6]] (eigenvalue -7.5).
    off = np.float32([[1e6, 1e6 + 7.5], [1e6 + 7.5, 1e6]])
    with pytest.raises(FilterError, match=r"\(Q, .* eigenvalue, -7\.5"):
        ekf.predict(lambda x: x, np.eye(2), off)


def test_the_ekf_says_nothing_of_q_when_q_is_semi_definite() -> None:
    ekf = ExtendedKalmanFilter([0.0, 0.0], np.eye(2))
    with pytest.raises(FilterError) as info:
        ekf.predict(lambda x: x, np.zeros((2, 2)), np.diag([0.0, 1.0]))
    assert str(info.value) == "predicted covariance is not positive definite"


def test_a_typed_negative_diagonal_is_refused_as_not_semi_definite() -> None:
    # Every entry a short decimal: typed, not rounded (review 54, FOUND7).
    ekf = ExtendedKalmanFilter([0.0, 0.0], np.eye(2))
    for q in (np.diag(np.float32([-7.5, 1e6])), np.diag([-7.5, 1e6])):
        with pytest.raises(ValueError, match="Q must be positive semi-definite"):
            ekf.predict(lambda x: x, np.eye(2), q)
    assert ekf.P.tolist() == np.eye(2).tolist()
    with pytest.raises(ValueError, match="process_noise must be positive semi-definite"):
        PlanarFusion(t0=0.0, process_noise=np.diag(np.float32([1e6, 1.0, 1.0, -7.5, 1.0, 1.0])))


def test_planar_fusion_names_its_process_noise() -> None:
    q = np.diag(np.float32([1e6 + 0.0625, 1.0, 1.0, -7.5, 1.0, 1.0]))
    fusion = PlanarFusion(t0=0.0, process_noise=q)
    with pytest.raises(FilterError, match=r"\(process_noise, .* eigenvalue, -7\.5"):
        fusion.update_odometry(1.0, 1.0, 0.0, v_variance=0.01, omega_variance=0.01)
    assert fusion.t == 0.0
    # A late measurement's replay takes the same step again, and names it too.
    late = PlanarFusion(t0=0.0, P0=np.eye(6) * 1e4, process_noise=q, history=10.0)
    late.update_odometry(0.5, 1.0, 0.0, v_variance=0.01, omega_variance=0.01)
    late.update_yaw(5.0, 0.0, variance=1e-6)
    with pytest.raises(FilterError, match=r"taken again .* \(process_noise, .* eigenvalue, -7\.5"):
        late.update_yaw(0.6, 0.0, variance=1e-6)
