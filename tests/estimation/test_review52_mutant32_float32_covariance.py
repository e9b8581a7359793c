"""A float32 covariance's tolerance, 64 float32 epsilons, at its edges (review 52, MUTANT32).

PRECISION's tests accept float32 products asymmetric by about 2 float32
epsilons and refuse 800: a tolerance of 2 epsilons (a mutant of the
documented 64) passed them. Its check of whether every entry is a float32
value casts to float32, which overflows for entries beyond float32's range
(up to ``MAX_COVARIANCE``, 1e100): a mutant without the overflow's silencing
passed too, and would warn (an error under ``-W error``) for such a matrix.
A float32 matrix of entries beyond 2**24 (all integers, float32's spacing
there being 2 or more) keeps the float32 tolerance: only integers float32
computes exactly get the strict one (fafdb71), which a mutant without the
bound gave them all.
"""

from __future__ import annotations

import warnings

import numpy as np
import pytest

from navkit.estimation import ExtendedKalmanFilter

_F32 = np.float32
_EPS = float(np.finfo(_F32).eps)


def _asymmetric(epsilons: int) -> np.ndarray:
    """A float32 matrix, largest entry 1, its off-diagonals ``epsilons`` float32 epsilons apart."""
    low = _F32(0.25)
    high = _F32(0.25 + epsilons * _EPS)
    assert float(high) - float(low) == epsilons * _EPS  # exact: 0.25's spacing is eps / 8
    return np.array([[1.0, low], [high, 0.5]], dtype=_F32)


@pytest.mark.parametrize("epsilons", [8, 32, 63])
def test_a_float32_p0_asymmetric_within_64_epsilons_is_averaged(epsilons: int) -> None:
    p = _asymmetric(epsilons)
    ekf = ExtendedKalmanFilter(np.zeros(2), p)
    mean = (float(p[0, 1]) + float(p[1, 0])) / 2.0
    assert ekf.P[0, 1] == ekf.P[1, 0] == pytest.approx(mean, rel=1e-15)


@pytest.mark.parametrize("epsilons", [65, 100])
def test_a_float32_p0_asymmetric_beyond_64_epsilons_is_refused(epsilons: int) -> None:
    with pytest.raises(ValueError, match="P0 must be symmetric"):
        ExtendedKalmanFilter(np.zeros(2), _asymmetric(epsilons))


def test_entries_beyond_float32s_range_are_float64_values_without_a_warning() -> None:
    p = np.diag([1e60, 1.0])
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        ekf = ExtendedKalmanFilter(np.zeros(2), p)
        np.testing.assert_array_equal(ekf.P, p)
        # Read as float64 values: 1e-9 of the largest entry, not 7.6e-6, is the tolerance.
        near = np.array([[1e60, 5e59], [5e59 * (1.0 + 1e-7), 1e60]])
        with pytest.raises(ValueError, match="P0 must be symmetric"):
            ExtendedKalmanFilter(np.zeros(2), near)


def test_float32_entries_beyond_2_to_the_24_keep_the_float32_tolerance() -> None:
    # Variances in mm^2: every entry an integer, 3e7's float32 neighbour 2 above it.
    p = np.array([[1e8, 3e7], [np.nextafter(_F32(3e7), _F32(np.inf)), 1e8]], dtype=_F32)
    assert float(p[1, 0]) - float(p[0, 1]) == 2.0  # 2e-8 of the largest entry: > 1e-9
    ekf = ExtendedKalmanFilter(np.zeros(2), p)
    assert ekf.P[0, 1] == ekf.P[1, 0] == 3e7 + 1.0
