"""The NIS bounds use ``S ⪰ R`` only with P proven positive semidefinite (review 44, EKFCHECK).

``_nis_interval`` bounded ``ρᵀ S⁻¹ ρ`` by R's least eigenvalue too (``S ⪰ R``), which
needs P ⪰ 0 exactly. The kernels' test of a covariance (a float Cholesky factor,
``_is_covariance``, which the filter applies to P0) passes a P within ε of singular
that is indefinite: below, ``fl(A Aᵀ)`` for A of rank 2 has the exact eigenvalue
-1.58e-17, and with ``R = 2e-17 I`` the bounds were ``[0, 1e17]`` around an exact NIS
of 2.4e17. R's bound is now taken only where a shifted Cholesky factor proves P
positive definite.
"""

from __future__ import annotations

import sys
from fractions import Fraction
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import navkit.estimation._ekf_kernels as kernels
from navkit.estimation import ExtendedKalmanFilter

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from exact_fractions import exact_nis, fractions, positive_definite

# fl(A Aᵀ), A (3, 2) from np.random.default_rng(1)'s sixth draw.
_P = np.array(
    [
        [5.721831169054897, -3.0713109591646424, 0.6322724313007356],
        [-3.0713109591646424, 4.31550138178418, 1.1102887415684923],
        [0.6322724313007356, 1.1102887415684923, 0.857877801083427],
    ]
)


def _exactly_positive_definite(a: np.ndarray) -> bool:
    return positive_definite(fractions(a))


def _holds(p: np.ndarray, h: np.ndarray, r: np.ndarray, y: np.ndarray, steps: int) -> None:
    found = kernels._nis_interval(p, h, r, y, steps)
    if found is not None:
        exact = exact_nis(p, h, r, y)
        assert Fraction(found[0]) <= exact <= Fraction(found[1]), (found, float(exact))


def test_the_filter_takes_an_indefinite_p() -> None:
    assert kernels._is_covariance(_P) and not _exactly_positive_definite(_P)
    ExtendedKalmanFilter(np.zeros(3), _P)  # accepted as P0


@pytest.mark.parametrize("variance", [1.7e-17, 2e-17, 3e-17, 5e-17])
@pytest.mark.parametrize("steps", [0, 8])
def test_the_bounds_hold_with_an_indefinite_p(variance: float, steps: int) -> None:
    # Along P's negative eigenvector: before, [0, 1.18e17], [0, 1e17], [0, 6.7e16]
    # around exact NIS of 8.5e17, 2.4e17, 7.1e16 (5e-17 held).
    y = np.linalg.eigh(_P)[1][:, 0]
    r = np.eye(3) * variance
    assert exact_nis(_P, np.eye(3), r, y) > 0  # S positive definite
    _holds(_P, np.eye(3), r, y, steps)


@settings(max_examples=30, deadline=None)
@given(
    seed=st.integers(0, 2**32 - 1),
    log_r=st.floats(-17.5, -15.0),
    steps=st.sampled_from([0, 8]),
)
def test_the_bounds_hold_with_a_p_within_rounding_of_singular(
    seed: int, log_r: float, steps: int
) -> None:
    rng = np.random.default_rng(seed)
    a = rng.normal(size=(3, 2))
    p = a @ a.T
    p = 0.5 * (p + p.T)
    r = np.eye(3) * 10.0**log_r
    if exact_nis(p, np.eye(3), r, np.ones(3)) <= 0:  # S itself indefinite: no NIS
        return
    _holds(p, np.eye(3), r, np.linalg.eigh(p)[1][:, 0], steps)
