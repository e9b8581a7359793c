"""Simulation(goal=(x, y, theta)): the heading counts only with yaw_tolerance, as documented."""

from __future__ import annotations

import math

import pytest
from shapely.geometry import box

from navkit.geometry import Twist2D
from navkit.kinematics import DiffDrive
from navkit.sim import Observation, Robot, Simulation, World

WORLD = World([box(0.0, 0.0, 6.0, 4.0).exterior])
ROBOT = Robot(drive=DiffDrive(track=0.3, wheel_radius=0.05), footprint=0.15, encoders=None)


def forward(obs: Observation) -> Twist2D:
    return Twist2D(0.4, 0.0, 0.0)  # along +x: arrives facing 0 rad


@pytest.mark.parametrize(
    ("yaw_tolerance", "reached"), [(None, True), (0.1, False), (math.pi, True)]
)
def test_a_goal_heading_counts_only_with_a_yaw_tolerance(
    yaw_tolerance: float | None, reached: bool
) -> None:
    goal = (3.0, 1.0, math.pi)  # facing the other way
    metrics = Simulation(WORLD, ROBOT, forward, start=(1.0, 1.0, 0.0), goal=goal,
                         yaw_tolerance=yaw_tolerance, duration=8.0).run().metrics  # fmt: skip
    assert metrics.reached is reached
    assert metrics.reason == ("goal reached" if reached else "timeout")
