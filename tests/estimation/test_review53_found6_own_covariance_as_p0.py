"""An ExtendedKalmanFilter's own covariance is a valid P0 (review 53, REUSE's finding, FOUND6).

The filter commits a covariance its kernels' LDLᵀ factorisation takes (or, after
an update whose Joseph form cancelled, a scaled Cholesky test), while the
constructor decided with NumPy's Cholesky alone, another order of operations:
near singular they disagree, and ``ExtendedKalmanFilter(ekf.x, ekf.P)`` raised
"P0 must be positive definite" for 80 of 1,197 filters after one update with R
1e-16 to 1e-40 of P (REUSE's matrix: second pivot 2.2e-16 in the kernels',
0.0 in LAPACK's). The constructor now also takes what those checks take; what
none takes is refused as before.
"""

from __future__ import annotations

import numpy as np
import pytest

from navkit.errors import FilterError
from navkit.estimation import ExtendedKalmanFilter

REUSE_P = np.array(
    [[1.2295186115074588, 1.1701889166820183], [1.1701889166820183, 1.113722141258639]]
)


def test_a_matrix_the_kernels_factorise_is_a_valid_p0() -> None:
    with pytest.raises(np.linalg.LinAlgError):
        np.linalg.cholesky(REUSE_P)  # LAPACK's second pivot is 0.0 here
    ekf = ExtendedKalmanFilter(np.zeros(2), REUSE_P)
    assert ekf.P.tolist() == REUSE_P.tolist()
    ekf.predict(lambda x: x, np.eye(2), 1e-3 * np.eye(2))
    assert np.all(np.linalg.eigvalsh(ekf.P) > 0.0)


def test_every_committed_covariance_is_a_valid_p0() -> None:
    rng = np.random.default_rng(0)
    committed = 0
    near_singular = 0
    for r in (1e-16, 1e-20, 1e-40):
        for _ in range(150):
            n = int(rng.integers(2, 5))
            m = int(rng.integers(1, n + 1))
            a = rng.standard_normal((n, n))
            ekf = ExtendedKalmanFilter(np.zeros(n), a @ a.T + 0.1 * np.eye(n))
            h = rng.standard_normal((m, n))
            try:
                ekf.update(
                    rng.standard_normal(m), lambda x, h=h: h @ x, lambda x, h=h: h, r * np.eye(m)
                )
            except (ValueError, FilterError):
                continue  # refused (an update it cannot take to its precision)
            committed += 1
            try:
                np.linalg.cholesky(ekf.P)
            except np.linalg.LinAlgError:
                near_singular += 1
            twin = ExtendedKalmanFilter(ekf.x, ekf.P)
            assert twin.P.tolist() == ekf.P.tolist()
    assert committed >= 250
    assert near_singular >= 5  # the cases NumPy alone refused


@pytest.mark.parametrize(
    "p0",
    [
        [[1.0, 1.0], [1.0, 1.0]],
        [[1.0, 2.0], [2.0, 1.0]],
        [[1e-320, 0.0], [0.0, 1.0]],
        np.ones((250, 250)),
    ],
)
def test_a_singular_or_indefinite_p0_is_still_refused(p0: object) -> None:
    n = np.asarray(p0).shape[0]
    with pytest.raises(ValueError, match="P0 must be positive definite"):
        ExtendedKalmanFilter(np.zeros(n), p0)
