"""A ``TrackerController`` tracking the estimate in a run without an estimator (review 31).

It sent zero twists for the whole run (no estimate ever came): the robot stood
still until the timeout, with no event saying why. The simulation now refuses it.
"""

from __future__ import annotations

import pytest
from shapely.geometry import box

from navkit.control import FollowTheCarrot
from navkit.geometry import Pose2D
from navkit.kinematics import DiffDrive
from navkit.sim import Robot, Simulation, TrackerController, World


def _parts() -> tuple[World, Robot, FollowTheCarrot]:
    world = World(box(-1.0, -1.0, 5.0, 3.0).exterior)
    robot = Robot(drive=DiffDrive(track=0.3, wheel_radius=0.05), footprint=0.15)
    tracker = FollowTheCarrot(max_speed=0.5)
    tracker.set_path([[0.0, 0.0], [3.0, 0.0]])
    return world, robot, tracker


class _Stuck:
    """An estimator (the ``Estimator`` protocol) that never moves from the start."""

    pose: Pose2D | None = Pose2D(0.0, 0.0, 0.0)

    def observe(self, t: float, reading: object) -> None:
        pass


def test_tracking_an_estimate_that_never_comes_is_refused() -> None:
    world, robot, tracker = _parts()
    follow = TrackerController(tracker, control_rate=10.0)
    with pytest.raises(ValueError, match=r"^controller: TrackerController\(use_estimate=True\)"):
        Simulation(world, robot, follow, start=(0.0, 0.0, 0.0), duration=5.0)


def test_the_true_pose_or_an_estimator_drive_the_robot() -> None:
    world, robot, tracker = _parts()
    oracle = TrackerController(tracker, control_rate=10.0, use_estimate=False)
    trace = Simulation(world, robot, oracle, start=(0.0, 0.0, 0.0), duration=5.0).run()
    assert trace.poses[-1, 0] > 1.0
    world, robot, tracker = _parts()
    follow = TrackerController(tracker, control_rate=10.0)
    estimated = Simulation(
        world, robot, follow, start=(0.0, 0.0, 0.0), duration=5.0, estimator=_Stuck()
    )
    assert estimated.run().poses[-1, 0] > 1.0
