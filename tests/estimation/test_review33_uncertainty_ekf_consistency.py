"""ExtendedKalmanFilter's covariance, NIS and gate are honest: Monte Carlo against the truth.

Each check simulates exactly the model the filter is given (seeded), runs
independent trials and compares the average normalised estimation error squared
(NEES, ``eᵀ P⁻¹ e`` with ``e`` the true state minus the estimate) and the
average NIS with their chi-square distributions: for a consistent filter the
NEES of ``N`` independent trials at one step sums to chi-square with ``n N``
degrees of freedom, and the NIS of a linear Gaussian filter are white, so all
``N K`` of them sum to chi-square with ``m N K``. The acceptance bands are the
two-sided 1e-6 quantiles of those sums (divided by the count), so a consistent
filter fails them once in a million seeds; the seeds are fixed, so the tests
are deterministic. A nonlinear model is only approximately Gaussian: its noise
is kept small against the curvature, and the same bands are used.

Each check also shows that its band has power: the same data with the noise
misstated by a factor of 2 (or the angle wrap left out) fall outside it.
"""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np
import pytest
from scipy.stats import binom, chi2

from navkit.estimation import ExtendedKalmanFilter
from navkit.geometry import wrap_angle

FALSE_ALARM = 1e-6


def mean_band(dof: int, count: int) -> tuple[float, float]:
    """Band of the mean of ``count`` independent chi-square(``dof``) values."""
    lo, hi = chi2.ppf([FALSE_ALARM / 2, 1 - FALSE_ALARM / 2], dof * count)
    return float(lo) / count, float(hi) / count


# A 1-D constant-velocity model observed in position (continuous white
# acceleration of density q, m²/s³).
DT = 0.1
F_CV = np.array([[1.0, DT], [0.0, 1.0]])
Q_CV = 0.5 * np.array([[DT**3 / 3, DT**2 / 2], [DT**2 / 2, DT]])
H_CV = np.array([[1.0, 0.0]])
R_CV = 0.04
P0_CV = np.diag([1.0, 0.5])


def constant_velocity_runs(
    trials: int, steps: int, seed: int, r_told: float, nees_steps: tuple[int, ...]
) -> tuple[np.ndarray, dict[int, np.ndarray]]:
    """NIS of every update (trials, steps) and NEES at ``nees_steps`` (trials,)."""
    rng = np.random.default_rng(seed)
    chol_q = np.linalg.cholesky(Q_CV)
    x0 = rng.standard_normal((trials, 2)) * np.sqrt(np.diag(P0_CV)) + [0.0, 1.0]
    w = rng.standard_normal((trials, steps, 2)) @ chol_q.T
    v = rng.standard_normal((trials, steps)) * math.sqrt(R_CV)
    nis = np.empty((trials, steps))
    nees: dict[int, np.ndarray] = {k: np.empty(trials) for k in nees_steps}
    r_matrix = np.array([[r_told]])
    for i in range(trials):
        truth = x0[i].copy()
        ekf = ExtendedKalmanFilter([0.0, 1.0], P0_CV)
        for k in range(steps):
            truth = F_CV @ truth + w[i, k]
            ekf.predict(lambda x: F_CV @ x, F_CV, Q_CV)
            z = np.array([truth[0] + v[i, k]])
            result = ekf.update(z, lambda x: x[:1], H_CV, r_matrix)
            assert result.accepted
            nis[i, k] = result.nis
            if k + 1 in nees:
                e = truth - ekf.x
                nees[k + 1][i] = e @ np.linalg.solve(ekf.P, e)
    return nis, nees


def test_linear_filter_nees_and_nis_lie_in_their_chi_square_bands() -> None:
    trials, steps = 100, 30
    nis, nees = constant_velocity_runs(trials, steps, 11, R_CV, (1, 10, 30))
    lo, hi = mean_band(1, nis.size)
    assert lo < nis.mean() < hi, (nis.mean(), lo, hi)
    lo, hi = mean_band(2, trials)
    for k, values in nees.items():
        assert lo < values.mean() < hi, (k, values.mean(), lo, hi)


@pytest.mark.parametrize("factor", [0.5, 2.0])
def test_linear_filter_bands_catch_a_misstated_measurement_noise(factor: float) -> None:
    # The same draws as the test above, the filter told R times 1/2 or 2: the NIS
    # average leaves its band (so the band above is not vacuous).
    nis, _ = constant_velocity_runs(100, 30, 11, R_CV * factor, ())
    lo, hi = mean_band(1, nis.size)
    assert not lo < nis.mean() < hi, (nis.mean(), lo, hi)


# A unicycle [x, y, θ] seeing a landmark behind it: range and bearing, the bearing
# near ±π, so the measured bearings wrap while h(x) does not.
LANDMARK = np.array([-5.0, 0.05])
V, OMEGA = 1.0, -0.05
Q_UNI = np.diag([1e-4, 1e-4, 2e-4])
R_UNI = np.diag([0.01, 0.0004])
P0_UNI = np.diag([0.01, 0.01, 0.002])


def _f(x: np.ndarray) -> np.ndarray:
    return np.array([x[0] + V * DT * math.cos(x[2]), x[1] + V * DT * math.sin(x[2]),
                     x[2] + OMEGA * DT])  # fmt: skip


def _jf(x: np.ndarray) -> np.ndarray:
    return np.array([[1.0, 0.0, -V * DT * math.sin(x[2])], [0.0, 1.0, V * DT * math.cos(x[2])],
                     [0.0, 0.0, 1.0]])  # fmt: skip


