"""What "positive definite" means for the filter's covariances (review 45).

``ExtendedKalmanFilter``'s docstring says a covariance passes its LDLᵀ check when
float64 cannot tell it from positive definite, so its exact least eigenvalue may lie
below zero, by at most about ``n**2 * 2.2e-16`` times its largest variance. The checks
below hold the filter to both halves: such a matrix (``fl(A Aᵀ)`` for a tall ``A``) is
taken as ``P0``, and whatever the check passes is exactly positive definite once that
margin is added to its diagonal (exact rational elimination, no rounding).
"""

from __future__ import annotations

import sys
from fractions import Fraction
from pathlib import Path

import numpy as np
from hypothesis import given
from hypothesis import strategies as st

import navkit.estimation._ekf_kernels as kernels
from navkit.estimation import ExtendedKalmanFilter

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from exact_fractions import positive_definite

_EPS = Fraction(2.0**-52)


def _shifted(p: np.ndarray, by: Fraction) -> list[list[Fraction]]:
    exact = [[Fraction(v) for v in row] for row in p.tolist()]
    for i in range(len(exact)):
        exact[i][i] += by
    return exact


@given(
    n=st.integers(2, 6),
    rank=st.integers(1, 5),
    seed=st.integers(0, 2**32 - 1),
    scale=st.sampled_from([1e-6, 1.0, 1e6]),
    nudge=st.booleans(),
)
def test_a_passed_covariance_is_positive_definite_within_the_documented_margin(
    n: int, rank: int, seed: int, scale: float, nudge: bool
) -> None:
    rng = np.random.default_rng(seed)
    # Rows of different sizes: variances apart, as a state of metres and radians.
    a = rng.standard_normal((n, min(rank, n - 1))) * scale * 10.0 ** rng.uniform(-2, 2, (n, 1))
    p = a @ a.T
    p = np.tril(p) + np.tril(p, -1).T  # exactly symmetric, as the filter mirrors it
    if nudge:  # just nonsingular, or still indefinite, depending on the draw
        p += np.diag(rng.uniform(0.0, 1e-15, n) * p.diagonal())
    if not kernels._is_covariance(p):
        return
    margin = n * n * _EPS * Fraction(float(np.max(p.diagonal())))
    assert positive_definite(_shifted(p, margin))


def test_a_singular_product_in_float_is_taken_as_p0() -> None:
    # Rank 2 in exact arithmetic; float64's Cholesky finds it positive definite.
    rng = np.random.default_rng(1)
    for _ in range(200):
        a = rng.standard_normal((3, 2))
        p = a @ a.T
        p = np.tril(p) + np.tril(p, -1).T
        if kernels._is_covariance(p) and not positive_definite(_shifted(p, Fraction(0))):
            break
    else:
        raise AssertionError("no float-positive-definite, exactly indefinite product drawn")
    f = ExtendedKalmanFilter(np.zeros(3), p)
    np.testing.assert_array_equal(f.P, p)
