"""A covariance typed with halves is refused as one typed with integers is (review 53, FRESH).

6a391e6 lets a matrix of float32 values be asymmetric by 64 float32 epsilons of
its largest entry (J S Jᵀ computed in float32); fafdb71 keeps the strict 1e-9
for integers, whose float32 arithmetic is exact, after a float64 P0 ``[[1e6,
3], [4, 1e6]]`` was averaged to 3.5. Halves are float32 values too: ``[[1e6,
2.5], [3.5, 1e6]]`` was averaged to 3.0 and ``[[1e5, 0.5], [1, 1e5]]`` to
0.75, where a float64 matrix asymmetric by that much is refused. Products
computed in float32 keep their tolerance. Fixed in review 54 (FOUND7): a matrix
whose every entry is an integer of at most 2²⁴ or a decimal of at most 6
significant digits is taken as typed, and keeps the strict check.
"""

from __future__ import annotations

import numpy as np
import pytest

from navkit.estimation import ExtendedKalmanFilter


@pytest.mark.parametrize(
    "p0",
    [[[1e6, 2.5], [3.5, 1e6]], [[1e5, 0.5], [1.0, 1e5]], [[4096.0, 0.0078125], [0.0, 4096.0]]],
)
def test_a_typed_asymmetric_covariance_is_refused(p0: list[list[float]]) -> None:
    with pytest.raises(ValueError, match="P0 must be symmetric"):
        ExtendedKalmanFilter(np.zeros(2), p0)


def test_the_integer_twin_is_refused() -> None:
    with pytest.raises(ValueError, match="P0 must be symmetric"):
        ExtendedKalmanFilter(np.zeros(2), [[1e6, 3.0], [4.0, 1e6]])


def test_products_computed_in_float32_are_still_accepted() -> None:
    rng = np.random.default_rng(53)
    asymmetric = 0
    for n in (2, 3, 6, 12):
        for _ in range(25):
            jac = rng.standard_normal((n, n)).astype(np.float32)
            spread = np.diag(rng.random(n) + 0.1).astype(np.float32)
            p0 = (jac @ spread @ jac.T).astype(np.float64)
            asymmetric += bool(np.any(p0 != p0.T))
            ekf = ExtendedKalmanFilter(np.zeros(n), p0)
            np.testing.assert_array_equal(ekf.P, 0.5 * p0 + 0.5 * p0.T)
    assert asymmetric > 50  # the tolerance was needed
