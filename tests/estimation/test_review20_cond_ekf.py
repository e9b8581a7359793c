"""Conditioning review: EKF updates whose computed innovation covariance S is singular.

P and R are positive definite, so the exact S = H P Hᵀ + R always is; a state
measured twice, each measurement far more precisely than the state is known
(R/P below about 1e-16), rounds S = [[p + r, p], [p, p + r]] to a singular
matrix. Such updates raised ``FilterError`` ("innovation covariance S is not
positive definite") although the posterior is well determined; they now take
the information form, with the NIS from S in exact arithmetic. The reference
here is exact rational arithmetic on the float inputs (tests/exact_fractions.py).
"""

from __future__ import annotations

import sys
from fractions import Fraction
from pathlib import Path

import numpy as np
import pytest
from hypothesis import example, given, settings
from hypothesis import strategies as st

from navkit.errors import FilterError
from navkit.estimation import ExtendedKalmanFilter, FusionStatus
from navkit.estimation._ekf_kernels import _EXACT_ELIMINATION_MAX, _exact_nis

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from exact_fractions import exact_gain, exact_update

pytestmark = pytest.mark.filterwarnings("error::RuntimeWarning")


def _exact(x: np.ndarray, p: np.ndarray, h: np.ndarray, r: np.ndarray, z: np.ndarray):  # type: ignore[no-untyped-def]
    """Exact posterior (x, P) and NIS of the update, as Fractions."""
    # The filter's residual z - h(x), h(x) = H @ x in float64, as the tests' h computes it.
    return exact_update(x, p, h, r, z - h @ x)


def _check(  # type: ignore[no-untyped-def]
    ekf: ExtendedKalmanFilter, x0: np.ndarray, x_exact, p_exact, nis_exact, nis: float
) -> None:
    n = ekf.dim
    sigma = [float(p_exact[i][i]) ** 0.5 for i in range(n)]
    for i in range(n):
        for j in range(n):
            error = abs(float(p_exact[i][j] - Fraction(ekf.P[i, j])))
            assert error <= 1e-12 * sigma[i] * sigma[j], (i, j, ekf.P[i, j], float(p_exact[i][j]))
        # x to within a fraction of the posterior's deviation, or a few ulps where
        # that is below float64's resolution at the size of the prior and posterior
        # states: x + step rounds once to it, and the step carries the roundings of
        # its solves (measured over 9000 updates of the property test's kind: at most
        # 1.8 ulps of the size; on the examples below a float64 information form,
        # sequential Joseph updates and a square-root (QR) update are within 1.4
        # ulps of the exact state). At 16 ulps this let through a filter keeping a
        # state 11-33 ulps, 1-2.6 deviations, off.
        error = abs(float(x_exact[i] - Fraction(ekf.x[i])))
        size = abs(float(x_exact[i])) + abs(float(x0[i]))
        assert error <= 0.25 * sigma[i] + 4 * 2.0**-52 * size, (i, error, sigma[i], size)
    # The NIS: the exact one rounded once where S is ill-conditioned (ε κ(S) > 2⁻³⁰),
    # else the kernel's, within about ε κ(S) <= 1e-9 of it.
    assert abs(nis - float(nis_exact)) <= 1e-8 * float(nis_exact) + 1e-300, (nis, nis_exact)


@pytest.mark.parametrize(
    ("p", "r"),
    [(1e20, 1e-20), (1.0, 1e-17), (1.0, 1e-16), (1e6, 1e-12), (1.0, 1e-30), (1e12, 1e-8)],
)
def test_a_state_measured_twice_precisely_is_applied(p: float, r: float) -> None:
    # Each of these raised FilterError: innovation covariance S is not positive definite.
    x = np.array([0.0, 0.0])
    p0 = np.diag([p, 1.0])
    h = np.array([[1.0, 0.0], [1.0, 0.0]])
    rr = np.diag([r, r])
    z = np.array([1.0, 1.0])
    ekf = ExtendedKalmanFilter(x, p0)
    result = ekf.update(z, lambda s: h @ s, h, rr)
    assert result.accepted
    x_exact, p_exact, nis_exact = _exact(x, p0, h, rr, z)
    _check(ekf, x, x_exact, p_exact, nis_exact, result.nis)
    assert result.nis == float(nis_exact)
    assert ekf.P[0, 0] == float(p_exact[0][0])  # r / 2, nearly: rounded once here


