"""The PlanarFusion a Simulation feeds: honest without latency, behind by it with it.

What ``Simulation``'s ``estimator`` parameter now documents, measured over
seeded runs of a robot turning at 0.4 rad/s with a noisy compass, IMU and
1024-tick encoders: without latency the heading's covariance bounds its error
(mean NEES within the 1e-6 chi-square band's upper edge); with 0.1 s on every
sensor the heading lags by about ω × latency = 0.04 rad, outside the
covariance, since each reading is fused at its delivery time; fused at its
stamp (``reading.stamp``) by a filter with ``history`` covering the latency,
the lag is gone.
"""

from __future__ import annotations

import math

import numpy as np
from scipy.stats import chi2

from navkit.estimation import PlanarFusion
from navkit.geometry import Pose2D, Twist2D, wrap_angle
from navkit.kinematics import DiffDrive
from navkit.sim import Compass, Imu, Reading, Robot, Simulation, WheelEncoders, World
from navkit.sim._estimators import FusionEstimator

RUNS = 30
OMEGA = 0.4


class Stamped:
    """The simulation's own PlanarFusion wrapper, fed each reading at its stamp."""

    def __init__(self, fusion: PlanarFusion, robot: Robot) -> None:
        self._inner = FusionEstimator(fusion, robot)

    def observe(self, t: float, reading: Reading) -> None:
        self._inner.observe(reading.stamp, reading)

    @property
    def pose(self) -> Pose2D | None:
        return self._inner.pose


def heading_errors(latency: float, stamped: bool) -> tuple[np.ndarray, np.ndarray]:
    """Heading errors at the filter's last time and their reported variances, per run."""
    robot = Robot(
        drive=DiffDrive(track=0.3, wheel_radius=0.05), footprint=0.2,
        compass=Compass(noise=0.05, rate=20.0, latency=latency),
        imu=Imu(gyro_noise=0.01, accel_noise=0.1, rate=100.0, latency=latency),
        encoders=WheelEncoders(ticks_per_rev=1024, rate=50.0, latency=latency),
        max_wheel_acceleration=20.0,
    )  # fmt: skip
    errors, variances = np.empty(RUNS), np.empty(RUNS)
    for seed in range(RUNS):
        fusion = PlanarFusion(pose=(0.0, 0.0, 0.3), t0=0.0, history=0.5)
        estimator = Stamped(fusion, robot) if stamped else fusion
        trace = Simulation(World(), robot, lambda obs: Twist2D(0.5, 0.0, OMEGA),
                           start=(0.0, 0.0, 0.3), estimator=estimator, duration=5.0,
                           seed=seed, stop_at_goal=False).run()  # fmt: skip
        assert fusion.t is not None
        row = int(np.searchsorted(trace.times, fusion.t))
        assert trace.times[row] == fusion.t
        errors[seed] = wrap_angle(float(trace.poses[row, 2] - fusion.x[2]))
        variances[seed] = fusion.P[2, 2]
    return errors, variances


def test_without_latency_the_heading_covariance_bounds_the_error() -> None:
    errors, variances = heading_errors(0.0, stamped=False)
    hi = chi2.ppf(1 - 5e-7, RUNS) / RUNS
    assert np.mean(errors**2 / variances) < hi
    assert abs(errors.mean()) < 0.02


def test_with_latency_the_heading_lags_outside_its_covariance() -> None:
    errors, variances = heading_errors(0.1, stamped=False)
    lag = OMEGA * 0.1
    assert 0.75 * lag < errors.mean() < 1.25 * lag
    assert errors.mean() > 4.0 * math.sqrt(variances.mean() / RUNS)  # not noise
    stamped, _ = heading_errors(0.1, stamped=True)
    assert abs(stamped.mean()) < 0.25 * lag
