"""Long runs of the estimators: what 10^4 to 10^6 updates leave behind (review 48, LONGRUN).

A fusion filter updated at 100 Hz for hours, started at epoch stamps (ROS stamps are
about 1.7e9 s); a generic EKF with an angle state; wheel odometry whose 16-bit
counters wrap hundreds of times; a compass unwrapped over thousands of turns. Each
must stay defined and bounded: covariances exactly symmetric and positive definite,
the observed block settled (neither growing nor collapsing), only the unobserved
position's variance growing (linearly, by the process noise), angles wrapped, memory
flat, and no drift beyond the documented rounding.
"""

from __future__ import annotations

import math
import tracemalloc

import numpy as np
import pytest

from navkit.estimation import CompassCalibration, DiffOdometry, ExtendedKalmanFilter, PlanarFusion
from navkit.kinematics import DiffDrive

_EPOCH = 1.7e9


def _drive(fusion: PlanarFusion, t0: float, steps: int, every: int = 0) -> list[np.ndarray]:
    """Odometry and yaw at 100 Hz on a 0.5 m/s, 0.3 rad/s circle; P every ``every`` steps."""
    rng = np.random.default_rng(7)
    v = rng.normal(0.5, 0.01, steps)
    w = rng.normal(0.3, 0.01, steps)
    yaw_noise = rng.normal(0.0, 0.01, steps)
    covariances = []
    for k in range(1, steps + 1):
        t = t0 + k * 0.01
        fusion.update_odometry(t, v[k - 1], w[k - 1], v_variance=1e-4, omega_variance=1e-4)
        if k % 2 == 0:
            yaw = math.remainder(0.3 * k * 0.01 + yaw_noise[k - 1], 2.0 * math.pi)
            fusion.update_yaw(t, yaw, variance=1e-4)
        if every and k % every == 0:
            covariances.append(fusion.P)
            assert -math.pi < fusion.x[2] <= math.pi
    return covariances


def _check_fusion_covariances(covariances: list[np.ndarray]) -> None:
    for P in covariances:
        np.testing.assert_array_equal(P, P.T)
        assert float(np.linalg.eigvalsh(P).min()) > 0.0
    # The observed block (yaw, v, omega, a) has settled: the same to 1e-9.
    np.testing.assert_allclose(covariances[-1][2:, 2:], covariances[1][2:, 2:], rtol=1e-9)
    # x and y are dead reckoning: their variance grows, by about the process noise
    # (0.05 m²/s) a second and no faster (no blow-up from the rounding).
    growth = [float(P[0, 0] + P[1, 1]) for P in covariances]
    rates = np.diff(growth) / 10.0  # 1000 steps of 0.01 s apart
    assert bool(np.all(rates > 0.09)) and bool(np.all(rates < 0.11))


@pytest.mark.parametrize("t0", [0.0, _EPOCH], ids=["zero", "epoch"])
def test_fusion_covariance_stays_symmetric_settled_and_bounded(t0: float) -> None:
    fusion = PlanarFusion(t0=t0)
    _check_fusion_covariances(_drive(fusion, t0, 20_000, every=1000))
    assert fusion.t == t0 + 20_000 * 0.01


@pytest.mark.slow
def test_fusion_million_updates_at_epoch_stamps() -> None:
    fusion = PlanarFusion(t0=_EPOCH)
    _check_fusion_covariances(_drive(fusion, _EPOCH, 1_000_000, every=1000))


def test_fusion_at_epoch_stamps_follows_the_run_from_zero() -> None:
    # Stamps at 1.7e9 s are rounded by up to 1.2e-7 s, and each dt by up to 2.4e-7 s
    # (of 0.01 s), but nothing accumulates: 200 s and 100 m later the two runs agree
    # to a micrometre (measured: 4e-8 m, 1e-9 rad).
    zero, epoch = PlanarFusion(t0=0.0), PlanarFusion(t0=_EPOCH)
    _drive(zero, 0.0, 20_000)
    _drive(epoch, _EPOCH, 20_000)
    assert abs(zero.x[2] - epoch.x[2]) < 1e-7
    assert math.dist(zero.x[:2], epoch.x[:2]) < 1e-6
    np.testing.assert_allclose(epoch.P, zero.P, rtol=1e-6, atol=1e-15)


def test_fusion_memory_with_history_stays_flat() -> None:
    # The steps kept for late measurements go once older than history: a filter
    # updated for 10^4 more steps holds no more than after the first 5000.
    fusion = PlanarFusion(t0=_EPOCH, history=0.5)
    _drive(fusion, _EPOCH, 2000)
    tracemalloc.start()
    try:
        _drive(fusion, _EPOCH + 20.0, 5000)
        early, _ = tracemalloc.get_traced_memory()
        _drive(fusion, _EPOCH + 100.0, 10_000)
        late, _ = tracemalloc.get_traced_memory()
    finally:
        tracemalloc.stop()
    assert late - early < 16_000