def _h(x: np.ndarray) -> np.ndarray:
    d = LANDMARK - x[:2]
    return np.array([math.hypot(d[0], d[1]), math.atan2(d[1], d[0]) - x[2]])


def _jh(x: np.ndarray) -> np.ndarray:
    d = LANDMARK - x[:2]
    r2 = float(d @ d)
    r = math.sqrt(r2)
    return np.array([[-d[0] / r, -d[1] / r, 0.0], [d[1] / r2, -d[0] / r2, -1.0]])


def bearing_runs(
    trials: int, steps: int, seed: int, angles: tuple[int, ...], nees_steps: tuple[int, ...]
) -> tuple[np.ndarray, dict[int, np.ndarray], int]:
    """NIS (trials, steps), NEES at ``nees_steps`` and how many bearings were wrapped."""
    rng = np.random.default_rng(seed)
    chol_q = np.linalg.cholesky(Q_UNI)
    chol_r = np.linalg.cholesky(R_UNI)
    nis = np.empty((trials, steps))
    nees: dict[int, np.ndarray] = {k: np.empty(trials) for k in nees_steps}
    wrapped = 0
    for i in range(trials):
        truth = rng.standard_normal(3) * np.sqrt(np.diag(P0_UNI))
        ekf = ExtendedKalmanFilter(np.zeros(3), P0_UNI, angle_states=[2])
        for k in range(steps):
            truth = _f(truth) + chol_q @ rng.standard_normal(3)
            truth[2] = wrap_angle(float(truth[2]))
            z = _h(truth) + chol_r @ rng.standard_normal(2)
            wrapped += abs(z[1]) > math.pi
            z[1] = wrap_angle(float(z[1]))
            ekf.predict(_f, _jf, Q_UNI)
            nis[i, k] = ekf.update(z, _h, _jh, R_UNI, angle_measurements=angles).nis
            if k + 1 in nees:
                e = truth - ekf.x
                e[2] = wrap_angle(float(e[2]))
                nees[k + 1][i] = e @ np.linalg.solve(ekf.P, e)
    return nis, nees, wrapped


def test_nonlinear_filter_with_wrapped_bearings_is_consistent() -> None:
    trials, steps = 100, 30
    nis, nees, wrapped = bearing_runs(trials, steps, 5, (1,), (10, 30))
    assert wrapped > trials * steps // 2  # the wrap is exercised: most bearings crossed ±π
    lo, hi = mean_band(2, nis.size)
    assert lo < nis.mean() < hi, (nis.mean(), lo, hi)
    lo, hi = mean_band(3, trials)
    for k, values in nees.items():
        assert lo < values.mean() < hi, (k, values.mean(), lo, hi)


def test_nonlinear_filter_without_the_angle_wrap_is_caught() -> None:
    nis, _, _ = bearing_runs(10, 10, 5, (), ())
    assert nis.mean() > mean_band(2, nis.size)[1]


def run_gate(probability: float, count: int, seed: int) -> int:
    """How many of ``count`` consistent 2-D measurements a gate at ``probability`` rejects."""
    rng = np.random.default_rng(seed)
    p = np.array([[0.5, 0.1], [0.1, 0.3]])
    r = np.diag([0.2, 0.1])
    chol_s = np.linalg.cholesky(p + r)
    gate = float(chi2.ppf(probability, 2))
    identity: Callable[[np.ndarray], np.ndarray] = lambda x: x  # noqa: E731
    rejected = 0
    ekf = ExtendedKalmanFilter([0.0, 0.0], p)
    for _ in range(count):
        # The filter is not updated by a rejected measurement, and an accepted one is
        # undone by a fresh filter: every measurement meets the same prior.
        result = ekf.update(chol_s @ rng.standard_normal(2), identity, np.eye(2), r, gate=gate)
        if result.accepted:
            ekf = ExtendedKalmanFilter([0.0, 0.0], p)
        else:
            rejected += 1
    return rejected


def test_gate_rejects_the_documented_fraction() -> None:
    # update(gate=chi2.ppf(p, m)) rejects a fraction 1 - p of consistent measurements.
    count, probability = 4000, 0.9
    rejected = run_gate(probability, count, 3)
    lo, hi = binom.ppf([FALSE_ALARM / 2, 1 - FALSE_ALARM / 2], count, 1 - probability)
    assert lo <= rejected <= hi, (rejected, lo, hi)


@pytest.mark.slow
def test_linear_filter_consistency_long() -> None:
    trials, steps = 1000, 100
    nis, nees = constant_velocity_runs(trials, steps, 12, R_CV, (1, 5, 20, 100))
    lo, hi = mean_band(1, nis.size)
    assert lo < nis.mean() < hi, (nis.mean(), lo, hi)
    lo, hi = mean_band(2, trials)
    for k, values in nees.items():
        assert lo < values.mean() < hi, (k, values.mean(), lo, hi)


@pytest.mark.slow
def test_nonlinear_filter_consistency_long() -> None:
    trials, steps = 1000, 60
    nis, nees, _ = bearing_runs(trials, steps, 6, (1,), (1, 20, 60))
    lo, hi = mean_band(2, nis.size)
    assert lo < nis.mean() < hi, (nis.mean(), lo, hi)
    lo, hi = mean_band(3, trials)
    for k, values in nees.items():
        assert lo < values.mean() < hi, (k, values.mean(), lo, hi)
