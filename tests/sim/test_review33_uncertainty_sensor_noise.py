"""The simulator's noise models have the statistics their docstrings state.

Empirical means, standard deviations and correlations of seeded readings
against the documented model: a mean within ``z σ / √n`` of its value (``z``
the two-sided 1e-6 normal quantile), a variance in its chi-square band at the
same false-alarm rate, a lag-one or cross-axis correlation within ``z / √n``
of 0, a dropout count in its binomial band (``tests/noise_bands.py``). The
noise of the compass and the IMU is a standard deviation per reading,
independent of the sensor's rate (not a density); the LiDAR's is relative to
the range, by band. A sensor without noise reads the truth exactly.
"""

from __future__ import annotations

import math
import sys
from pathlib import Path

import numpy as np
import pytest
from scipy.stats import binom
from scipy.stats import f as f_dist
from scipy.stats import t as t_dist
from shapely.geometry import box

from navkit.geometry import Twist2D
from navkit.kinematics import DiffDrive
from navkit.sim import (
    Compass,
    CompassReading,
    Imu,
    ImuReading,
    Lidar,
    RangeNoise,
    Robot,
    Simulation,
    World,
)

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from noise_bands import FALSE_ALARM, ReadingLog, check_normal, check_uncorrelated


def readings(
    *, compass: Compass | None = None, imu: Imu | None = None, omega: float = 0.0,
    duration: float = 10.0, rate: float = 100.0, seed: int = 0,
) -> tuple[ReadingLog, np.ndarray, np.ndarray]:  # fmt: skip
    """The readings of a robot turning on the spot at ``omega``, and the trace's times and poses."""
    robot = Robot(drive=DiffDrive(track=0.3, wheel_radius=0.05), footprint=0.2,
                  encoders=None, compass=compass, imu=imu)  # fmt: skip
    log = ReadingLog()
    trace = Simulation(World(), robot, lambda obs: Twist2D(0.0, 0.0, omega),
                       start=(0.0, 0.0, 0.3), estimator=log, duration=duration, seed=seed,
                       rate=rate).run()  # fmt: skip
    return log, trace.times, trace.poses


def test_compass_noise_is_the_documented_standard_deviation_per_reading() -> None:
    noise, bias = 0.05, 0.02
    log, _, _ = readings(compass=Compass(noise=noise, bias=bias, rate=50.0), duration=20.0)
    deg = np.array([r.heading_deg for r in log.readings if isinstance(r, CompassReading)])
    truth = math.degrees(math.pi / 2 - 0.3)  # north - yaw, the robot standing still
    error = np.radians((deg - truth + 180.0) % 360.0 - 180.0)
    assert error.size == 1001
    check_normal(error, bias, noise)
    check_uncorrelated(error[:-1], error[1:])


def test_imu_noise_is_per_sample_whatever_the_rate() -> None:
    # Imu(gyro_noise, accel_noise) are standard deviations of each sample (rad/s,
    # m/s²), white: the same at 100 Hz and 1 kHz, where a noise density would give
    # sqrt(10) times more per sample at the faster rate.
    gyro, accel, gyro_bias, accel_bias = 0.02, 0.1, 0.003, -0.04
    for rate in (100.0, 1000.0):
        imu = Imu(gyro_noise=gyro, accel_noise=accel, gyro_bias=gyro_bias,
                  accel_bias=accel_bias, rate=rate)  # fmt: skip
        log, _, _ = readings(imu=imu, duration=5.0, rate=rate, seed=1)
        values = np.array([[r.yaw_rate, r.acceleration_x, r.acceleration_y]
                           for r in log.readings if isinstance(r, ImuReading)])  # fmt: skip
        assert values.shape[0] == round(5.0 * rate) + 1
        check_normal(values[:, 0], gyro_bias, gyro)
        check_normal(values[:, 1], accel_bias, accel)
        check_normal(values[:, 2], accel_bias, accel)
        check_uncorrelated(values[:, 0], values[:, 1])
        check_uncorrelated(values[:, 1], values[:, 2])
        check_uncorrelated(values[:-1, 0], values[1:, 0])


def test_noise_free_compass_and_imu_read_the_truth() -> None:
    compass = Compass(rate=50.0, north=0.4)
    log, times, poses = readings(compass=compass, imu=Imu(rate=100.0), omega=1.0, duration=3.0)
    yaw_at = {float(t): float(p[2]) for t, p in zip(times, poses, strict=True)}
    cmp = [r for r in log.readings if isinstance(r, CompassReading)]
    assert len(cmp) == 151
    for r in cmp:
        assert abs(r.heading_deg - compass.heading_deg(yaw_at[r.stamp])) < 1e-9
    imu = [r for r in log.readings if isinstance(r, ImuReading)]
    # Turning on the spot at 1 rad/s (the wheels reach it within the first step):
    # the gyro reads it and the centre does not accelerate.
    for r in imu[1:]:
        assert abs(r.yaw_rate - 1.0) < 1e-12
        assert abs(r.acceleration_x) < 1e-9 and abs(r.acceleration_y) < 1e-9


WORLD = World(box(-2.0, -6.0, 2.0, 6.0).exterior)  # sides 2 m away (band 0), ends 6 m (band 1)


