"""The EKF fallbacks' numeric helpers against exact rational arithmetic (mutation review).

``finish_cancelled`` and ``finish_singular_s`` rest on a few helpers whose promises
no test checked directly, only through whole updates, where their errors hide behind
the choice among candidates: mutants of them passed every test. Dekker's split with
``2²⁸ + 2`` (products of the halves no longer exact) left ``_exact_residual`` a few
ulps off; the scaling of ``_scaled_inverse_parts`` by ``2^-e`` instead of
``2^-(e // 2)`` left a diagonal far from [0.5, 2); its condition number took twice the
reciprocal of the smallest pivot; and ``_refined_inverse``'s error bound cubed ε κ
instead of squaring it, a bound that no longer bounds. Each is checked here against
its docstring with ``fractions.Fraction``.
"""

from __future__ import annotations

import sys
from fractions import Fraction
from pathlib import Path

import numpy as np

from navkit.estimation import ExtendedKalmanFilter
from navkit.estimation import _ekf_kernels as kernels

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from exact_fractions import fractions, inverse

_EPS = 2.0**-53


def _spd(rng: np.random.Generator, n: int, log_kappa: float, log_scale: float) -> np.ndarray:
    """A symmetric positive definite matrix of condition about 10**log_kappa, badly scaled."""
    q, _ = np.linalg.qr(rng.normal(size=(n, n)))
    eig = 10.0 ** np.linspace(0.0, log_kappa, n)
    a = (q * eig) @ q.T
    s = 10.0 ** rng.uniform(-log_scale, log_scale, n)
    a = a * s * s[:, None]
    return 0.5 * (a + a.T)


def test_exact_residual_is_the_exact_value_rounded_once() -> None:
    rng = np.random.default_rng(37)
    for _ in range(40):
        n, k, q = (int(v) for v in rng.integers(1, 5, 3))
        # Full 53-bit significands at mixed exponents: every product has a rounding
        # error that only an exact split recovers.
        a = rng.normal(size=(n, k)) * 2.0 ** rng.integers(-30, 30, (n, k))
        b = rng.normal(size=(k, q)) * 2.0 ** rng.integers(-30, 30, (k, q))
        c = a @ b * (1.0 + 1e-9 * rng.normal(size=(n, q)))  # the result cancels
        got = kernels._exact_residual(a, b, c)
        fa, fb, fc = fractions(a), fractions(b), fractions(c)
        for i in range(n):
            for j in range(q):
                exact = sum((fa[i][t] * fb[t][j] for t in range(k)), Fraction(0)) - fc[i][j]
                assert got[i, j] == float(exact), (i, j)


def test_exact_residual_recovers_each_product_s_rounding_error() -> None:
    # a b - fl(a b), one term: the rounding error of the product itself (TwoProduct),
    # 2^-53 of it, exact only with every partial product of the halves exact.
    rng = np.random.default_rng(53)
    a = rng.uniform(1.0, 2.0, (300, 1)) * 2.0 ** rng.integers(-40, 40, (300, 1))
    b = rng.uniform(1.0, 2.0, (1, 300)) * 2.0 ** rng.integers(-40, 40, (1, 300))
    got = kernels._exact_residual(a, b, a @ b)
    for i in range(300):
        exact = Fraction(a[i, 0]) * Fraction(b[0, i]) - Fraction(a[i, 0] * b[0, i])
        assert got[i, i] == float(exact), i


def test_product_minus_identity_is_exact_to_one_rounding() -> None:
    rng = np.random.default_rng(8)
    a = _spd(rng, 4, 8.0, 3.0)
    inv = np.linalg.inv(a)
    got = kernels._product_minus_identity(a, inv)
    fa, fi = fractions(a), fractions(inv)
    for i in range(4):
        for j in range(4):
            exact = sum((fa[i][t] * fi[t][j] for t in range(4)), Fraction(0)) - (i == j)
            assert got[i, j] == float(exact)


