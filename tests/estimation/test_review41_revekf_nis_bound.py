"""Review 41's EKF changes with fresh eyes (REVEKF): the NIS lower bound, inputs, states.

``_nis_lower_bound`` (EKFREV, review 41) gates a computed-singular S past the 24-row
limit on ``Σₖ yₖ² / (m cₖ)``, ``cₖ = uₖ² + Rₖₖ``, lowered by 2⁻³⁰ relative. That is a
true bound of the exact NIS for any positive semidefinite P and R (``|Sₖₗ| <=
sqrt(cₖ cₗ)``, so S <= m C), tight to 2⁻³⁰ for m = 1 and for a rank-one H P Hᵀ with y
along it and R far below it; but among subnormal numbers a rounding is absolute, not
relative, and a cₖ rounded down by up to half of 2⁻¹⁰⁷⁴ put the bound 22 % above the
exact NIS. Pinned here, with the public paths through the bound: every input left as it
was and the state unchanged, whether the update is rejected or refused.
"""

from __future__ import annotations

import math
import sys
from fractions import Fraction
from pathlib import Path

import numpy as np
import pytest
from hypothesis import example, given, settings
from hypothesis import strategies as st

from navkit.errors import FilterError
from navkit.estimation import ExtendedKalmanFilter
from navkit.estimation import _ekf_kernels as kernels

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from exact_fractions import exact_update
from precise_updates import linear, precise_problem

_TINY = 2.0**-1074  # the least subnormal float64


@settings(max_examples=100, deadline=None)
@given(
    m=st.integers(1, 4),
    n=st.integers(1, 3),
    seed=st.integers(0, 2**32 - 1),
    log_y=st.floats(-200.0, -150.0),
)
@example(m=1, n=1, seed=-1, log_y=-160.0)  # c = 2.44 × 2⁻¹⁰⁷⁴ rounded to 2 × 2⁻¹⁰⁷⁴
def test_the_nis_lower_bound_holds_among_subnormal_numbers(
    m: int, n: int, seed: int, log_y: float
) -> None:
    if seed < 0:
        h, p, r = np.array([[0.6]]), np.array([[4 * _TINY]]), np.array([[_TINY]])
        y = np.array([10.0**log_y])
    else:
        rng = np.random.default_rng(seed)
        h = rng.uniform(-1.0, 1.0, (m, n))
        p = np.diag(rng.integers(1, 16, n) * _TINY)
        r = np.diag(rng.integers(1, 16, m) * _TINY)
        # y along H's range (the bound is tightest there), rounded
        y = h @ rng.normal(size=n) * 10.0**log_y
    bound = kernels._nis_lower_bound(p, h, r, y)
    exact = exact_update(np.zeros(h.shape[1]), p, h, r, y)[2]
    # Before: 1012.0 for an exact 829.5 in the pinned example.
    assert bound >= 0.0 and Fraction(bound) <= exact


@settings(max_examples=40, deadline=None)
@given(
    m=st.integers(1, 6),
    n=st.integers(1, 3),
    log_scale=st.floats(-140.0, 140.0),
    log_r=st.floats(-30.0, -8.0),
    seed=st.integers(0, 2**32 - 1),
)
@example(m=1, n=1, log_scale=0.0, log_r=-30.0, seed=0)
def test_the_nis_lower_bound_holds_where_it_is_tight(
    m: int, n: int, log_scale: float, log_r: float, seed: int
) -> None:
    # H P Hᵀ of rank one, R far below it, y along H: for one state the bound within about
    # 2⁻³⁰ + (m - 1) R/(H P Hᵀ) of the exact NIS, so only its 2⁻³⁰ covers the roundings.
    rng = np.random.default_rng(seed)
    base = rng.normal(size=n)
    h = np.outer(rng.normal(size=m), base)
    p = np.diag(10.0 ** rng.uniform(-2.0, 2.0, n)) * 10.0**log_scale
    r = np.eye(m) * float(base @ p @ base) * 10.0**log_r
    y = h @ (base * 10.0 ** (0.5 * log_scale))
    bound = kernels._nis_lower_bound(p, h, r, y)
    exact = exact_update(np.zeros(n), p, h, r, y)[2]
    assert Fraction(bound) <= exact
    if m == n == 1:  # tight: the 2⁻³⁰ is all that lies between them
        assert Fraction(bound) >= exact * Fraction(1 - 2.0**-29)


def _past_the_limit() -> tuple[np.ndarray, ...]:
    """A dense R of 26 components whose computed S is singular (no exact route)."""
    drawn = precise_problem(24, (25, 30))
    assert drawn is not None
    x0, p, h, r, z = drawn
    assert kernels._exact_route(h.shape[1], r) is None
    return x0, p, h, r, z