def _unicycle(steps: int) -> tuple[ExtendedKalmanFilter, list[np.ndarray]]:
    dt = 0.01
    rng = np.random.default_rng(3)

    def f(x: np.ndarray) -> np.ndarray:
        c, s = math.cos(x[2]), math.sin(x[2])
        return np.array([x[0] + x[3] * c * dt, x[1] + x[3] * s * dt, x[2] + x[4] * dt, x[3], x[4]])

    def jac(x: np.ndarray) -> np.ndarray:
        c, s = math.cos(x[2]), math.sin(x[2])
        J = np.eye(5)
        J[0, 2:4] = -x[3] * s * dt, c * dt
        J[1, 2:4] = x[3] * c * dt, s * dt
        J[2, 4] = dt
        return J

    Q = np.diag([1e-6, 1e-6, 1e-6, 1e-4, 1e-4])
    H = np.zeros((3, 5))
    H[0, 2] = H[1, 3] = H[2, 4] = 1.0
    R = np.diag([1e-3, 1e-4, 1e-4])
    ekf = ExtendedKalmanFilter([0.0, 0.0, 0.0, 1.0, 0.5], np.eye(5), angle_states=[2])
    covariances = []
    for k in range(1, steps + 1):
        ekf.predict(f, jac, Q)
        z = [
            math.remainder(0.5 * k * dt, 2.0 * math.pi) + rng.normal(0.0, 0.03),
            1.0 + rng.normal(0.0, 0.01),
            0.5 + rng.normal(0.0, 0.01),
        ]
        assert ekf.update(z, lambda x: x[2:5], H, R, angle_measurements=[0]).accepted
        assert -math.pi < ekf.x[2] <= math.pi
        if k % 1000 == 0:
            covariances.append(ekf.P)
    return ekf, covariances


def _check_ekf(covariances: list[np.ndarray]) -> None:
    for P in covariances:
        np.testing.assert_array_equal(P, P.T)
        assert float(np.linalg.eigvalsh(P).min()) > 0.0
    np.testing.assert_allclose(covariances[-1][2:, 2:], covariances[1][2:, 2:], rtol=1e-9)
    # Position is unobserved: its variance grows by Q's 2e-6 a step and the heading's
    # share, never explosively.
    growth = np.diff([float(P[0, 0] + P[1, 1]) for P in covariances])
    assert bool(np.all(growth > 0.0)) and float(growth.max()) < 2.0 * float(growth.min())


def test_ekf_twenty_thousand_cycles_stay_symmetric_and_settled() -> None:
    ekf, covariances = _unicycle(20_000)
    _check_ekf(covariances)
    # The heading follows the 0.5 rad/s truth, wrapped (200 s: 100 rad, 16 turns).
    assert abs(math.remainder(ekf.x[2] - 100.0, 2.0 * math.pi)) < 0.05


@pytest.mark.slow
def test_ekf_quarter_million_cycles() -> None:
    _check_ekf(_unicycle(250_000)[1])


def test_diff_odometry_wrapping_counters_stay_on_the_circle() -> None:
    # 16-bit counters, 1 and 3 ticks a reading: 10^5 readings wrap the right one
    # 4.6 times and drive 160 turns of a 0.5 m radius circle (2500 readings a turn).
    drive = DiffDrive(track=0.5, wheel_radius=0.1)
    odo = DiffOdometry(drive, ticks_per_rev=1000, bits=16)
    odo.update(0, 0)
    steps = 100_000
    radius = 0.5
    for k in range(1, steps + 1):
        pose = odo.update(k % 65536, (3 * k) % 65536)
        assert -math.pi < pose.theta <= math.pi
        if k % 2500 == 0:  # a whole number of turns: back at the start
            assert math.hypot(pose.x, pose.y) < 1e-10
    assert abs(math.hypot(pose.x, pose.y - radius) - radius) < 1e-12
    assert abs(pose.theta) < 1e-10
    # The batch of the same counters, from the same start, ends at the same place.
    batch = DiffOdometry(drive, ticks_per_rev=1000, bits=16)
    k = np.arange(steps + 1)
    end = batch.update_batch(k % 65536, (3 * k) % 65536)[-1]
    np.testing.assert_allclose(end, [pose.x, pose.y, pose.theta], rtol=0.0, atol=1e-9)


def test_compass_unwrapped_over_ten_thousand_turns() -> None:
    # Eight readings a turn, clockwise, streamed in pieces of 1000: the running sum
    # of 2π corrections drifts by its rounding only (documented: about 1e-8 rad
    # after 10^4 turns); the wrapped yaw has no memory at all.
    turns = 10_000
    readings = np.arange(8 * turns + 1) * 45.0
    unwrapping, wrapping = CompassCalibration(unwrap=True), CompassCalibration()
    yaws = np.concatenate([unwrapping(piece) for piece in np.array_split(readings, 81)])
    within = -np.radians(readings % 360.0)  # exact: multiples of 45°
    exact = within - (readings // 360.0) * (2.0 * math.pi)
    assert float(np.abs(yaws - exact).max()) < 1e-7
    wrapped = wrapping(readings)
    expected = np.where(within <= -math.pi, within + 2.0 * math.pi, within)
    np.testing.assert_allclose(wrapped, expected, rtol=0.0, atol=1e-15)
