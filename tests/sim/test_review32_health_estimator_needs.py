"""DiffOdometry as a simulation's estimator on a robot without encoders (review 32).

tests/sim/test_review28_lead_sim_advice.py covers the other refusals; this one
was not reached.
"""

from __future__ import annotations

import pytest
from shapely.geometry import box

from navkit.estimation import DiffOdometry
from navkit.geometry import Twist2D
from navkit.kinematics import DiffDrive
from navkit.sim import Observation, Robot, Simulation, World

ROOM = World(box(-1.0, -1.0, 1.0, 1.0).exterior)
DIFF = DiffDrive(track=0.3, wheel_radius=0.05)


def _still(obs: Observation) -> Twist2D:
    return Twist2D(0.0, 0.0, 0.0)


def test_diff_odometry_needs_wheel_encoders_and_says_how_to_give_them() -> None:
    no_encoders = Robot(drive=DIFF, footprint=0.2, encoders=None)
    odometry = DiffOdometry(DIFF, ticks_per_rev=1024)
    with pytest.raises(
        ValueError,
        match=r"^estimator: DiffOdometry needs wheel encoders.*Robot\(encoders=WheelEncoders\(\)\)",
    ):
        Simulation(ROOM, no_encoders, _still, start=(0.0, 0.0, 0.0), estimator=odometry)
    fixed = Robot(drive=DIFF, footprint=0.2)
    Simulation(ROOM, fixed, _still, start=(0.0, 0.0, 0.0), estimator=odometry, duration=0.1).run()
