"""Long runs: the simulated encoder counters wrap, and a DiffOdometry estimator must not jump.

The robot's ``WheelEncoders`` report counters modulo ``2**bits`` (16 by default:
64 wheel turns, 20 m on a 5 cm wheel). A ``DiffOdometry`` built for counters
of another width (its default ``bits=None`` among them) read that
wrap-around as a huge backward step: after 40 m the estimate was at 20 m.
"""

from __future__ import annotations

import math

import pytest
from shapely.geometry import box

from navkit.estimation import DiffOdometry
from navkit.geometry import Twist2D
from navkit.kinematics import DiffDrive
from navkit.sim import Robot, Simulation, WheelEncoders, World

DRIVE = DiffDrive(track=0.3, wheel_radius=0.05)
CORRIDOR = World(box(-1.0, -2.0, 10.0, 2.0).exterior)
TICKS = 64  # an 8-bit counter then wraps every 4 wheel turns (1.26 m)


def _run(robot_bits: int | None, odometry_bits: int | None, omega: float) -> tuple[float, ...]:
    robot = Robot(
        drive=DRIVE, footprint=0.15, encoders=WheelEncoders(ticks_per_rev=TICKS, bits=robot_bits)
    )
    odometry = DiffOdometry(DRIVE, ticks_per_rev=TICKS, bits=odometry_bits)
    trace = Simulation(
        CORRIDOR, robot, lambda obs: Twist2D(1.0, 0.0, omega), start=(0.0, 0.0, 0.0),
        estimator=odometry, duration=5.0,
    ).run()  # fmt: skip
    true = trace.poses[-1]
    est = odometry.pose
    dtheta = math.remainder(est.theta - true[2], math.tau)
    return float(true[0]), float(true[1]), est.x, est.y, dtheta


@pytest.mark.parametrize(
    ("robot_bits", "odometry_bits"), [(8, None), (8, 16), (8, 64), (None, 8), (16, None), (8, 8)]
)
def test_diff_odometry_follows_the_robot_through_counter_wraps(
    robot_bits: int | None, odometry_bits: int | None
) -> None:
    x, y, ex, ey, dtheta = _run(robot_bits, odometry_bits, 0.1)
    assert x > 4.0  # several wraps of an 8-bit counter at 64 ticks a turn
    # Only the tick quantisation separates the odometry from the truth.
    assert math.hypot(ex - x, ey - y) < 0.05
    assert abs(dtheta) < 0.05


def test_the_estimate_does_not_depend_on_the_odometrys_counter_width() -> None:
    """Widths that can decode every reading's tick change give the same poses, bit for bit."""
    same = {_run(8, bits, -0.2)[2:] for bits in (None, 8, 12, 16, 32, 64)}
    assert len(same) == 1


def test_diff_odometry_reports_its_counter_width() -> None:
    assert DiffOdometry(DRIVE, ticks_per_rev=TICKS).bits is None
    assert DiffOdometry(DRIVE, ticks_per_rev=TICKS, bits=12).bits == 12