def test_the_singular_s_path_gates_on_the_exact_nis() -> None:
    p0 = np.diag([1e20, 1.0])
    h = np.array([[1.0, 0.0], [1.0, 0.0]])
    rr = np.diag([1e-20, 1e-20])
    z = np.array([1.0, 1.0 + 2e-10])  # the two readings 1.4 of their deviations apart
    _, _, nis_exact = _exact(np.zeros(2), p0, h, rr, z)
    assert 1.0 < float(nis_exact) < 3.0
    ekf = ExtendedKalmanFilter(np.zeros(2), p0)
    result = ekf.update(z, lambda s: h @ s, h, rr, gate=1.0)
    assert not result.accepted
    assert result.status == FusionStatus.GATED
    assert result.nis == float(nis_exact)
    np.testing.assert_array_equal(ekf.x, np.zeros(2))
    np.testing.assert_array_equal(ekf.P, p0)
    result = ekf.update(z, lambda s: h @ s, h, rr, gate=3.0)
    assert result.accepted
    assert result.nis == float(nis_exact)


# A position measured twice in different units, 1e-16 of its variance each: the computed
# S stays positive definite, but with κ(S) 3e16 the kernel's NIS was 21.04 for an exact
# 9.3768 (HEAD at 33e58e0 rejected the measurement at a gate of 11.3).
_P0 = np.array([[22346.388302374035]])
_H = np.array([[0.5], [-1.0]])
_R = np.diag([1.7889116508411613e-12, 1.5158758869751346e-12])
_X0 = np.array([43.57834019027863])
_Z = np.array([94.41555455974368, -188.83110056824205])


@pytest.mark.parametrize("gate", [None, 11.3, 9.0])
def test_an_ill_conditioned_s_is_gated_on_the_exact_nis(gate: float | None) -> None:
    x_exact, p_exact, nis_exact = _exact(_X0, _P0, _H, _R, _Z)
    assert 9.0 < float(nis_exact) < 9.5
    ekf = ExtendedKalmanFilter(_X0, _P0)
    result = ekf.update(_Z, lambda s: _H @ s, _H, _R, gate=gate)
    assert result.nis == float(nis_exact)
    if gate == 9.0:
        assert result.status == FusionStatus.GATED
        np.testing.assert_array_equal(ekf.x, _X0)
        np.testing.assert_array_equal(ekf.P, _P0)
    else:
        assert result.accepted
        _check(ekf, _X0, x_exact, p_exact, nis_exact, result.nis)


def test_larger_measurements_still_raise() -> None:
    # Where the exact arithmetic would eliminate more than _EXACT_ELIMINATION_MAX rows
    # (an R of one dense block that size) it would cost too much: as before. (Before
    # review 40 every measurement of more than 8 components raised here.)
    m = _EXACT_ELIMINATION_MAX + 1
    h = np.zeros((m, 2))
    h[:, 0] = 1.0
    r = np.eye(m) * 1e-20 + np.diag(np.full(m - 1, 0.25e-20), 1)
    r += np.diag(np.full(m - 1, 0.25e-20), -1)
    ekf = ExtendedKalmanFilter(np.zeros(2), np.diag([1e20, 1.0]))
    with pytest.raises(FilterError, match="innovation covariance S is not positive definite"):
        ekf.update(np.ones(m), lambda s: h @ s, h, r)
    np.testing.assert_array_equal(ekf.x, np.zeros(2))