def test_scaled_inverse_parts_scale_by_powers_of_two_to_a_unit_diagonal() -> None:
    rng = np.random.default_rng(3)
    for _ in range(30):
        n = int(rng.integers(1, 6))
        a = _spd(rng, n, rng.uniform(0.0, 10.0), 40.0)
        found = kernels._scaled_inverse_parts(a)
        assert found is not None
        scaled, inv, d, kappa = found
        mantissa, _ = np.frexp(d)
        assert (mantissa == 0.5).all()  # powers of two: D a D holds a's values exactly
        assert np.array_equal(scaled, a * d * d[:, None])
        diagonal = scaled.diagonal()
        assert ((diagonal >= 0.5) & (diagonal < 2.0)).all()
        # κ: the larger of κ₁ of D a D (with the computed inverse) and 1 / the smallest
        # pivot of its Cholesky factor, each computed here on its own.
        kappa_1 = np.linalg.norm(scaled, 1) * np.linalg.norm(inv, 1)
        pivot = float(np.min(np.linalg.cholesky(scaled).diagonal() ** 2))
        assert kappa == max(kappa_1, 1.0 / pivot)
        assert kappa >= np.linalg.cond(scaled) / n * (1.0 - 1e-12)


def test_a_multiple_of_the_identity_has_condition_one() -> None:
    # κ₁ is 1 to rounding, and every pivot of D a D is in [0.5, 2), its reciprocal at
    # most 2: above 1 only where the pivots are below 1.
    for value in (1.0, 1.5, 1.9, 3.0, 1e-300, 7e300):
        found = kernels._scaled_inverse_parts(np.eye(3) * value)
        assert found is not None
        pivot = found[0][0, 0]
        assert abs(found[3] - max(1.0, 1.0 / pivot)) <= 4.0 * _EPS, value


def test_the_refined_inverse_s_bound_bounds_its_error() -> None:
    # "a bound on the magnitude of its error entry by entry ((4 ε + 2 (ε κ)²) times
    # sqrt(inv_ii inv_jj))": against the exact inverse, up to κ near 1e14.
    rng = np.random.default_rng(26)
    worst = 0.0
    for trial in range(24):
        n = int(rng.integers(2, 5))
        a = _spd(rng, n, 6.0 + 8.0 * trial / 23, 20.0)
        found = kernels._refined_inverse(a)
        assert found is not None
        inv, bound, kappa, _ = found
        exact = inverse(fractions(a))
        error = np.array([[abs(float(Fraction(inv[i, j]) - exact[i][j])) for j in range(n)]
                          for i in range(n)])  # fmt: skip
        assert (error <= bound).all(), (trial, kappa)
        worst = max(worst, float(np.max(error / bound)))
    assert worst > 1e-3  # the bound is reached within a few orders, not vacuous


def test_is_covariance_agrees_with_the_filter_s_own_check() -> None:
    # "as _positive_definite requires of every committed P": the fallbacks' test of an
    # exact posterior takes what the filter takes as a P0, and no more, across the
    # smallest normal pivot (a subnormal variance, or correlated variances whose second
    # pivot is below 2.2e-308).
    rng = np.random.default_rng(308)
    verdicts = set()
    for _ in range(60):
        scale = 10.0 ** rng.uniform(-325.0, -270.0)
        rho = 1.0 - 2.0 ** -rng.uniform(1.0, 50.0)
        a = np.array([[1.0, rho], [rho, 1.0]]) * scale * rng.uniform(1.0, 2.0)
        a = 0.5 * (a + a.T)
        if not a[0, 0] > 0.0:
            continue
        try:
            ExtendedKalmanFilter(np.zeros(2), a)
            taken = True
        except ValueError:
            taken = False
        assert kernels._is_covariance(a) == taken, a.tolist()
        verdicts.add(taken)
    for value in (1e-310, 3e-308):
        a = np.diag([value, 1.0])
        assert kernels._is_covariance(a) == (value >= 2.2250738585072014e-308)
    assert verdicts == {True, False}