@pytest.mark.parametrize("gate", [100.0, None, "just above"])
def test_the_bound_s_paths_leave_inputs_and_state_as_they_were(gate: object) -> None:
    x0, p, h, r, z = _past_the_limit()
    far = z + 1e150 * np.sqrt(np.diag(h @ p @ h.T + r)) * np.resize([1.0, -1.0], z.shape)
    ekf = ExtendedKalmanFilter(x0, p)
    if gate == "just above":
        gate = 1.01 * ekf.update(far, linear(h), h, r, gate=100.0).nis
    kept = [a.copy() for a in (x0, p, h, r, far)]
    before_x, before_p = ekf.x.copy(), ekf.P.copy()
    if gate == 100.0:
        result = ekf.update(far, linear(h), h, r, gate=100.0)
        assert not result.accepted and result.status.name == "GATED"
        assert result.reason is not None and "NIS at least" in result.reason
        assert Fraction(result.nis) <= exact_update(x0, p, h, r, far - h @ x0)[2]
    elif gate is None:
        with pytest.raises(FilterError, match="more than 24 rows"):
            ekf.update(far, linear(h), h, r)
    else:
        # Just above the bound: refused before review 43; rejected on the exact NIS
        # (its work within the cap) since (EKFREV5).
        result = ekf.update(far, linear(h), h, r, gate=gate)  # type: ignore[arg-type]
        exact = exact_update(x0, p, h, r, far - h @ x0)[2]
        assert not result.accepted
        if exact > Fraction(sys.float_info.max):  # as the kernel's: not applied, an overflow
            assert result.status.name == "OVERFLOW" and result.nis == math.inf
        else:
            assert result.status.name == "GATED" and result.nis == float(exact)
    for a, b in zip(kept, (x0, p, h, r, far), strict=True):
        assert np.array_equal(a, b)
    assert np.array_equal(ekf.x, before_x) and np.array_equal(ekf.P, before_p)
    # The filter still works: a plain update afterwards is the exact one.
    small = np.eye(1, h.shape[1])
    result = ekf.update(small @ x0 + 1.0, linear(small), small, np.eye(1))
    assert result.accepted


def test_a_nis_bound_beyond_float64_is_an_overflow_with_or_without_a_gate() -> None:
    x0, p, h, r, z = _past_the_limit()
    far = z + 1e170 * np.sqrt(np.diag(h @ p @ h.T + r)) * np.resize([1.0, -1.0], z.shape)
    for gate in (None, 100.0):
        ekf = ExtendedKalmanFilter(x0, p)
        # Before: FilterError without a gate (with one, OVERFLOW): the kernel's path
        # reports a NIS beyond float64 as OVERFLOW, gate or not.
        result = ekf.update(far, linear(h), h, r, gate=gate)
        assert not result.accepted and result.status.name == "OVERFLOW"
        assert result.nis == np.inf
        assert exact_update(x0, p, h, r, far - h @ x0)[2] > Fraction(np.finfo(float).max)
        assert np.array_equal(ekf.x, x0) and np.array_equal(ekf.P, p)


def test_a_nis_lower_bound_whose_terms_sum_beyond_float64_is_finite() -> None:
    # S = 1 1ᵀ + 1e-10 I, y along 1: each term y²/c = 1e308, their sum beyond float64,
    # the bound (their mean) and the exact NIS both about 1e308.
    m = 4
    h, p, r = np.ones((m, 1)), np.ones((1, 1)), 1e-10 * np.eye(m)
    y = np.full(m, 1e154)
    bound = kernels._nis_lower_bound(p, h, r, y)
    exact = exact_update(np.zeros(1), p, h, r, y)[2]
    assert exact < Fraction(np.finfo(float).max)
    assert np.isfinite(bound) and Fraction(bound) <= exact  # before: inf
    assert Fraction(bound) >= exact / 2


def test_a_singular_r_block_past_the_limit_leaves_inputs_and_state_as_they_were() -> None:
    # EKFREV's R: a 2 x 2 block singular in exact arithmetic among 25 components.
    m, n = 25, 3
    a, b = 58_893_648, 65_446_701
    r = np.eye(m) * 2.0**-40
    r[:2, :2] = np.array([[a * a, a * b], [a * b, b * b]], dtype=float) * 2.0**-92
    rng = np.random.default_rng(2)
    h = rng.normal(size=(m, n))
    x0, p = np.zeros(n), np.eye(n)
    z = h @ rng.normal(size=n) + 1e-6 * rng.normal(size=m)
    kept = [v.copy() for v in (x0, p, h, r, z)]
    ekf = ExtendedKalmanFilter(x0, p)
    for gate in (None, 1e300):
        with pytest.raises(FilterError, match="is singular"):
            ekf.update(z, linear(h), h, r, gate=gate)
        for want, got in zip(kept, (x0, p, h, r, z), strict=True):
            assert np.array_equal(want, got)
        assert np.array_equal(ekf.x, x0) and np.array_equal(ekf.P, p)
