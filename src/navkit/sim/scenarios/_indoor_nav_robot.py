"""The indoor-navigation robot: drive, wheel errors, encoders, IMU, LiDAR, EKF, tracker.

Shared by the mapping tour (:mod:`._indoor_nav_mapping`) and the localisation,
planning and tracking runs (:mod:`._indoor_nav_runs`).
"""

from __future__ import annotations

import math

import numpy as np

from navkit.control import OnOffTracker
from navkit.estimation import PlanarFusion
from navkit.geometry import Pose2D, angle_diff
from navkit.kinematics import DiffDrive
from navkit.sim import Compass, Imu, Lidar, RangeNoise, Robot, WheelEncoders
from navkit.sim.scenarios._indoor_nav_lab import BODY_RADIUS

__all__ = [
    "CONTROL_RATE",
    "DRIVE",
    "ENCODER_BITS",
    "GYRO_NOISE",
    "HEADING_NOISE",
    "LIDAR",
    "PHYSICS_RATE",
    "RADIUS_ERROR_SIGMA",
    "SPEED",
    "SUCCESS_RADIUS",
    "TICKS_PER_REV",
    "TURN_RATE",
    "WHEEL_SLIP",
    "errors",
    "fusion",
    "make_robot",
    "make_tracker",
]

#: The robot: a differential drive, 0.40 m track, 75 mm wheels.
DRIVE = DiffDrive(track=0.40, wheel_radius=0.075)
TICKS_PER_REV = 2048
ENCODER_BITS = 16
PHYSICS_RATE = 100.0  # Hz
CONTROL_RATE = 20.0  # Hz
#: Wheel imperfections: each wheel's true radius is off by N(0, 0.2 %) (after a
#: calibration), and slip takes N(0, 0.5 %) of the rim speed per physics step.
RADIUS_ERROR_SIGMA = 0.002
WHEEL_SLIP = 0.005
#: The 9-DoF IMU: gyro white noise (rad/s), gyro bias spread (rad/s), accelerometer
#: noise (m/s²); its magnetometer heading (the Compass): noise and bias spread (rad).
GYRO_NOISE = 0.005
GYRO_BIAS_SIGMA = 0.0005
ACCEL_NOISE = 0.05
HEADING_NOISE = math.radians(2.0)
HEADING_BIAS_SIGMA = math.radians(0.5)
#: The mapping LiDAR (the paper does not name its scanner): an RPLIDAR A1-class
#: 360-beam, 10 Hz, 12 m scanner at the robot's centre, with the A1 datasheet's
#: accuracy as relative range noise: 1 % below 3 m, 2 % to 5 m, 2.5 % beyond.
LIDAR = Lidar(
    n_beams=360,
    range_min=0.15,
    range_max=12.0,
    noise=RangeNoise(limits=(3.0, 5.0, math.inf), sigma=(0.01, 0.02, 0.025)),
    rate=10.0,
)
#: EKF process noise per second for [x, y, θ, v, ω, a]: robot_localization's defaults
#: except the heading's, 1e-4 rad²/s instead of 0.06: the heading follows the turn
#: rate, which the gyro measures, so it needs little noise of its own; with the default
#: the filter follows the magnetometer's noise (about 1.4° mean heading error here).
PROCESS_NOISE = (0.05, 0.05, 1e-4, 0.025, 0.02, 0.01)
#: ON-OFF tracker settings (heading tolerance and goal tolerance are the paper's).
SPEED = 0.3  # m/s
TURN_RATE = 0.6  # rad/s
#: A tracked path ends within this distance of its goal (true position), m.
SUCCESS_RADIUS = 0.2


def make_robot(rng: np.random.Generator, *, lidar: bool = False) -> Robot:
    """The indoor robot with this trial's wheel errors and sensor biases (and the LiDAR).

    Examples
    --------
    >>> robot = make_robot(np.random.default_rng(0))
    >>> robot.n_wheels, robot.imu is not None, robot.compass is not None, robot.lidar
    (2, True, True, None)
    >>> make_robot(np.random.default_rng(0), lidar=True).lidar.n_beams
    360
    """
    radius_error = np.clip(rng.normal(0.0, RADIUS_ERROR_SIGMA, 2), -0.01, 0.01)
    gyro_bias = float(rng.normal(0.0, GYRO_BIAS_SIGMA))
    heading_bias = float(np.clip(rng.normal(0.0, HEADING_BIAS_SIGMA), -0.05, 0.05))
    return Robot(
        drive=DRIVE,
        footprint=BODY_RADIUS,
        max_wheel_speed=12.0,
        max_wheel_acceleration=20.0,
        wheel_slip=WHEEL_SLIP,
        wheel_radius_error=radius_error,
        encoders=WheelEncoders(ticks_per_rev=TICKS_PER_REV, bits=ENCODER_BITS, rate=50.0),
        imu=Imu(gyro_noise=GYRO_NOISE, gyro_bias=gyro_bias, accel_noise=ACCEL_NOISE, rate=50.0),
        compass=Compass(noise=HEADING_NOISE, bias=heading_bias, rate=10.0),
        lidar=LIDAR if lidar else None,
    )


def make_tracker(max_speed: float = SPEED, rotate_omega: float = TURN_RATE) -> OnOffTracker:
    """The ON-OFF tracker with the scenario's settings (or another speed and turn rate).

    Examples
    --------
    >>> make_tracker().max_speed, make_tracker(0.2, 0.4).rotate_omega
    (0.3, 0.4)
    """
    return OnOffTracker(max_speed=max_speed, rotate_omega=rotate_omega,
                        rotate_angle=math.radians(10.0), goal_tolerance=0.05)  # fmt: skip


def fusion(start: Pose2D) -> PlanarFusion:
    """The EKF (wheel odometry + IMU) started at ``start``, at rest, at t = 0.

    Examples
    --------
    >>> fusion(Pose2D(1.0, 2.0, 0.5)).pose
    Pose2D(x=1.0, y=2.0, theta=0.5)
    """
    return PlanarFusion(
        x0=[start.x, start.y, start.theta, 0.0, 0.0, 0.0], process_noise=PROCESS_NOISE, t0=0.0
    )


def errors(truth: Pose2D, estimate: Pose2D) -> tuple[float, float, float]:
    """Absolute errors in x, y (m) and heading (rad) of an estimate.

    Examples
    --------
    >>> errors(Pose2D(0.0, 0.0, 3.1), Pose2D(0.1, -0.2, -3.1))[:2]
    (0.1, 0.2)
    """
    dth = angle_diff(estimate.theta, truth.theta)
    return abs(estimate.x - truth.x), abs(estimate.y - truth.y), abs(dth)
