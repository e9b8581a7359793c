"""The simulator's random streams: independent noises, common random numbers, any physics rate.

``Simulation``'s docstring: every draw comes from the one seeded generator, in
the order the run needs them; the sensors' noises are independent of each
other and of the wheel slip; changing only the size of a noise that is on
(or a bias) keeps every draw, so that runs compare on common random numbers,
while a change that adds or removes draws moves every later one. And the
sensors' noise is per reading (``Compass``, ``Imu``), so with the sensors'
rates fixed the physics rate changes neither their noise's statistics nor,
for a held or ramping command, the encoders' counts (each wheel turns by the
exact integral of its speed profile, ``Robot``).
"""

from __future__ import annotations

import math
import sys
from pathlib import Path

import numpy as np
import pytest

from navkit.geometry import Twist2D
from navkit.kinematics import DiffDrive
from navkit.sim import (
    Circle,
    Compass,
    CompassReading,
    EncoderReading,
    Imu,
    ImuReading,
    Lidar,
    RangeNoise,
    Robot,
    ScanReading,
    Simulation,
    WheelEncoders,
    World,
)

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from noise_bands import ReadingLog, check_normal, check_uncorrelated

DIFF = DiffDrive(track=0.3, wheel_radius=0.05)
#: A round room of radius 2 m about the start: a LiDAR at its centre reads 2 m
#: on every beam whatever the heading, so that its noise is seen whole.
ROUND_ROOM = World(Circle((0.0, 0.0), 2.0, solid=False))
LIDAR = {"n_beams": 16, "range_max": 5.0, "rate": 10.0}
EXACT = Lidar(noise=None, **LIDAR)


TURN = Twist2D(0.0, 0.0, 1.0)


def run(
    robot: Robot, *, rate: float = 100.0, duration: float = 10.0, seed: int = 0,
    twist: Twist2D = TURN,
) -> tuple[ReadingLog, np.ndarray, np.ndarray]:  # fmt: skip
    """Open loop (the command ignores the readings): the log, the trace's times and poses."""
    log = ReadingLog()
    trace = Simulation(ROUND_ROOM, robot, lambda obs: twist, start=(0.0, 0.0, 0.0),
                       estimator=log, rate=rate, duration=duration, seed=seed).run()  # fmt: skip
    return log, trace.times, trace.poses


def compass_errors(log: ReadingLog, times: np.ndarray, poses: np.ndarray) -> np.ndarray:
    """Each compass reading less the noise-free one, rad, wrapped (the default north)."""
    yaw = dict(zip(times.tolist(), poses[:, 2].tolist(), strict=True))
    exact = Compass()
    out = []
    for r in log.of(CompassReading):
        assert isinstance(r, CompassReading)
        out.append(
            math.radians((r.heading_deg - exact.heading_deg(yaw[r.stamp]) + 180.0) % 360.0 - 180.0)
        )
    return np.array(out)


def gyro_errors(log: ReadingLog, times: np.ndarray, poses: np.ndarray, rate: float) -> np.ndarray:
    """Each gyro reading less its step's yaw rate (the heading change over ``1 / rate``)."""
    step = dict(zip(times[1:].tolist(), step_yaw_rates(poses, rate).tolist(), strict=True))
    imu = [r for r in log.of(ImuReading) if r.stamp > 0.0]
    return np.array([r.yaw_rate - step[r.stamp] for r in imu if isinstance(r, ImuReading)])


def scan_errors(log: ReadingLog, times: np.ndarray, poses: np.ndarray) -> np.ndarray:
    """Relative range errors of every scan, (scans, beams), against the exact scan."""
    at = dict(zip(times.tolist(), poses.tolist(), strict=True))
    rows = []
    for r in log.of(ScanReading):
        assert isinstance(r, ScanReading)
        exact = EXACT.scan(ROUND_ROOM, at[r.stamp]).ranges
        rows.append(r.scan.ranges / exact - 1.0)
    return np.array(rows)


def step_yaw_rates(poses: np.ndarray, rate: float) -> np.ndarray:
    """Each physics step's yaw rate: its heading change (wrapped) times ``rate``."""
    turn = np.diff(poses[:, 2])
    return ((turn + math.pi) % (2.0 * math.pi) - math.pi) * rate


def noisy_robot(*, compass: float = 0.05, gyro: float = 0.02, sigma: float = 0.02,
                slip: float = 0.1) -> Robot:  # fmt: skip
    return Robot(
        drive=DIFF, footprint=0.2, wheel_slip=slip, encoders=WheelEncoders(rate=50.0),
        compass=Compass(noise=compass, rate=100.0), imu=Imu(gyro_noise=gyro, rate=100.0),
        lidar=Lidar(noise=RangeNoise(limits=(math.inf,), sigma=(sigma,)), **LIDAR),
    )  # fmt: skip


