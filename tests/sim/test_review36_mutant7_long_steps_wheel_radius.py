"""A robot whose wheels are larger than nominal does not tunnel (mutation review, session 40).

A segment's physics steps are checked along their arc only when a step may be
long for the footprint: ``_long_steps`` bounds the twist from the wheels' speeds
times ``1 + wheel_radius_error`` (the true radius over the nominal one). A
mutant that divided by that factor instead survived the simulator tests: the tunnelling
tests use exact wheels. With wheels 50 % larger than nominal, a command of
1.45 disc radii per step moves the robot 2.175 radii per step: the mutant took
that for a short step (0.97 radii) and the disc jumped a thin wall.

Oracle: geometry. Each run starts at another offset, so for some the ends of
two successive steps lie on both sides of the wall, clear of it; the robot must
stop touching the wall, never wholly past it, in every run.
"""

from __future__ import annotations

import numpy as np
from shapely.geometry import LineString

from navkit.geometry import Twist2D
from navkit.kinematics import DiffDrive
from navkit.sim import Observation, Robot, Simulation, World

RADIUS = 0.1
WALL_X = 1.0
RATE = 5.0


def _forward(_obs: Observation) -> Twist2D:
    return Twist2D(1.45 * RADIUS * RATE, 0.0, 0.0)  # 1.45 radii per step, nominally


def test_a_disc_on_oversized_wheels_stops_at_a_thin_wall_from_every_start() -> None:
    world = World(LineString([(WALL_X, -3.0), (WALL_X, 3.0)]))
    robot = Robot(
        drive=DiffDrive(track=0.3, wheel_radius=0.05),
        footprint=RADIUS,
        encoders=None,
        wheel_radius_error=0.5,
    )
    step = 1.5 * 1.45 * RADIUS  # the true distance per step
    jumps = 0
    for x0 in np.linspace(0.0, step, 48, endpoint=False):
        # Without the arc check, a step whose start and end both clear the wall,
        # on either side of it, jumps it.
        ends = x0 + step * np.arange(0, 12)
        if np.any(
            (ends + RADIUS < WALL_X) & (ends + step - RADIUS > WALL_X)
        ):  # a step that would jump the wall
            jumps += 1
        trace = Simulation(
            world, robot, _forward, start=(float(x0), 0.0, 0.0), rate=RATE, control_rate=RATE,
            duration=3.0,
        ).run()  # fmt: skip
        assert trace.metrics.reason == "collision", x0
        x, y, theta = trace.poses[-1]
        assert world.collides(RADIUS, (x, y, theta))
        # Never wholly past the wall (a step whose end overlaps it ends there).
        assert np.all(trace.poses[:, 0] - RADIUS <= WALL_X), x0
    assert jumps >= 2  # the wall lies between two free step ends in some runs
