"""A fast robot beside a wall: the arc check ends at the step's end (mutation review, session 40).

A long step is checked along its arc from the pose before it, in advances of
the clearance (at least ``sweep``), until what is left of the step is clear.
The older tunnelling tests drive across open floor, where the first pose's
clearance already covers the whole step: a mutant that counted what is left
as ``span + done`` instead of ``span - done`` survived them. Beside a wall the
clearance stays small, and that mutant walked the arc on past the step's end
until it met the wall ahead: the robot jumped metres in one step.

Oracle: kinematics and geometry. A disc driving straight at constant speed
advances exactly ``v / rate`` per step while it is clear of everything, and
stops where it first touches the wall ahead.
"""

from __future__ import annotations

import numpy as np
import pytest
from shapely.geometry import LineString

from navkit.geometry import Twist2D
from navkit.kinematics import DiffDrive
from navkit.sim import MovingObstacle, Observation, Robot, Simulation, World

RADIUS = 0.1
SPEED = 2.0  # m/s: 0.4 m per step at 5 Hz, four radii
RATE = 5.0
END_X = 3.0  # the wall ahead
SIDE = LineString([(-1.0, 0.15), (10.0, 0.15)])  # 5 cm beside the disc all the way
AHEAD = LineString([(END_X, -2.0), (END_X, 2.0)])
FAR_BALL = MovingObstacle.constant_velocity(0.1, start_xy=(-5.0, 5.0), velocity_xy=(0.0, 0.1))


def _forward(_obs: Observation) -> Twist2D:
    return Twist2D(SPEED, 0.0, 0.0)


@pytest.mark.parametrize(
    "world",
    [World([SIDE, AHEAD]), World([SIDE, AHEAD], moving=[FAR_BALL])],
    ids=["edges-only", "full-kernel"],
)
def test_a_fast_disc_beside_a_wall_advances_a_step_at_a_time_to_the_wall_ahead(
    world: World,
) -> None:
    robot = Robot(drive=DiffDrive(track=0.3, wheel_radius=0.05), footprint=RADIUS, encoders=None)
    trace = Simulation(
        world, robot, _forward, start=(0.0, 0.0, 0.0), rate=RATE, control_rate=RATE, duration=3.0
    ).run()
    assert trace.metrics.reason == "collision"
    assert trace.metrics.collisions == 1
    x = trace.poses[:, 0]
    step = SPEED / RATE
    free = int(np.floor((END_X - RADIUS) / step))  # step ends clear of the wall ahead: 0..7
    np.testing.assert_allclose(x[: free + 1], step * np.arange(free + 1), rtol=0.0, atol=1e-12)
    np.testing.assert_allclose(trace.poses[:, 1:], 0.0, atol=1e-12)
    # The last pose touches the wall ahead, between the last free step end and the wall.
    assert x.shape[0] == free + 2
    assert step * free < x[-1] <= END_X - RADIUS + 1e-9
    assert world.collides(RADIUS, tuple(trace.poses[-1]))
