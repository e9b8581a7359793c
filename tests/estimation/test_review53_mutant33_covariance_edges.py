"""The covariance tolerances at their exact edges (review 53, MUTANT33).

Mutants of review 52's float32 tolerance that passed the tests before: 63
float32 epsilons, or ``>=`` where the symmetry check has ``>`` (review 52's
tests stopped at 63 and 65 epsilons: a matrix asymmetric by exactly the
documented 64 is averaged); ``<=`` where the semi-definite check has ``<`` (a
float32 Q whose eigenvalue is exactly minus the tolerance is taken); the
bound of the integers kept strict moved to 2**23, 2**25, or ``<`` (the
entries at 2**24 exactly are integers float32 computes exactly, those at
2**24 + 2 are not); and the float32 test made of the argument as given, not
of its array (a nested list raised AttributeError).
"""

from __future__ import annotations

import numpy as np
import pytest

from navkit.estimation import ExtendedKalmanFilter

_F32 = np.float32
_EPS = float(np.finfo(_F32).eps)


def test_a_float32_p0_asymmetric_by_exactly_64_epsilons_is_averaged() -> None:
    low = _F32(0.25)
    high = _F32(0.25 + 64 * _EPS)
    assert float(high) - float(low) == 64 * _EPS  # the tolerance times the largest entry, 1
    ekf = ExtendedKalmanFilter(np.zeros(2), np.array([[1.0, low], [high, 0.5]], dtype=_F32))
    assert ekf.P[0, 1] == ekf.P[1, 0] == (float(low) + float(high)) / 2.0


def test_a_float32_q_with_an_eigenvalue_of_exactly_minus_the_tolerance_is_taken() -> None:
    tol = 64 * _EPS  # of the largest entry, 1
    q = np.array([[1.0, 0.0], [0.0, -tol]], dtype=_F32)
    assert float(np.linalg.eigvalsh(q.astype(np.float64))[0]) == -tol
    ekf = ExtendedKalmanFilter(np.zeros(2), np.eye(2))
    ekf.predict(lambda x: x, np.eye(2), q)
    np.testing.assert_array_equal(ekf.P, np.diag([2.0, 1.0 - tol]))
    with pytest.raises(ValueError, match="Q must be positive semi-definite"):
        ekf.predict(lambda x: x, np.eye(2), np.diag([1.0, -2.0 * tol]).astype(_F32))


@pytest.mark.parametrize("dtype", [np.float64, _F32])
def test_integers_of_exactly_2_to_the_24_keep_the_strict_check(dtype: type) -> None:
    big = 2.0**24
    p: np.ndarray = np.array([[big, 3.0], [4.0, big]], dtype=dtype)
    with pytest.raises(ValueError, match="P0 must be symmetric"):
        ExtendedKalmanFilter(np.zeros(2), p)


@pytest.mark.parametrize("dtype", [np.float64, _F32])
def test_integers_just_beyond_2_to_the_24_take_the_float32_tolerance(dtype: type) -> None:
    big = 2.0**24 + 2.0  # a float32 value (2 apart there): float32 sums of it round
    assert float(_F32(big)) == big
    p: np.ndarray = np.array([[big, 3.0], [4.0, big]], dtype=dtype)
    ekf = ExtendedKalmanFilter(np.zeros(2), p)
    assert ekf.P[0, 1] == ekf.P[1, 0] == 3.5


def test_a_nested_list_of_float32_values_takes_the_float32_tolerance() -> None:
    low, high, var = float(_F32(0.1)), float(_F32(0.1000001)), float(_F32(0.2))
    assert low != high
    ekf = ExtendedKalmanFilter([0.0, 0.0], [[0.5, low], [high, var]])
    assert ekf.P[0, 1] == ekf.P[1, 0] == (low + high) / 2.0
