"""Covariances given in float32 are symmetric to float32's rounding (review 52, PRECISION).

A covariance computed in float32 (``J @ S @ J.T`` on a driver's or a learned
model's float32 arrays) is asymmetric by about one float32 epsilon of its largest
entry, 1e-7: the filters refused 167 of 200 such 3 x 3 matrices as "must be
symmetric", since their tolerance was 1e-9 whatever the precision of the input,
and a rank-deficient process noise ``G Q Gᵀ`` as "must be positive semi-definite".
A matrix whose entries are all float32 values now gets 64 float32 epsilons
(7.6e-6) of its largest entry; float64 matrices keep the 1e-9, and a matrix
asymmetric by intent is still refused.

The oracle: the filter with such a matrix holds, and steps with, exactly the
float64 symmetric matrix ``0.5 (A + Aᵀ)`` of the float32 values (which it accepted
before).
"""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from navkit.estimation import ExtendedKalmanFilter, PlanarFusion

_F32 = np.float32


def _float32_product(seed: int, n: int, rank: int | None = None) -> np.ndarray:
    """``J S Jᵀ`` computed in float32 (``J`` of ``rank`` columns), not exactly symmetric."""
    rng = np.random.default_rng(seed)
    k = n if rank is None else rank
    for _ in range(100):
        j = rng.normal(size=(n, k)).astype(_F32)
        s = np.diag(rng.uniform(0.01, 1.0, k)).astype(_F32)
        p = j @ s @ j.T
        if not np.array_equal(p, p.T):
            return p
    raise AssertionError("no asymmetric float32 product found")  # pragma: no cover


def _symmetric(a: np.ndarray) -> np.ndarray:
    """The float64 matrix the filters take for ``a``: its average with its transpose."""
    a = a.astype(np.float64)
    return 0.5 * a + 0.5 * a.T


@settings(max_examples=30, deadline=None)
@given(st.integers(0, 2**32 - 1), st.integers(2, 6))
def test_a_float32_p0_is_taken_as_its_symmetric_float64_matrix(seed: int, n: int) -> None:
    p0 = _float32_product(seed, n)
    ekf = ExtendedKalmanFilter(np.zeros(n, dtype=_F32), p0)
    np.testing.assert_array_equal(ekf.P, _symmetric(p0))
    assert ekf.P.dtype == np.float64


def test_most_float32_products_used_to_be_refused() -> None:
    # Not one of a few: 200 products of 3 x 3 float32 matrices, none refused.
    for seed in range(200):
        ExtendedKalmanFilter(np.zeros(3), _float32_product(seed, 3))


def test_a_float32_rank_deficient_q_steps_as_its_float64_matrix() -> None:
    p0 = np.diag([0.5, 0.4, 0.3, 0.2])
    jac = np.eye(4) + 0.1 * np.eye(4, k=1)
    refused_before = 0
    for seed in range(20):
        q = _float32_product(seed, 4, rank=2)  # positive semi-definite, singular
        qs = _symmetric(q)
        # Its float64 eigenvalues dip below zero by float32 rounding, beyond 1e-9 of
        # its largest entry in most cases: the old check refused it.
        refused_before += bool(np.linalg.eigvalsh(qs)[0] < -1e-9 * np.max(np.abs(qs)))
        ekf = ExtendedKalmanFilter(np.zeros(4), p0)
        ekf.predict(lambda x: jac @ x, jac, q)
        np.testing.assert_allclose(ekf.P, jac @ p0 @ jac.T + qs, rtol=0, atol=1e-15)
    assert refused_before >= 10


def test_a_float32_r_updates_as_its_float64_matrix() -> None:
    h = np.array([[1.0, 0.0, 0.0], [0.0, 1.0, 0.0]])
    z = np.array([500_000.25, 4_500_000.5])
    for seed in range(20):
        r = _float32_product(seed, 2)
        results = []
        for noise in (r, _symmetric(r)):
            ekf = ExtendedKalmanFilter([500_000.0, 4_500_000.0, 0.1], np.eye(3))
            results.append((ekf.update(z, lambda x: x[:2], h, noise), ekf.x.copy(), ekf.P.copy()))
        (ours, x1, p1), (oracle, x2, p2) = results
        assert ours.accepted and oracle.accepted
        assert ours.nis == oracle.nis
        np.testing.assert_array_equal(x1, x2)
        np.testing.assert_array_equal(p1, p2)


def test_float32_values_stored_as_float64_are_read_as_float32() -> None:
    # A driver that computes in float32 and fills a ROS message's float64 covariance.
    p0 = _float32_product(7, 6)
    as_message = [float(v) for v in p0.ravel()]
    fusion = PlanarFusion(P0=np.reshape(as_message, (6, 6)))
    np.testing.assert_array_equal(fusion.P, _symmetric(p0))


def test_plainly_asymmetric_matrices_are_still_refused() -> None:
    p = np.array([[1.0, 0.5], [0.5 + 1e-4, 1.0]], dtype=_F32)  # 800 float32 epsilons
    with pytest.raises(ValueError, match="P0 must be symmetric"):
        ExtendedKalmanFilter(np.zeros(2), p)
    # float64 values keep their tolerance, 1e-9 of the largest entry.
    near = np.array([[1.0, 0.5], [0.5 + 1e-8, 1.0]])
    ekf = ExtendedKalmanFilter(np.zeros(2), np.eye(2))
    with pytest.raises(ValueError, match="R must be symmetric"):
        ekf.update([0.0, 0.0], lambda x: x, np.eye(2), near)


def test_a_float32_q_negative_beyond_its_rounding_is_refused() -> None:
    q = np.array([[1.0, 0.0], [0.0, -1e-4]], dtype=_F32)
    ekf = ExtendedKalmanFilter(np.zeros(2), np.eye(2))
    with pytest.raises(ValueError, match="Q must be positive semi-definite"):
        ekf.predict(lambda x: x, np.eye(2), q)
    np.testing.assert_array_equal(ekf.P, np.eye(2))
