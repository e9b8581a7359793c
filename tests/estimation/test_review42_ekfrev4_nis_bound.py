"""Review 42 (EKFREV4): the NIS lower bound's rounding margins, against exact Sₖₖ.

``_nis_lower_bound`` divides each yₖ² by an upper bound dₖ of the exact Sₖₖ: the
computed Hₖ P Hₖᵀ + Rₖₖ raised by 2⁻³⁰ uₖ² + 2⁻³¹ Rₖₖ and, among subnormal numbers, an
absolute slack. Review 42's own tests drew at most 4 states; here up to 150, with
strongly correlated states (Hₖ P Hₖᵀ cancelling far below uₖ²) and scales from
subnormal to 1e300. The bound must not exceed ``maxₖ yₖ² / Sₖₖ`` taken exactly
(without the margin the computed Sₖₖ fell below the exact one in 33 of 200 draws;
without the subnormal slack in 71 of 257 draws of a P near 2⁻¹⁰⁶⁰; without cₖ's
factor 1 + 2⁻³¹ in the pinned draw of one state).
"""

from __future__ import annotations

import math
from fractions import Fraction

import numpy as np
from hypothesis import example, given, settings
from hypothesis import strategies as st

from navkit.estimation._ekf_kernels import _nis_lower_bound


def _exact_diagonal(p: np.ndarray, h: np.ndarray, r: np.ndarray) -> list[Fraction]:
    """The exact Sₖₖ = Hₖ P Hₖᵀ + Rₖₖ of the float inputs."""
    pf = [[Fraction(v) for v in row] for row in p.tolist()]
    out = []
    for k in range(h.shape[0]):
        hk = [Fraction(v) for v in h[k].tolist()]
        used = [i for i, v in enumerate(hk) if v]
        quad = sum((hk[i] * pf[i][j] * hk[j] for i in used for j in used), Fraction(0))
        out.append(quad + Fraction(float(r[k, k])))
    return out


def _pairs_bounded(p: np.ndarray) -> bool:
    """|Pᵢⱼ| <= sqrt(Pᵢᵢ Pⱼⱼ) exactly (as a covariance's entries are)."""
    d = [Fraction(v) for v in p.diagonal().tolist()]
    rows = p.tolist()
    return all(Fraction(rows[i][j]) ** 2 <= d[i] * d[j] for i in range(len(d)) for j in range(i))


@settings(max_examples=60, deadline=None)
@given(
    seed=st.integers(0, 2**32 - 1),
    n=st.sampled_from([1, 2, 3, 5, 20, 60, 150]),
    m=st.integers(1, 3),
    kind=st.sampled_from(["correlated", "diagonal", "dense"]),
    p_exp=st.integers(-1100, 1000),
    h_exp=st.integers(-200, 200),
    r_exp=st.integers(-1100, 1000),
)
# One state: uₖ² rounded below the exact Hₖ P Hₖᵀ, where cₖ without its 2⁻³¹ is less
# than the computed Sₖₖ with its margin, and taken.
@example(seed=220, n=1, m=1, kind="correlated", p_exp=0, h_exp=0, r_exp=0)
def test_the_bound_is_below_each_readings_exact_quotient(
    seed: int, n: int, m: int, kind: str, p_exp: int, h_exp: int, r_exp: int
) -> None:
    rng = np.random.default_rng(seed)
    if kind == "correlated":  # v vᵀ plus a little: H = sign(v) cancels
        v = rng.standard_normal(n)
        p = np.outer(v, v)
        p += np.diag(np.abs(p).sum(axis=1) * 2.0 ** -int(rng.integers(0, 60)))
    elif kind == "diagonal":
        p = np.diag(rng.random(n) + 0.1)
    else:
        a = rng.standard_normal((n, n))
        p = a @ a.T + n * np.eye(n) * 2.0 ** -int(rng.integers(0, 50))
    p = (p + p.T) / 2 * 2.0**p_exp
    h = rng.standard_normal((m, n)) * 2.0 ** rng.integers(-60, 60, size=(m, n))
    if kind == "correlated":
        h[0] = np.sign(v) * np.where(rng.random(n) < 0.5, 1.0, -1.0)
    h *= 2.0**h_exp
    r = np.diag(rng.random(m) * 2.0**r_exp)
    with np.errstate(all="ignore"):
        finite = np.isfinite(p).all() and np.isfinite(h @ p @ h.T).all()
    if not finite or not _pairs_bounded(p):
        return
    s_diag = _exact_diagonal(p, h, r)
    if not all(s > 0 for s in s_diag):
        return
    deviations = np.sqrt([float(s) for s in s_diag])
    y = rng.standard_normal(m) * deviations * 2.0 ** rng.integers(0, 40, size=m)
    if not (np.isfinite(y).all() and y.any()):
        return
    bound = _nis_lower_bound(p, h, r, y)
    exact = max(Fraction(float(y[k])) ** 2 / s_diag[k] for k in range(m))
    if bound == math.inf:  # beyond float64: the exact quotient must be too
        assert exact > Fraction(np.finfo(float).max)
    else:
        assert Fraction(bound) <= exact


@settings(max_examples=60, deadline=None)
@given(
    seed=st.integers(0, 2**32 - 1),
    n=st.sampled_from([2, 5, 20, 60]),
    p_exp=st.integers(-1080, -1040),
    h_exp=st.integers(-3, 8),
    r_exp=st.integers(-1200, -1060),
)
def test_the_bound_is_below_the_exact_quotient_among_subnormal_products(
    seed: int, n: int, p_exp: int, h_exp: int, r_exp: int
) -> None:
    # P near the subnormal range, H near 1 and R at most subnormal: each product of
    # H P rounds absolutely, below the relative margin (2⁻³⁰ uₖ² underflows): only the
    # absolute slack keeps dₖ above the exact Sₖₖ.
    rng = np.random.default_rng(seed)
    a = rng.standard_normal((n, n))
    p = a @ a.T + np.eye(n)
    p = (p + p.T) / 2 * 2.0**p_exp
    h = rng.standard_normal((1, n)) * 2.0**h_exp
    r = np.array([[rng.random() * 2.0**r_exp]])
    if not _pairs_bounded(p):
        return
    s_diag = _exact_diagonal(p, h, r)[0]
    if not s_diag > 0:
        return
    y = np.array([math.sqrt(float(s_diag)) * 2.0**30])
    bound = _nis_lower_bound(p, h, r, y)
    assert Fraction(bound) <= Fraction(float(y[0])) ** 2 / s_diag