def test_lidar_range_noise_is_relative_by_band() -> None:
    exact = Lidar(n_beams=720, noise=None, range_max=20.0).scan(WORLD, (0.0, 0.0, 0.0)).ranges
    noise = RangeNoise(limits=(3.0, math.inf), sigma=(0.02, 0.05), bias=(0.01, -0.02))
    lidar = Lidar(n_beams=720, noise=noise, range_max=20.0)
    rng = np.random.default_rng(0)
    rel = np.array([lidar.scan(WORLD, (0.0, 0.0, 0.0), seed=rng).ranges for _ in range(40)])
    rel = rel / exact - 1.0
    near = exact < 3.0
    assert 0 < near.sum() < near.size
    check_normal(rel[:, near].ravel(), 0.01, 0.02)
    check_normal(rel[:, ~near].ravel(), -0.02, 0.05)
    z = np.where(near, (rel - 0.01) / 0.02, (rel + 0.02) / 0.05)  # standard normal
    check_uncorrelated(z[:, :-1].ravel(), z[:, 1:].ravel())  # beam to beam
    check_uncorrelated(z[:-1].ravel(), z[1:].ravel())  # scan to scan


def test_noise_free_lidar_reads_the_exact_distances() -> None:
    lidar = Lidar(n_beams=720, noise=None, range_max=20.0)
    angles = lidar.angles()
    with np.errstate(divide="ignore"):
        truth = np.minimum(2.0 / np.abs(np.cos(angles)), 6.0 / np.abs(np.sin(angles)))
    ranges = lidar.scan(WORLD, (0.0, 0.0, 0.0)).ranges
    np.testing.assert_allclose(ranges, truth, rtol=1e-12)
    zero = Lidar(n_beams=720, noise=RangeNoise(sigma=(0.0, 0.0)), range_max=20.0)
    np.testing.assert_array_equal(zero.scan(WORLD, (0.0, 0.0, 0.0), seed=3).ranges, ranges)


def test_lidar_dropout_is_the_documented_probability() -> None:
    lidar = Lidar(n_beams=720, noise=None, range_max=20.0, dropout=0.1)
    rng = np.random.default_rng(1)
    dropped = sum(
        int(np.isnan(lidar.scan(WORLD, (0.0, 0.0, 0.0), seed=rng).ranges).sum()) for _ in range(20)
    )
    lo, hi = binom.ppf([FALSE_ALARM / 2, 1 - FALSE_ALARM / 2], 720 * 20, 0.1)
    assert lo <= dropped <= hi, (dropped, lo, hi)


def straight_runs(slip: float, rate: float, runs: int) -> np.ndarray:
    """End positions of ``runs`` seeded 10 s drives straight ahead at 0.5 m/s."""
    robot = Robot(drive=DiffDrive(track=0.3, wheel_radius=0.05), footprint=0.2, wheel_slip=slip)
    ends = []
    for seed in range(runs):
        sim = Simulation(World(), robot, lambda obs: Twist2D(0.5, 0.0, 0.0),
                         start=(0.0, 0.0, 0.0), duration=10.0, seed=seed, rate=rate)  # fmt: skip
        trace = sim.run()
        ends.append(trace.poses[-1][:2])
    return np.array(ends)


def test_wheel_slip_slows_the_robot_by_its_mean_magnitude() -> None:
    # Robot.wheel_slip: each physics step a wheel's ground speed is its rim speed
    # times 1 - min(|s|, 1), s ~ N(0, wheel_slip²): on average 1 - wheel_slip √(2/π).
    slip, runs = 0.1, 20
    x = straight_runs(slip, 100.0, runs)[:, 0]
    expected = 5.0 * (1.0 - slip * math.sqrt(2.0 / math.pi))  # 4.601 m of 5
    bound = float(t_dist.ppf(1 - FALSE_ALARM / 2, runs - 1)) * x.std(ddof=1) / math.sqrt(runs)
    assert abs(x.mean() - expected) < bound, (x.mean(), expected, bound)
    assert bound < 0.02  # the check is sharp: the loss is 0.4 m


@pytest.mark.slow
def test_wheel_slip_is_drawn_per_physics_step() -> None:
    # The random part of the slip is drawn each physics step, not as a density:
    # at 10 times the rate the heading drift, and with it the sideways spread of
    # the end points, is about sqrt(10) times smaller; the mean loss is the same.
    slow, fast = straight_runs(0.1, 100.0, 40), straight_runs(0.1, 1000.0, 40)
    ratio = slow[:, 1].std(ddof=1) / fast[:, 1].std(ddof=1)
    # F(39, 39) at 1e-6 two-sided: a ratio of standard deviations within about 2.1 of
    # the true one; 1 (a density) and sqrt(10) (per step) are told apart.
    lo, hi = f_dist.ppf([FALSE_ALARM / 2, 1 - FALSE_ALARM / 2], 39, 39) ** 0.5
    assert lo * math.sqrt(10.0) < ratio < hi * math.sqrt(10.0), ratio
    assert not lo < ratio < hi
    assert abs(slow[:, 0].mean() - fast[:, 0].mean()) < 0.01
