"""Integer-valued covariances keep the strict symmetry check (review 52, FRESH on 6a391e6).

The float32 tolerance (64 float32 epsilons of the largest entry) is for values
float32 arithmetic rounded. Integers of at most 2²⁴ are exact in float32, and so
are their products and sums: their asymmetry is intent, not rounding. A float64
P0 ``[[1e6, 3], [4, 1e6]]`` was silently averaged to 3.5 by 6a391e6 (refused
before it); it is refused again, in float64 and in float32.
"""

from __future__ import annotations

import numpy as np
import pytest

from navkit.estimation import ExtendedKalmanFilter, PlanarFusion


@pytest.mark.parametrize("dtype", [np.float64, np.float32])
def test_an_asymmetric_integer_covariance_is_refused(dtype: type) -> None:
    p0 = np.array([[1e6, 3.0], [4.0, 1e6]], dtype=dtype)
    with pytest.raises(ValueError, match="P0 must be symmetric"):
        ExtendedKalmanFilter([0.0, 0.0], p0)
    ekf = ExtendedKalmanFilter([0.0, 0.0], np.eye(2))
    with pytest.raises(ValueError, match="Q must be symmetric"):
        ekf.predict(lambda x: x, np.eye(2), p0)
    fusion_p0 = np.diag(np.full(6, 1e6)).astype(dtype)
    fusion_p0[0, 1], fusion_p0[1, 0] = 3.0, 4.0
    with pytest.raises(ValueError, match="P0 must be symmetric"):
        PlanarFusion(P0=fusion_p0)


def test_float32_rounding_of_non_integers_is_still_averaged() -> None:
    rng = np.random.default_rng(52)
    j = rng.normal(size=(3, 3)).astype(np.float32)
    s = np.diag(rng.uniform(0.1, 2.0, 3)).astype(np.float32)
    p0 = j @ s @ j.T  # float32 products: asymmetric by rounding
    ekf = ExtendedKalmanFilter(np.zeros(3), p0)
    want = 0.5 * p0.astype(np.float64) + 0.5 * p0.T.astype(np.float64)
    np.testing.assert_array_equal(ekf.P, want)
