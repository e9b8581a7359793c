"""PlanarFusion's covariance update stays exact to rounding for any documented variances.

The Joseph form used ``A = I - K H`` also in the rows of the observed states, where
it is ``R S⁻¹``: ``1 - K`` cancels and leaves about ``ε² P`` for a gain rounded by
``ε``. Once a measurement is much more precise than the estimate (``R < ε² P``,
variances and covariances may be anywhere in [1e-100, 1e100]) the posterior
variance of the observed state came out as that noise (4e68 instead of 1e-100),
its cross-covariances were wrong by orders of magnitude (already 7e-8 relative
at ``P/R`` 3e10) and some updates raised ``FilterError`` (not positive definite).

The references are exact: ``fractions.Fraction`` arithmetic on the float inputs,
``P - P Hᵀ (H P Hᵀ + R)⁻¹ H P``, rounded once at the end. Priors are well
conditioned (condition number up to 1e3), so the exact posterior is well
conditioned relative to the prior and a few float64 roundings are all it may
lose; errors are compared with ``sqrt(P⁺ᵢᵢ P⁺ⱼⱼ)`` of the exact posterior.
"""

from __future__ import annotations

from fractions import Fraction

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from exact_fractions import inverse
from navkit.estimation import FusionStatus, MeasurementLog, PlanarFusion

# Entries a few roundings off, relative to the posterior's own scale.
TOLERANCE = 1e-12


def exact_posterior(prior: np.ndarray, variances: list[float], states: list[int]) -> np.ndarray:
    """``P - P Hᵀ S⁻¹ H P`` with H selecting ``states``, exactly, rounded at the end."""
    p = [[Fraction(v) for v in row] for row in prior.tolist()]
    m = len(states)
    s = [
        [p[states[a]][states[b]] + (Fraction(variances[a]) if a == b else 0) for b in range(m)]
        for a in range(m)
    ]
    s_inv = inverse(s)
    out = np.empty((6, 6))
    for i in range(6):
        for j in range(6):
            v = p[i][j]
            for a in range(m):
                for b in range(m):
                    v -= p[i][states[a]] * s_inv[a][b] * p[states[b]][j]
            out[i, j] = float(v)
    return out


def relative_error(got: np.ndarray, exact: np.ndarray) -> float:
    scale = np.sqrt(np.diag(exact))
    return float(np.max(np.abs(got - exact) / np.outer(scale, scale)))


def test_a_precise_speed_on_a_vague_estimate_known_case() -> None:
    # Prior variance 1e100 everywhere, a speed measured with variance 1e-100: the
    # posterior variance of v is 1e-100 (it was 4.3e68).
    fusion = PlanarFusion(P0=np.full(6, 1e100), t0=0.0, process_noise=np.zeros(6))
    assert fusion.update_speed(0.0, 1.0, variance=1e-100).accepted
    p = fusion.P
    assert abs(p[3, 3] / 1e-100 - 1.0) < 1e-15
    assert np.all(np.delete(np.diag(p), 3) == 1e100)


def test_a_precise_speed_keeps_the_cross_covariance_known_case() -> None:
    # v and a correlated (0.5); the posterior cross-covariance is ρ√(P_vv P_aa) R / S.
    # At R = 1e-20 it came out -2.5e3 times that; at 1e-100 the update raised
    # FilterError once the variance of v was right.
    for variance in (1e-10, 1e-20, 1e-40, 1e-100):
        prior = np.eye(6) * 3.7
        prior[3, 3] = 2.9
        prior[3, 5] = prior[5, 3] = 0.5 * np.sqrt(2.9 * 3.7)
        fusion = PlanarFusion(P0=prior, t0=0.0, process_noise=np.zeros(6))
        assert fusion.update_speed(0.0, 1.0, variance=variance).accepted
        exact = exact_posterior(prior, [variance], [3])
        assert relative_error(fusion.P, exact) < TOLERANCE


priors = st.tuples(
    st.lists(st.floats(-3.0, 0.0), min_size=6, max_size=6),  # log10 eigenvalues
    st.integers(0, 2**32 - 1),  # seed of the eigenvectors
    st.floats(-40.0, 40.0),  # log10 scale
)


def prior_matrix(log_eigenvalues: list[float], seed: int, log_scale: float) -> np.ndarray:
    q, _ = np.linalg.qr(np.random.default_rng(seed).standard_normal((6, 6)))
    p = (q * 10.0 ** np.array(log_eigenvalues)) @ q.T * 10.0**log_scale
    out: np.ndarray = 0.5 * (p + p.T)
    return out


@settings(max_examples=60, deadline=None)
@given(
    prior=priors,
    log_variances=st.lists(st.floats(-100.0, 40.0), min_size=4, max_size=4),
    observed=st.lists(st.booleans(), min_size=4, max_size=4).filter(any),
)
def test_every_update_is_the_exact_posterior_to_rounding(
    prior: tuple[list[float], int, float], log_variances: list[float], observed: list[bool]
) -> None:
    p = prior_matrix(*prior)
    variances = [10.0**v for v in log_variances]
    fusion = PlanarFusion(P0=p, t0=0.0, process_noise=np.zeros(6))
    log = MeasurementLog(
        times=[0.0], values=[[0.1, 0.2, 0.3, 0.4]], variances=[variances], observed=[observed]
    )
    result = fusion.update_batch(log)
    # Always applied: a well-conditioned prior and any variances give a positive
    # definite posterior (the old update refused about one in eight).
    assert result.status[0] == FusionStatus.ACCEPTED
    seen = [k for k in range(4) if observed[k]]
    exact = exact_posterior(p, [variances[k] for k in seen], [k + 2 for k in seen])
    assert relative_error(fusion.P, exact) < TOLERANCE
    np.testing.assert_array_equal(fusion.P, fusion.P.T)


@settings(max_examples=40, deadline=None)
@given(prior=priors, log_variances=st.tuples(st.floats(-100.0, 40.0), st.floats(-100.0, 40.0)))
def test_online_odometry_update_is_the_exact_posterior_to_rounding(
    prior: tuple[list[float], int, float], log_variances: tuple[float, float]
) -> None:
    # The online path (the fast path for floats) computes with the same kernel.
    p = prior_matrix(*prior)
    v_var, w_var = (10.0**v for v in log_variances)
    fusion = PlanarFusion(P0=p, t0=0.0, process_noise=np.zeros(6))
    assert fusion.update_odometry(0.0, 0.1, 0.2, v_variance=v_var, omega_variance=w_var).accepted
    exact = exact_posterior(p, [v_var, w_var], [3, 4])
    assert relative_error(fusion.P, exact) < TOLERANCE
