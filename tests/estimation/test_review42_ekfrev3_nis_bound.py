"""Review 42 (EKFREV3): the NIS lower bound past the 24-row limit is ``maxₖ yₖ² / dₖ``.

A computed-singular S with no exact route (a dense R of more than 24 components) is
gated on a lower bound of its exact NIS before it is refused (review 41). That bound
was the mean ``Σₖ yₖ² / (m cₖ)``; for a positive definite S each ``yₖ² / Sₖₖ`` is one
(``yₖ² = (eₖᵀ y)² <= Sₖₖ yᵀ S⁻¹ y``, Cauchy-Schwarz), so with dₖ an upper bound of the
exact Sₖₖ (the least of cₖ and the computed Sₖₖ plus its rounding) the largest quotient
is too, never below the mean, and up to m cₖ / Sₖₖ times above it: one reading far off
among 26 was refused with ``FilterError`` where its exact NIS is 10 times the gate.
"""

from __future__ import annotations

import math
import sys
from fractions import Fraction
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from navkit.estimation import ExtendedKalmanFilter
from navkit.estimation import _ekf_kernels as kernels

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from exact_fractions import exact_innovation, exact_update
from precise_updates import linear, precise_problem

_MAX = Fraction(np.finfo(float).max)


def _exact_nis(p: np.ndarray, h: np.ndarray, r: np.ndarray, y: np.ndarray) -> Fraction:
    """``yᵀ S⁻¹ y`` exactly (the NIS alone: no gain, no posterior)."""
    m = h.shape[0]
    _, s_inv = exact_innovation(p, h, r)
    yf = [Fraction(v) for v in y.tolist()]
    return sum((yf[a] * s_inv[a][b] * yf[b] for a in range(m) for b in range(m)), Fraction(0))


def test_one_reading_far_off_past_the_limit_is_rejected_by_the_gate() -> None:
    # Review 41's dense R of 26 components, S singular as computed; one reading 100
    # deviations off: exact NIS about 1e4, the mean bound about 1e4 / 26 below a gate of
    # 1000 (FilterError before), the largest quotient about 9.5e3 above it.
    x0, p, h, r, z = precise_problem(24, (25, 30))  # type: ignore[misc]
    assert kernels._exact_route(h.shape[1], r) is None
    far = z.copy()
    far[0] += 100.0 * math.sqrt(float((h @ p @ h.T + r)[0, 0]))
    kept = [a.copy() for a in (x0, p, h, r, far)]
    ekf = ExtendedKalmanFilter(x0, p)
    result = ekf.update(far, linear(h), h, r, gate=1000.0)
    assert not result.accepted and result.status.name == "GATED"
    assert result.reason is not None and "NIS at least" in result.reason
    exact = exact_update(x0, p, h, r, far - h @ x0)[2]
    assert result.nis > 1000.0 and Fraction(result.nis) <= exact
    for a, b in zip(kept, (x0, p, h, r, far), strict=True):
        assert np.array_equal(a, b)
    assert np.array_equal(ekf.x, x0) and np.array_equal(ekf.P, p)


@pytest.mark.parametrize("delta", [1e-3, 1e-9, 2.0**-40])
def test_a_difference_of_correlated_states_is_bounded_by_its_own_variance(delta: float) -> None:
    # x₀ - x₁ with correlation 1 - δ: S = 2δ + R, cₖ = 4 + R. For one component the
    # bound is y² / (S + 2⁻²⁹ cₖ) or more, S's rounding bounded (before: about
    # y² / (4 + R), 2 / δ times lower).
    p = np.array([[1.0, 1.0 - delta], [1.0 - delta, 1.0]])
    h, r, y = np.array([[1.0, -1.0]]), np.array([[1e-20]]), np.array([0.3])
    bound = kernels._nis_lower_bound(p, h, r, y)
    exact = _exact_nis(p, h, r, y)
    assert Fraction(bound) <= exact
    s_exact = Fraction(y[0]) ** 2 / exact
    assert Fraction(bound) >= Fraction(y[0]) ** 2 / (s_exact + Fraction(2.0**-29) * 4)


def _mean_bound(p: np.ndarray, h: np.ndarray, r: np.ndarray, y: np.ndarray) -> Fraction:
    """Review 41's ``Σₖ yₖ² / (m cₖ)``, exactly but for the square roots of P's diagonal."""
    m = h.shape[0]
    roots = [Fraction(math.sqrt(v)) for v in np.diag(p).tolist()]
    total = Fraction(0)
    for k in range(m):
        reach = sum((abs(Fraction(v)) * s for v, s in zip(h[k].tolist(), roots, strict=True)))
        total += Fraction(float(y[k])) ** 2 / (reach * reach + Fraction(float(r[k, k])))
    return total / m