def test_the_noises_of_different_sensors_and_the_slip_are_independent() -> None:
    log, times, poses = run(noisy_robot())
    yaw_rate = step_yaw_rates(poses, 100.0)  # slip-driven: a stream of its own
    gyro = gyro_errors(log, times, poses, 100.0)
    compass = compass_errors(log, times, poses)[1:]  # from step 1, as the gyro's
    assert gyro.size == compass.size == yaw_rate.size == 1000
    check_normal(gyro, 0.0, 0.02)
    check_normal(compass, 0.0, 0.05)
    check_uncorrelated(gyro, compass)
    check_uncorrelated(gyro, yaw_rate)
    check_uncorrelated(compass, yaw_rate)
    assert yaw_rate.std() > 0.03  # the slip does move the heading about (0.043 rad/s)
    scans = scan_errors(log, times, poses)  # 101 scans at 0.0, 0.1, ...: the compass's every tenth
    assert scans.shape == (101, 16)
    check_normal(scans.ravel(), 0.0, 0.02)
    at_scans = compass_errors(log, times, poses)[::10]
    for beam in range(16):
        check_uncorrelated(scans[:, beam], at_scans)


@pytest.mark.parametrize(
    ("change", "scaled"),
    [({"compass": 0.1}, "compass"), ({"gyro": 0.04}, "gyro"), ({"sigma": 0.04}, "lidar"),
     ({"slip": 0.2}, "slip")],
)  # fmt: skip
def test_changing_the_size_of_a_noise_keeps_every_draw(
    change: dict[str, float], scaled: str
) -> None:
    base_log, base_times, base_poses = run(noisy_robot(), duration=3.0, seed=5)
    log, times, poses = run(noisy_robot(**change), duration=3.0, seed=5)
    base, new = (base_log, base_times, base_poses), (log, times, poses)
    errors = {
        "compass": (compass_errors(*base), compass_errors(*new)),
        "gyro": (gyro_errors(*base, 100.0), gyro_errors(*new, 100.0)),
        "lidar": (scan_errors(*base), scan_errors(*new)),
        # Turning on the spot at 1 rad/s: each step's yaw rate less the slip's loss.
        "slip": (step_yaw_rates(base_poses, 100.0) - 1.0, step_yaw_rates(poses, 100.0) - 1.0),
    }
    for name, (before, after) in errors.items():
        assert before.size > 100
        # Twice the noise: twice each error (its draws kept); the others' draws are as before.
        np.testing.assert_allclose(after, 2.0 * before if name == scaled else before, atol=1e-9)
    if scaled != "slip":  # the motion too (the command ignores the readings)
        np.testing.assert_array_equal(poses, base_poses)
        ticks = [np.array([r.ticks for r in x.of(EncoderReading)]) for x in (base_log, log)]
        np.testing.assert_array_equal(*ticks)


def test_turning_a_noise_on_moves_the_later_draws_of_the_others() -> None:
    # The convention Simulation's docstring states (one generator, draws in order):
    # the compass's draws, once there, come before the IMU's of each stretch.
    quiet_log, times, poses = run(noisy_robot(compass=0.0, slip=0.0), duration=1.0, seed=6)
    loud_log, loud_times, loud_poses = run(noisy_robot(slip=0.0), duration=1.0, seed=6)
    np.testing.assert_array_equal(poses, loud_poses)  # no slip: the same motion
    quiet = gyro_errors(quiet_log, times, poses, 100.0)
    loud = gyro_errors(loud_log, loud_times, loud_poses, 100.0)
    assert quiet.size == loud.size == 100
    assert not np.any(np.isclose(quiet, loud, rtol=0.0, atol=1e-12))


@pytest.mark.parametrize("rate", [100.0, 400.0])
def test_the_physics_rate_changes_no_sensor_noise_and_no_encoder_count(rate: float) -> None:
    # Sensors at fixed rates, a ramping turn with unequal wheels: the encoders count
    # the same ticks at every physics rate, and the noise per reading keeps its spread.
    robot = Robot(
        drive=DIFF, footprint=0.2, max_wheel_acceleration=4.0,
        wheel_radius_error=np.array([0.01, -0.02]), encoders=WheelEncoders(rate=50.0),
        compass=Compass(noise=0.03, rate=50.0), imu=Imu(gyro_noise=0.01, rate=50.0),
    )  # fmt: skip
    log, times, poses = run(robot, rate=rate, duration=20.0, seed=7, twist=Twist2D(0.3, 0.0, 0.5))
    reference, _, _ = run(robot, rate=50.0, duration=20.0, seed=7, twist=Twist2D(0.3, 0.0, 0.5))
    ticks, expected = (np.array([r.ticks for r in x.of(EncoderReading)]) for x in (log, reference))
    assert ticks.shape == (1001, 2) and ticks[-1].min() > 1000
    np.testing.assert_array_equal(ticks, expected)
    check_normal(compass_errors(log, times, poses), 0.0, 0.03)
    # The gyro reads the yaw rate of the physics step ending at the sample.
    gyro = gyro_errors(log, times, poses, rate)
    assert gyro.size == 1000
    check_normal(gyro, 0.0, 0.01)
