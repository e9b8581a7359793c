"""A PlanarFusion estimator is refused for a drive that can move sideways."""

from __future__ import annotations

import pytest
from shapely.geometry import box

from navkit.estimation import PlanarFusion
from navkit.geometry import Pose2D, Twist2D
from navkit.kinematics import DiffDrive, OmniDrive
from navkit.sim import Compass, Observation, Robot, Simulation, WheelEncoders, World


def _still(obs: Observation) -> Twist2D:
    return Twist2D(0.0, 0.0, 0.0)


def _simulation(drive: DiffDrive | OmniDrive) -> Simulation:
    robot = Robot(drive=drive, footprint=0.25, compass=Compass(),
                  encoders=WheelEncoders(ticks_per_rev=4096))  # fmt: skip
    fusion = PlanarFusion(x0=[0.0, 0.0, 0.0, 0.0, 0.0, 0.0], t0=0.0)
    world = World(box(-3.0, -3.0, 3.0, 3.0).exterior)
    return Simulation(world, robot, _still, start=Pose2D(0.0, 0.0, 0.0), estimator=fusion,
                      duration=0.5)  # fmt: skip


def test_omni_drive_with_planar_fusion_is_refused() -> None:
    # Its unicycle state dropped the wheels' sideways speed: an omni robot
    # strafing 1.5 m stayed at its start in the estimate.
    drive = OmniDrive.three_wheel(wheel_radius=0.05, base_radius=0.2)
    with pytest.raises(ValueError, match=r"estimator: PlanarFusion.*sideways"):
        _simulation(drive)


def test_diff_drive_with_planar_fusion_runs() -> None:
    trace = _simulation(DiffDrive(track=0.3, wheel_radius=0.05)).run()
    assert trace.metrics.estimate_error < 1e-6