def _draw(seed: int, m: int, n: int, low: float, high: float) -> tuple[np.ndarray, ...] | None:
    """P, H, R, y at scales 10**low to 10**high, with -0.0s, exact zeros and subnormal H."""
    rng = np.random.default_rng(seed)

    def spd(size: int) -> np.ndarray:
        q, _ = np.linalg.qr(rng.normal(size=(size, size)))
        a = (q * 10.0 ** np.linspace(0.0, rng.uniform(0.0, 12.0), size)) @ q.T
        d = np.sqrt(np.diag(a))
        c = a / d / d[:, None]
        np.fill_diagonal(c, 1.0)
        scales = 10.0 ** (rng.uniform(low, high, size) / 2.0)
        return 0.5 * (c + c.T) * scales * scales[:, None]

    p = spd(n)
    if rng.random() < 0.3:
        p = np.diag(np.diag(p))
    r = spd(m) if rng.random() < 0.5 else np.diag(10.0 ** rng.uniform(low, high, m))
    if rng.random() < 0.3:  # exact zeros off R's diagonal
        mask = rng.random((m, m)) < 0.5
        mask = mask | mask.T
        np.fill_diagonal(mask, False)
        r[mask] = 0.0
    h = rng.normal(size=(m, n)) * 10.0 ** rng.uniform(low / 2, high / 2, (m, n))
    h[rng.random((m, n)) < 0.3] = -0.0
    if rng.random() < 0.2:
        h[rng.random((m, n)) < 0.5] *= 2.0**-1060  # subnormal entries
    y = h @ rng.normal(size=n) * 10.0 ** rng.uniform(low / 2, high / 2)
    y += rng.normal(size=m) * np.sqrt(np.diag(r)) * (rng.random() < 0.5)
    y[rng.random(m) < 0.2] = -0.0
    arrays = (p, h, r, y)
    if not all(np.isfinite(a).all() for a in arrays):
        return None
    with np.errstate(all="ignore"):  # the kernel raises where S overflows
        if not np.isfinite(h @ p @ h.T + r).all():
            return None
    if (np.diag(p) <= 0.0).any() or (np.diag(r) <= 0.0).any():
        return None
    try:
        np.linalg.cholesky(p)
        np.linalg.cholesky(r)
    except np.linalg.LinAlgError:
        return None
    return arrays


@settings(max_examples=60, deadline=None)
@given(
    seed=st.integers(0, 2**32 - 1),
    m=st.integers(1, 6),
    n=st.integers(1, 4),
    ends=st.tuples(st.floats(-300.0, 300.0), st.floats(-300.0, 300.0)),
)
def test_the_bound_is_below_the_exact_nis_and_not_below_the_mean(
    seed: int, m: int, n: int, ends: tuple[float, float]
) -> None:
    low, high = sorted(ends)
    drawn = _draw(seed, m, n, low, high)
    if drawn is None:
        return
    p, h, r, y = drawn
    kept = [a.copy() for a in drawn]
    with np.errstate(all="ignore"):
        bound = kernels._nis_lower_bound(p, h, r, y)
    for a, b in zip(kept, drawn, strict=True):
        assert np.array_equal(a, b) and np.array_equal(np.signbit(a), np.signbit(b))
    exact = _exact_nis(p, h, r, y)
    if exact <= 0:  # S positive definite only as rounded
        return
    if bound == math.inf:
        assert exact > _MAX
        return
    assert bound >= 0.0 and Fraction(bound) <= exact
    # Never below review 41's mean but for the roundings of cₖ (2⁻³⁰) and subnormals.
    assert Fraction(bound) >= _mean_bound(p, h, r, y) * Fraction(1 - 2.0**-29) - Fraction(
        2.0**-1000
    )


@pytest.mark.slow
@settings(max_examples=10, deadline=None)
@given(seed=st.integers(0, 2**32 - 1), m=st.integers(25, 30), n=st.integers(1, 3))
def test_the_bound_is_below_the_exact_nis_past_the_limit(seed: int, m: int, n: int) -> None:
    drawn = _draw(seed, m, n, -100.0, 100.0)
    if drawn is None:
        return
    p, h, r, y = drawn
    bound = kernels._nis_lower_bound(p, h, r, y)
    exact = _exact_nis(p, h, r, y)
    if exact > 0 and bound < math.inf:
        assert Fraction(bound) <= exact