@settings(max_examples=40, deadline=None)
@given(
    n=st.integers(1, 3),
    m=st.integers(2, 3),
    scale=st.floats(-30.0, 30.0),
    ratio=st.floats(-40.0, -12.0),
    correlated=st.booleans(),
    seed=st.integers(0, 2**32 - 1),
)
# The kernel's x kept, 4.4 deviations (170 ulps) off: the information form's, 0.01
# deviations off, had an error bound of 0.29 deviations (found at random).
@example(n=2, m=2, scale=0.0, ratio=-29.0, correlated=False, seed=111790)
# The same, 4.1 deviations (20 ulps) and 1.1 deviations (33 ulps) off.
@example(
    n=1,
    m=2,
    scale=-23.71771362098264,
    ratio=-29.106122269033513,
    correlated=True,
    seed=3007780589,
)
@example(
    n=1,
    m=2,
    scale=11.526623943164275,
    ratio=-28.968572826422005,
    correlated=True,
    seed=293798354,
)
# Passed at 16 ulps, the kernel's x 11.4 ulps (2.6 deviations) off.
@example(
    n=1,
    m=2,
    scale=16.405338145104956,
    ratio=-29.659165190873274,
    correlated=False,
    seed=213129303,
)
def test_precise_repeated_measurements_match_exact_arithmetic(
    n: int, m: int, scale: float, ratio: float, correlated: bool, seed: int
) -> None:
    rng = np.random.default_rng(seed)
    sd = 10.0 ** (scale + rng.uniform(-3.0, 3.0, n))
    p0 = np.diag(sd**2)
    if correlated and n > 1:
        p0[0, 1] = p0[1, 0] = 0.5 * sd[0] * sd[1]
    k = int(rng.integers(0, n))
    h = np.zeros((m, n))
    h[:, k] = rng.choice([1.0, -1.0, 2.0, 0.5], m)
    rr = np.diag(p0[k, k] * 10.0**ratio * 10.0 ** rng.uniform(0.0, 1.0, m))
    x = rng.normal(size=n) * sd
    z = h @ (x + rng.normal(size=n) * sd) + rng.normal(size=m) * np.sqrt(rr.diagonal())
    ekf = ExtendedKalmanFilter(x, p0)
    result = ekf.update(z, lambda s: h @ s, h, rr)
    assert result.accepted
    x_exact, p_exact, nis_exact = _exact(x, p0, h, rr, z)
    _check(ekf, x, x_exact, p_exact, nis_exact, result.nis)


@settings(max_examples=30, deadline=None)
@given(
    n=st.integers(1, 4),
    m=st.integers(1, 4),
    p_scale=st.floats(-100.0, 100.0),
    r_scale=st.floats(-100.0, 100.0),
    seed=st.integers(0, 2**32 - 1),
)
def test_exact_nis_is_the_exact_value_rounded(
    n: int, m: int, p_scale: float, r_scale: float, seed: int
) -> None:
    rng = np.random.default_rng(seed)
    a = rng.normal(size=(n, n))
    p = (a @ a.T + 0.1 * np.eye(n)) * 10.0**p_scale
    p = 0.5 * (p + p.T)
    h = rng.normal(size=(m, n))
    r = np.diag(10.0 ** (r_scale + rng.uniform(-3.0, 3.0, m)))
    y = rng.normal(size=m) * 10.0 ** rng.uniform(-5.0, 5.0)
    _, s_inv, _ = exact_gain(p, h, r)
    yf = [Fraction(v) for v in y]
    exact = sum(yf[i] * s_inv[i][j] * yf[j] for i in range(m) for j in range(m))
    try:
        expected = float(exact)
    except OverflowError:
        expected = float("inf")
    assert _exact_nis(p, h, r, y) == expected


def test_exact_nis_overflow_is_inf() -> None:
    p = np.array([[1.0]])
    r = np.array([[1e-100]])
    h = np.array([[0.0]])
    assert _exact_nis(p, h, r, np.array([1e200])) == float("inf")
