"""Review 48 (SIMGOAL): a goal tolerance below where the controller comes to rest.

A ``PotentialFieldController`` refuses its own ``goal_tolerance`` at or below the
distance at which its attraction brings the robot to rest (3.75 mm from the goal
with the default ``BlendedAttraction``, review 47). The simulation's
``goal_tolerance`` is the run's own criterion, and the simulator cannot see that
distance (the controller it is given is any callable; the distance is not public
API): a run whose tolerance is below it never reaches the goal and ends at its
``duration``. Documented at ``Simulation(goal_tolerance=)``; checked here, with
the controller's own ``goal_tolerance`` reached.
"""

from __future__ import annotations

import pytest
from shapely.geometry import box

from navkit.control import PotentialFieldController
from navkit.geometry import Pose2D, Twist2D
from navkit.kinematics import OmniDrive
from navkit.sim import Observation, Robot, Simulation, World

GOAL = Pose2D(2.0, 1.0, 0.0)


def _run(goal_tolerance: float) -> tuple[PotentialFieldController, Simulation]:
    ctl = PotentialFieldController(drive="omni", goal_tolerance=0.05)

    def control(obs: Observation) -> Twist2D:
        return ctl.step(obs.true_pose, GOAL, 0.05 if obs.dt is None else obs.dt)

    robot = Robot(
        drive=OmniDrive([0.0, 2.0944, 4.1888], wheel_radius=0.05, base_radius=0.2),
        footprint=0.15,
    )
    sim = Simulation(
        World([box(0.0, 0.0, 3.0, 2.0).exterior]), robot, control, start=(1.0, 1.0, 0.0),
        goal=(GOAL.x, GOAL.y), goal_tolerance=goal_tolerance, duration=12.0,
        control_rate=20.0,
    )  # fmt: skip
    return ctl, sim


@pytest.mark.parametrize("tolerance", [0.05, 0.005])
def test_a_tolerance_beyond_the_rest_distance_is_reached(tolerance: float) -> None:
    _ctl, sim = _run(tolerance)
    metrics = sim.run().metrics
    assert metrics.reached, metrics
    assert metrics.final_error <= tolerance


def test_a_tolerance_within_the_rest_distance_is_never_reached() -> None:
    ctl, sim = _run(0.002)
    metrics = sim.run().metrics
    # The robot settles 3.75 mm from the goal, the controller done (within its own
    # 0.05 m), and the run goes on to its duration.
    assert not metrics.reached
    assert metrics.reason == "timeout"
    assert ctl.done
    assert 0.0035 < metrics.final_error < 0.004
