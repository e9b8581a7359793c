"""The EKF's precise updates of more than 24 components (review 41, EKFREV).

Session 44 (review 40) made precise updates of more than 12 components exact, by S's
elimination or, for a diagonal or block-diagonal R, the information form in exact
arithmetic (``_ExactUpdate``, any number of components), and refused unvouched updates
whose exact arithmetic would eliminate more than ``_EXACT_ELIMINATION_MAX`` (24) rows.
Three leftovers, each pinned here:

* The update kernel's test of an ill-conditioned S (then the exact NIS, gated again)
  and ``retry_gated`` stopped at 24 components, though a diagonal R has an exact route
  for any number: 25 readings of one poorly known combination of states reported a NIS
  4.1e-8 relative off, and a gate between it and the exact one decided wrongly.
* An R block singular in exact arithmetic (positive definite only as rounded) sent
  ``_ExactUpdate`` to S's elimination of every component, past the limit (a 60-row
  elimination took 2.9 s, growing as m³).
* A computed S that is not positive definite past the limit raised ``FilterError``
  before any gate: readings 1e150 deviations apart were refused, not rejected. They are
  now gated on a lower bound of the exact NIS (``_nis_lower_bound``).
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
from test_review40_ekfbig2_exact_large_measurements import _ill_conditioned

from exact_fractions import exact_update
from precise_updates import linear, precise_problem, spd


def _combination_readings(seed: int, m: int) -> tuple[np.ndarray, ...]:
    """m readings of about one combination of states (the least known), R diagonal.

    Review 40's ``_ill_conditioned`` with independent readings of distinct
    variances: κ(S) large, no variance shrinking 4096-fold.
    """
    return _ill_conditioned(seed, m, diagonal=True)


@pytest.mark.parametrize(
    "seed, m, before",
    [
        (59, 25, -4.0606e-8),
        (6, 25, 3.0582e-9),
        pytest.param(20, 40, -5.506e-10, marks=pytest.mark.slow),
    ],
)
def test_an_ill_conditioned_s_past_the_limit_with_a_diagonal_r_gets_the_exact_nis(
    seed: int, m: int, before: float
) -> None:
    # The kernel's NIS was `before` relative below the exact one (above where negative).
    x0, p, h, r, z = _combination_readings(seed, m)
    assert m > kernels._EXACT_ELIMINATION_MAX
    assert kernels._exact_route(len(x0), r) == [[i] for i in range(m)]
    ekf = ExtendedKalmanFilter(x0, p)
    result = ekf.update(z, linear(h), h, r)
    assert result.accepted
    x_exact, p_exact, nis = exact_update(x0, p, h, r, z - h @ x0)
    assert result.nis == float(nis)
    unit = np.sqrt(np.array([float(p_exact[i][i]) for i in range(len(x0))]))
    x_round = np.array([float(v) for v in x_exact])
    assert np.all(np.abs(ekf.x - x_round) <= 2.0**-20 * unit)
    # A gate between the kernel's NIS and the exact one decides by the exact one (it
    # decided the other way before).
    gate = float(nis) * (1.0 - before / 2.0)
    gated = ExtendedKalmanFilter(x0, p).update(z, linear(h), h, r, gate=gate)
    assert gated.accepted is (before < 0.0)
    assert gated.nis == float(nis)


def _singular_block(m: int) -> np.ndarray:
    """A diagonal R of m components but for a 2 x 2 block singular in exact arithmetic.

    ``[[a², a b], [a b, b²]]`` with 26-bit a and b: every entry exact, the exact
    determinant 0, but LDLᵀ in float64 finds a positive second pivot (a rounding),
    so R passes the filter's check.
    """
    a, b = 58_893_648, 65_446_701
    r = np.eye(m) * 2.0**-40
    r[:2, :2] = np.array([[a * a, a * b], [a * b, b * b]], dtype=float) * 2.0**-92
    assert Fraction(r[0, 0]) * Fraction(r[1, 1]) == Fraction(r[0, 1]) ** 2
    return r


def test_a_singular_r_block_does_not_bypass_the_elimination_limit(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    m, n = 25, 3
    r = _singular_block(m)
    rng = np.random.default_rng(2)
    h = rng.normal(size=(m, n))
    x0 = np.zeros(n)
    p = np.eye(n)
    z = h @ rng.normal(size=n) + 1e-6 * rng.normal(size=m)
    assert kernels._exact_route(n, r) is not None  # R's blocks: the information route
    rows: list[int] = []
    eliminated = kernels._eliminated

    def recorded(*args: np.ndarray) -> kernels._Elimination:
        rows.append(args[1].shape[0])
        return eliminated(*args)

    monkeypatch.setattr(kernels, "_eliminated", recorded)
    ekf = ExtendedKalmanFilter(x0, p)
    with pytest.raises(FilterError, match=r"R's block of components \[0, 1\] is singular"):
        ekf.update(z, linear(h), h, r)
    # Before: S's elimination of all 25 rows (then a refusal for another reason).
    assert all(size <= kernels._EXACT_ELIMINATION_MAX for size in rows), rows
    assert np.array_equal(ekf.x, x0) and np.array_equal(ekf.P, p)


def _far_readings() -> tuple[np.ndarray, ...]:
    """A dense R of 26 components whose computed S is singular (review 40's REVE draw)."""
    drawn = precise_problem(24, (25, 30))
    assert drawn is not None
    x0, p, h, r, z = drawn
    assert kernels._exact_route(h.shape[1], r) is None
    return x0, p, h, r, z


def test_readings_far_apart_past_the_limit_are_rejected_by_the_gate() -> None:
    x0, p, h, r, z = _far_readings()
    far = z + 1e150 * np.sqrt(np.diag(h @ p @ h.T + r)) * np.resize([1.0, -1.0], z.shape)
    ekf = ExtendedKalmanFilter(x0, p)
    result = ekf.update(far, linear(h), h, r, gate=100.0)
    # Before: FilterError (S not positive definite past the limit).
    assert not result.accepted
    assert result.reason is not None and result.reason.startswith(
        "rejected by the gate: NIS at least"
    )
    assert result.status.name == "GATED"
    assert result.nis > 100.0
    assert Fraction(result.nis) <= exact_update(x0, p, h, r, far - h @ x0)[2]
    assert np.array_equal(ekf.x, x0) and np.array_equal(ekf.P, p)
    # Without a gate it is refused as before. With one the bound does not exceed, it
    # was refused too before review 43; now the exact NIS (its work within the cap)
    # rejects it (EKFREV5).
    with pytest.raises(FilterError, match=f"more than {kernels._EXACT_ELIMINATION_MAX} rows"):
        ekf.update(far, linear(h), h, r)
    assert np.array_equal(ekf.x, x0) and np.array_equal(ekf.P, p)
    exact = exact_update(x0, p, h, r, far - h @ x0)[2]
    above = ekf.update(far, linear(h), h, r, gate=1.01 * result.nis)
    assert not above.accepted and above.reason is not None and "at least" not in above.reason
    if exact > Fraction(sys.float_info.max):  # as the kernel's: not applied, an overflow
        assert above.status.name == "OVERFLOW" and above.nis == math.inf
    else:
        assert above.status.name == "GATED" and above.nis == float(exact)
    assert np.array_equal(ekf.x, x0) and np.array_equal(ekf.P, p)


@settings(max_examples=60, deadline=None)
@given(
    seed=st.integers(0, 2**32 - 1),
    n=st.integers(1, 4),
    m=st.integers(1, 5),
    log_kappa=st.floats(0.0, 8.0),
    log_scale=st.floats(0.0, 6.0),
)
@example(seed=0, n=1, m=1, log_kappa=0.0, log_scale=0.0)
def test_the_nis_lower_bound_is_below_the_exact_nis(
    seed: int, n: int, m: int, log_kappa: float, log_scale: float
) -> None:
    rng = np.random.default_rng(seed)
    p = spd(rng, n, log_kappa, log_scale)
    r = spd(rng, m, log_kappa, log_scale)
    h = rng.normal(size=(m, n)) * 10.0 ** rng.uniform(-log_scale, log_scale, (m, n))
    y = rng.normal(size=m) * 10.0 ** rng.uniform(-log_scale, log_scale, m)
    bound = kernels._nis_lower_bound(p, h, r, y)
    assert 0.0 <= bound <= exact_update(np.zeros(n), p, h, r, y)[2]


def _fraction_solution(a: list[list[int]], b: list[list[int]]) -> list[list[Fraction]] | None:
    """``a⁻¹ b`` in Fractions (Gauss-Jordan with row exchanges), None if ``a`` is singular."""
    k = len(a)
    rows = [[Fraction(v) for v in a[i] + b[i]] for i in range(k)]
    for col in range(k):
        at = next((i for i in range(col, k) if rows[i][col]), None)
        if at is None:
            return None
        rows[col], rows[at] = rows[at], rows[col]
        rows[col] = [v / rows[col][col] for v in rows[col]]
        for i in range(k):
            if i != col and rows[i][col]:
                factor = rows[i][col]
                rows[i] = [u - factor * v for u, v in zip(rows[i], rows[col], strict=True)]
    return [row[k:] for row in rows]


@settings(max_examples=200, deadline=None)
@given(
    data=st.data(),
    k=st.integers(1, 6),
    q=st.integers(1, 3),
)
@example(data=None, k=2, q=1)
def test_the_one_bareiss_elimination_solves_exactly(
    data: st.DataObject | None, k: int, q: int
) -> None:
    # _eliminated, _exact_posterior's replay and _bareiss_solve share one loop since
    # review 41 (the same integers, checked against review 40's three, bit for bit, in
    # 400 random draws); here the solve with row exchanges and singular matrices.
    if data is None:  # a zero first pivot: the rows exchanged
        a, b = [[0, 1], [1, 0]], [[3], [-5]]
    else:
        small = st.integers(-2, 2)
        a = data.draw(st.lists(st.lists(small, min_size=k, max_size=k), min_size=k, max_size=k))
        big = st.integers(-(10**30), 10**30)
        b = data.draw(st.lists(st.lists(big, min_size=q, max_size=q), min_size=k, max_size=k))
    found = kernels._bareiss_solve(a, b)
    want = _fraction_solution(a, b)
    if want is None:
        assert found is None
        return
    assert found is not None
    numerators, det = found
    assert det > 0
    assert [[Fraction(v, det) for v in row] for row in numerators] == want
