"""Wheel slip's statistics at different physics rates, against Robot's and Imu's docstrings.

``Robot.wheel_slip`` draws each wheel's slip anew at every physics step
(white, per step), so what it does depends on the rate: each step's yaw rate
has a spread that no rate changes, the heading drift after ``T`` seconds
shrinks as ``sqrt(dt)``, and an IMU reads each step's speed change over
``dt``, a spread that grows with the rate. For a differential drive of track
``D`` whose wheel rims move at ``u`` m/s, each wheel's ground speed is
``u (1 - |s|)`` with ``s ~ N(0, slip²)``, and ``|s|`` has the variance
``slip² (1 - 2 / π)``: so a step's yaw rate ``u (|s_l| - |s_r|) / D`` has the
standard deviation ``sqrt(2 (1 - 2 / π)) slip u / D`` and its speed
``u (1 - (|s_l| + |s_r|) / 2)`` the standard deviation
``sqrt((1 - 2 / π) / 2) slip u``. The docstrings' numbers are those, checked
here both ways: recomputed from these formulas, and the formulas against
seeded runs (bands at a 1e-6 false-alarm rate, see ``tests/noise_bands.py``).
"""

from __future__ import annotations

import math
import sys
from pathlib import Path

import numpy as np
import pytest

from navkit.geometry import Twist2D
from navkit.kinematics import DiffDrive
from navkit.sim import Imu, ImuReading, Robot, Simulation, World

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from noise_bands import ReadingLog, check_normal, check_spread, check_uncorrelated

TRACK, RADIUS, SPEED, SLIP = 0.3, 0.05, 0.5, 0.1
#: Standard deviation of one step's yaw rate (rad/s) and speed (m/s) under slip.
OMEGA_STD = math.sqrt(2.0 * (1.0 - 2.0 / math.pi)) * SLIP * SPEED / TRACK
SPEED_STD = math.sqrt((1.0 - 2.0 / math.pi) / 2.0) * SLIP * SPEED
MEAN_SPEED = SPEED * (1.0 - SLIP * math.sqrt(2.0 / math.pi))


def heading_std(duration: float, rate: float) -> float:
    """Standard deviation of the heading after ``duration`` s: a sum of white steps."""
    return OMEGA_STD * math.sqrt(duration / rate)


def sideways_std(duration: float, rate: float) -> float:
    """Of the sideways offset after a straight drive: ``∫ v θ dt`` of a random walk θ."""
    return MEAN_SPEED * heading_std(duration, rate) * duration / math.sqrt(3.0)


def drive(rate: float, duration: float, seed: int, imu: Imu | None = None) -> tuple:
    """A straight drive at 0.5 m/s with ``wheel_slip=0.1``: its reading log and trace."""
    robot = Robot(drive=DiffDrive(track=TRACK, wheel_radius=RADIUS), footprint=0.2,
                  wheel_slip=SLIP, encoders=None, imu=imu)  # fmt: skip
    log = ReadingLog()
    trace = Simulation(World(), robot, lambda obs: Twist2D(SPEED, 0.0, 0.0),
                       start=(0.0, 0.0, 0.0), duration=duration, rate=rate, seed=seed,
                       control_rate=min(rate, 20.0), estimator=log).run()  # fmt: skip
    return log, trace


def imu_values(log: ReadingLog) -> np.ndarray:
    return np.array([(r.yaw_rate, r.acceleration_x) for r in log.of(ImuReading)])


@pytest.mark.parametrize("rate", [100.0, 400.0])
def test_a_steps_yaw_rate_under_slip_has_the_same_spread_at_any_rate(rate: float) -> None:
    log, trace = drive(rate, 1000.0 / rate, seed=3, imu=Imu(rate=rate))
    gyro = imu_values(log)[1:, 0]  # the first sample is the start's, at rest
    assert gyro.size == 1000
    check_spread(gyro, 0.0, OMEGA_STD)
    check_uncorrelated(gyro[:-1], gyro[1:])  # white: drawn anew every step
    # The heading is the sum of those yaw rates over the steps (Imu's docstring).
    assert abs(gyro.sum() / rate - trace.poses[-1, 2]) < 1e-12


@pytest.mark.parametrize(("rate", "imu_rate"), [(100.0, 100.0), (400.0, 400.0), (400.0, 50.0)])
def test_the_accelerometer_reads_slip_as_speed_changes_over_the_physics_step(
    rate: float, imu_rate: float
) -> None:
    # Each step's speed is drawn anew: its change over dt has the spread
    # sqrt(2) SPEED_STD / dt, in proportion to the physics rate whatever the IMU's.
    log, _ = drive(rate, 500.0 / imu_rate, seed=4, imu=Imu(rate=imu_rate))
    accel = imu_values(log)[2:, 1]  # past the start and the first step's jump to speed
    assert accel.size == 499
    check_spread(accel, 0.0, math.sqrt(2.0) * SPEED_STD * rate)
    lag_one = float(np.corrcoef(accel[:-1], accel[1:])[0, 1])
    if imu_rate == rate:
        # Successive differences of white speeds share one speed: correlated -1/2.
        assert abs(lag_one + 0.5) < 5.0 / math.sqrt(accel.size), lag_one
    else:
        check_uncorrelated(accel[:-1], accel[1:])  # samples eight steps apart


def _doc(obj: object) -> str:
    return " ".join((obj.__doc__ or "").split())


def test_the_docstrings_quote_the_models_numbers() -> None:
    robot = _doc(Robot)
    travelled = 10.0 * MEAN_SPEED
    assert f"{travelled:.2f} m travelled at 100 Hz and 1 kHz alike" in robot
    headings = f"{heading_std(10.0, 100.0):.3f} rad and {heading_std(10.0, 1000.0):.3f} rad"
    assert f"a heading spread of {headings}" in robot
    sideways = (
        f"{100 * sideways_std(10.0, 100.0):.0f} cm and {100 * sideways_std(10.0, 1000.0):.1f} cm"
    )
    assert f"a sideways one of {sideways}" in robot  # 12 cm and 3.8 cm (13 and 4.3 before)
    assert "sqrt(2 * (1 - 2 / π)) * wheel_slip * u / D" in robot
    slow, fast = (math.sqrt(2.0) * SPEED_STD * rate for rate in (100.0, 1000.0))
    assert f"a forward spread of {slow:.1f} m/s² at 100 Hz, {fast:.0f} m/s² at 1 kHz" in _doc(Imu)


@pytest.mark.slow
@pytest.mark.parametrize(("rate", "runs"), [(100.0, 1000), (1000.0, 200)])
def test_the_heading_and_sideways_spread_of_seeded_drives_are_the_models(
    rate: float, runs: int
) -> None:
    ends = np.array([drive(rate, 10.0, seed)[1].poses[-1] for seed in range(runs)])
    check_normal(ends[:, 2], 0.0, heading_std(10.0, rate))
    check_normal(ends[:, 1], 0.0, sideways_std(10.0, rate))
