"""PlanarFusion's covariance, NIS and gates are honest: Monte Carlo against its own model.

The truth follows the model the class documents: the constant-acceleration
unicycle over each ``dt``, plus process noise of covariance ``process_noise *
dt`` (the noise is given per second), the heading crossing ±π; the
measurements are the state's components plus noise of the variances passed.
Over independent trials the NEES of the state at one time sums to chi-square
with ``6 N`` degrees of freedom and the NIS of each kind of measurement
(white, for a consistent filter) to chi-square with ``m`` per update; the
acceptance bands are the two-sided 1e-6 quantiles, the seeds fixed (see
test_review33_uncertainty_ekf_consistency). The model is nonlinear in the
heading, with small noise against its curvature.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.stats import binom, chi2

from navkit.estimation import PlanarFusion
from navkit.geometry import wrap_angle

FALSE_ALARM = 1e-6
Q_C = np.diag([0.05, 0.05, 0.06, 0.025, 0.02, 0.01])  # per second: the defaults
P0 = np.diag([1e-2, 1e-2, 1e-2, 0.1, 0.1, 0.1])
X0 = np.array([0.0, 0.0, 3.0, 0.5, 0.3, 0.0])  # the heading crosses π after about 0.5 s
VAR = {"v": 1e-3, "omega": 1e-3, "gyro": 1e-4, "accel": 1e-2, "yaw": 1e-3}


def mean_band(dof: int, count: int) -> tuple[float, float]:
    """Band of the mean of ``count`` independent chi-square(``dof``) values."""
    lo, hi = chi2.ppf([FALSE_ALARM / 2, 1 - FALSE_ALARM / 2], dof * count)
    return float(lo) / count, float(hi) / count


def motion(x: np.ndarray, dt: float) -> np.ndarray:
    """The documented motion model (mid-step heading), without noise."""
    v, omega, a = x[3], x[4], x[5]
    s = v * dt + 0.5 * a * dt * dt
    mid = x[2] + 0.5 * omega * dt
    return np.array([x[0] + math.cos(mid) * s, x[1] + math.sin(mid) * s,
                     wrap_angle(float(mid + 0.5 * omega * dt)), v + a * dt, omega, a])  # fmt: skip


def fusion_runs(
    trials: int, duration: float, dt: float, seed: int, told: float = 1.0
) -> tuple[np.ndarray, dict[str, list[float]]]:
    """NEES at the end of each trial and the NIS of every update by kind.

    Odometry every second step, gyro and accelerometer every step, yaw every
    fifth; ``told`` scales the variances the filter is given.
    """
    rng = np.random.default_rng(seed)
    chol = np.linalg.cholesky(Q_C * dt)
    sd = {k: math.sqrt(v) for k, v in VAR.items()}
    nees = np.empty(trials)
    nis: dict[str, list[float]] = {"odometry": [], "yaw_rate": [], "acceleration": [], "yaw": []}
    steps = round(duration / dt)
    for i in range(trials):
        truth = X0 + np.sqrt(np.diag(P0)) * rng.standard_normal(6)
        fusion = PlanarFusion(X0, P0, process_noise=Q_C, t0=0.0)
        for k in range(1, steps + 1):
            t = k * dt
            truth = motion(truth, dt) + chol @ rng.standard_normal(6)
            truth[2] = wrap_angle(float(truth[2]))
            noise = rng.standard_normal(5)
            if k % 2 == 0:
                r = fusion.update_odometry(
                    t, truth[3] + sd["v"] * noise[0], truth[4] + sd["omega"] * noise[1],
                    v_variance=told * VAR["v"], omega_variance=told * VAR["omega"],
                )  # fmt: skip
                nis["odometry"].append(r.nis)
            r = fusion.update_yaw_rate(t, truth[4] + sd["gyro"] * noise[2],
                                       variance=told * VAR["gyro"])  # fmt: skip
            nis["yaw_rate"].append(r.nis)
            r = fusion.update_acceleration(t, truth[5] + sd["accel"] * noise[3],
                                           variance=told * VAR["accel"])  # fmt: skip
            nis["acceleration"].append(r.nis)
            if k % 5 == 0:
                yaw = wrap_angle(float(truth[2] + sd["yaw"] * noise[4]))
                nis["yaw"].append(fusion.update_yaw(t, yaw, variance=told * VAR["yaw"]).nis)
        e = truth - fusion.x
        e[2] = wrap_angle(float(e[2]))
        nees[i] = e @ np.linalg.solve(fusion.P, e)
    return nees, nis


def check(nees: np.ndarray, nis: dict[str, list[float]]) -> None:
    lo, hi = mean_band(6, nees.size)
    assert lo < nees.mean() < hi, ("NEES", nees.mean(), lo, hi)
    for kind, values in nis.items():
        lo, hi = mean_band(2 if kind == "odometry" else 1, len(values))
        assert lo < np.mean(values) < hi, (kind, np.mean(values), lo, hi)


def test_fusion_is_consistent_on_its_own_model() -> None:
    check(*fusion_runs(60, 1.0, 0.01, 2))


def test_fusion_bands_catch_variances_misstated() -> None:
    # The same draws, the filter told every variance twice what it is: the NIS
    # averages leave their bands.
    _, nis = fusion_runs(60, 1.0, 0.01, 2, told=2.0)
    for kind in ("odometry", "yaw_rate", "acceleration"):
        lo, _ = mean_band(2 if kind == "odometry" else 1, len(nis[kind]))
        assert np.mean(nis[kind]) < lo, kind


def test_process_noise_is_a_density_per_second() -> None:
    # ω and a are random walks (their rows of F are the identity): over 1 s their
    # predicted variances grow by process_noise * 1 s whether predicted in one step
    # or a hundred, as for a noise given per second (a per-step noise would grow
    # 100 times more over the hundred steps).
    p0 = np.diag([1e-9, 1e-9, 1e-9, 0.5, 0.25, 0.125])
    once = PlanarFusion(X0, p0, process_noise=Q_C, t0=0.0)
    once.predict(1.0)
    often = PlanarFusion(X0, p0, process_noise=Q_C, t0=0.0)
    for k in range(1, 101):
        often.predict(k / 100)
    expected = np.diag(p0)[4:] + np.diag(Q_C)[4:]
    np.testing.assert_allclose(np.diag(once.P)[4:], expected, rtol=1e-12)
    np.testing.assert_allclose(np.diag(often.P)[4:], expected, rtol=1e-12)


def test_gate_probability_rejects_the_documented_fraction() -> None:
    # gate_probability p: a consistent measurement is rejected with probability 1 - p.
    rng = np.random.default_rng(4)
    count, probability = 3000, 0.9
    p0 = [1e-9, 1e-9, 0.2, 0.3, 0.4, 0.5]
    rejected = 0
    for _ in range(count):
        fusion = PlanarFusion(np.zeros(6), p0, t0=0.0, gate_probability=probability)
        v = math.sqrt(0.3 + 0.01) * rng.standard_normal()
        omega = math.sqrt(0.4 + 0.02) * rng.standard_normal()
        result = fusion.update_odometry(0.0, v, omega, v_variance=0.01, omega_variance=0.02)
        rejected += not result.accepted
    lo, hi = binom.ppf([FALSE_ALARM / 2, 1 - FALSE_ALARM / 2], count, 1 - probability)
    assert lo <= rejected <= hi, (rejected, lo, hi)


@pytest.mark.slow
@pytest.mark.parametrize("dt", [0.01, 0.002])
def test_fusion_is_consistent_on_its_own_model_long(dt: float) -> None:
    # Two rates: the process noise per second means the same at both.
    check(*fusion_runs(300, 2.0, dt, 3))
