"""The collision pose of a long step swept along its arc (review 34, mutation testing).

A mutant of ``_sweep_static`` that placed the footprint along the arc with
another state component (the speed) for its heading lived: the tunnelling
tests drive footprints whose contact with the wall hardly depends on the
heading. Here a 0.6 m stick pointing forward drives at a wall in 1 m steps, its
steps' ends clear of the wall on both sides (x = 0.6, then 1.6), so the step
is swept; its front touches the wall first at x = 0.7 (0.7 + 0.3 = 1), by the
geometry of the stick, and its heading stays 0 (it drives straight).
"""

from __future__ import annotations

from shapely.geometry import LineString

from navkit.geometry import Twist2D
from navkit.kinematics import DiffDrive
from navkit.sim import Observation, Robot, Simulation, World

STICK = [[-0.3, -0.05], [0.3, -0.05], [0.3, 0.05], [-0.3, 0.05]]


def _forward(_obs: Observation) -> Twist2D:
    return Twist2D(2.0, 0.0, 0.0)


def test_a_swept_step_stops_a_stick_where_its_front_meets_the_wall() -> None:
    world = World(LineString([(1.0, -3.0), (1.0, 3.0)]))
    bot = Robot(drive=DiffDrive(track=0.3, wheel_radius=0.05), footprint=STICK, encoders=None)
    start = (-0.4, 0.0, 0.0)
    assert not world.collides(STICK, (0.6, 0.0, 0.0))  # the steps' ends are free
    assert not world.collides(STICK, (1.6, 0.0, 0.0))
    trace = Simulation(
        world, bot, _forward, start=start, rate=2.0, control_rate=2.0, duration=3.0
    ).run()
    assert trace.metrics.reason == "collision"
    x, y, theta = trace.poses[-1]
    assert theta == 0.0 and y == 0.0
    # The first pose found touching: front at the wall, at most one inner-disc step
    # (0.05 m, the stick's half width) past first contact.
    assert 0.7 - 1e-9 <= x <= 0.75 + 1e-9
    assert world.collides(STICK, (x, y, theta))
