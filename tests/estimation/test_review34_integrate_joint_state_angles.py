"""Review 34 (integrator lens): wheel angles where encoder counts are wanted.

A ROS 2 differential robot publishes its wheels as ``sensor_msgs/JointState``
positions, angles in radians (floats), not encoder counts. Given to
``DiffOdometry`` (or ``tick_delta``) they were refused with "must hold integer
counter readings, got dtype float64" alone, which does not say what to do with
angles; the message now says how to turn them into odometry.
"""

from __future__ import annotations

import itertools
import math

import numpy as np
import pytest

from navkit.estimation import DiffOdometry
from navkit.geometry import Pose2D
from navkit.kinematics import DiffDrive, tick_delta

DRIVE = DiffDrive(track=0.3, wheel_radius=0.05)


@pytest.mark.parametrize(
    "readings",
    [(0.25, 0.5), ([0.25, 1.0], [0.5, 1.5]), (np.array([0.25]), np.array([0.5]))],
    ids=["floats", "lists", "arrays"],
)
def test_wheel_angles_are_refused_with_the_way_to_odometry(readings: tuple[object, object]) -> None:
    odo = DiffOdometry(DRIVE, ticks_per_rev=4096)
    left, right = readings
    update = odo.update if isinstance(left, float) else odo.update_batch
    with pytest.raises(TypeError) as info:
        update(left, right)  # type: ignore[arg-type]
    message = str(info.value)
    assert "left_ticks must hold integer counter readings, got dtype float64" in message
    assert "radians" in message and "JointState" in message
    assert "odometry_step" in message
    assert odo.pose == Pose2D(0.0, 0.0, 0.0)  # nothing taken


def test_tick_delta_names_it_too() -> None:
    with pytest.raises(TypeError, match=r"current must hold integer counter readings.*radians"):
        tick_delta(3, 4.5, bits=16)


def test_the_way_the_message_gives_works() -> None:
    # The recipe the message names: distances rolled = wheel_radius x angle change,
    # stepped with DiffDrive.odometry_step. A quarter turn of the right wheel alone.
    angles = [(0.0, 0.0), (0.0, math.pi / 2)]
    pose = Pose2D(0.0, 0.0, 0.0)
    for (l0, r0), (l1, r1) in itertools.pairwise(angles):
        step = DRIVE.odometry_step(0.05 * (l1 - l0), 0.05 * (r1 - r0))
        pose = pose.compose(step)
    # The same motion from integer counts (4096 a turn: a quarter is 1024 ticks).
    odo = DiffOdometry(DRIVE, ticks_per_rev=4096)
    odo.update(0, 0)
    counted = odo.update(0, 1024)
    assert math.isclose(pose.x, counted.x, abs_tol=1e-15)
    assert math.isclose(pose.y, counted.y, abs_tol=1e-15)
    assert math.isclose(pose.theta, counted.theta, abs_tol=1e-15)


def test_integer_counts_and_integral_objects_still_pass() -> None:
    odo = DiffOdometry(DRIVE, ticks_per_rev=4096)
    odo.update(np.int64(5), 5)
    assert odo.update(1029, 1029).x > 0.0
    assert tick_delta(65535, 2, bits=16) == 3
