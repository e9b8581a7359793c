"""Simulation and TrackerController print what they are (review 32, OBJECTS).

Both printed Python's default ``<navkit.sim._simulation.Simulation object at
0x7f...>``: nothing of the run, and a private module path. They now print
their world, start, goal, duration and rates, and their tracker, control rate
and pose source, under the class's own name (a subclass's too).
"""

from __future__ import annotations

from shapely.geometry import box

from navkit.control import FollowTheCarrot
from navkit.geometry import Twist2D
from navkit.kinematics import DiffDrive
from navkit.sim import Observation, Robot, Simulation, TrackerController, World


def _stop(_: Observation) -> Twist2D:
    return Twist2D(0.0, 0.0, 0.0)


def _simulation(cls: type[Simulation] = Simulation, **kw: object) -> Simulation:
    world = World(box(-10.0, -10.0, 10.0, 10.0).exterior)
    robot = Robot(drive=DiffDrive(track=0.3, wheel_radius=0.05), footprint=0.2)
    return cls(world, robot, _stop, start=(1.0, 2.0, 0.5), duration=3.0, **kw)  # type: ignore[arg-type]


def test_a_simulation_prints_its_run() -> None:
    text = repr(_simulation(goal=(5.0, 5.0)))
    assert text == (
        "Simulation(World(<4 edges, 0 circles>, grid=None, moving=<0 obstacles>), "
        "start=Pose2D(x=1.0, y=2.0, theta=0.5), goal=(5.0, 5.0), duration=3.0, "
        "rate=100.0, control_rate=20.0)"
    )


def test_a_goal_with_a_heading_and_no_goal() -> None:
    assert "goal=(5.0, 5.0, 1.0)," in repr(_simulation(goal=(5.0, 5.0, 1.0)))
    assert "goal=None," in repr(_simulation())


def test_a_tracker_controller_prints_its_tracker_and_rate() -> None:
    tracker = FollowTheCarrot(max_speed=0.5)
    for rate in (20.0, 3.0, 13.7, 0.1):
        text = repr(TrackerController(tracker, control_rate=rate, use_estimate=False))
        assert text == f"TrackerController({tracker!r}, control_rate={rate!r}, use_estimate=False)"


def test_subclasses_are_named_as_themselves() -> None:
    class MySimulation(Simulation):
        __slots__ = ()

    class MyController(TrackerController[FollowTheCarrot]):
        __slots__ = ()

    assert repr(_simulation(MySimulation)).startswith("MySimulation(World(")
    controller = MyController(FollowTheCarrot(), control_rate=10.0)
    assert repr(controller).startswith("MyController(FollowTheCarrot(")
    assert "object at 0x" not in repr(controller) + repr(_simulation())
