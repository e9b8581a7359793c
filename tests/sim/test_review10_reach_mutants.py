"""Mutation gap: a polygon footprint's reach is its FARTHEST point from the reference point.

``navkit.sim._segment_kernels`` checks a step along its arc when its span,
``(|v| + |omega| * reach) * dt``, exceeds the radius of a disc inside the
footprint. For a footprint whose reference point lies near one end (a stick
pivoting about its end, like a robot arm or a towed bar), the farthest vertex
is far and the nearest one close; a reach taken from the nearest vertex makes
a fast turn look short, and the stick's far end sweeps through a thin wall or a
post between two step ends without a collision. The existing spinning-stick
test pivots a symmetric stick about its centre, where every vertex is equally
far, so it cannot tell the two apart.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from shapely.geometry import LineString, Point, Polygon
from shapely.geometry.base import BaseGeometry

from navkit.geometry import Twist2D
from navkit.kinematics import DiffDrive
from navkit.sim import Circle, MovingObstacle, Observation, Robot, Simulation, World

#: A 1 m stick, 2 cm wide, pivoting 1 cm from its near end: its vertices are
#: 0.014 m and 1.0 m from the reference point (the inner disc's radius is 0.01 m).
STICK = [[-0.01, -0.01], [1.0, -0.01], [1.0, 0.01], [-0.01, 0.01]]
#: 6 rad/s at 10 Hz: 0.6 rad a step, so the far end moves 0.6 m along its arc.
OMEGA = 6.0
RATE = 10.0
BETWEEN = 0.3  # an obstacle's bearing, between the first two step ends' headings 0 and 0.6
FAR_BALL = MovingObstacle.constant_velocity(0.1, start_xy=(-5.0, 5.0), velocity_xy=(0.0, 0.1))


def _spin(_obs: Observation) -> Twist2D:
    return Twist2D(0.0, 0.0, OMEGA)


def _stick_at(theta: float) -> Polygon:
    c, s = math.cos(theta), math.sin(theta)
    return Polygon([(c * x - s * y, s * x + c * y) for x, y in STICK])


def _radial_wall() -> LineString:
    c, s = math.cos(BETWEEN), math.sin(BETWEEN)
    return LineString([(0.55 * c, 0.55 * s), (0.9 * c, 0.9 * s)])


def _post() -> Point:
    return Point(0.8 * math.cos(BETWEEN), 0.8 * math.sin(BETWEEN)).buffer(0.02)


@pytest.mark.parametrize("kind", ["wall", "post", "wall-with-moving"])
def test_a_stick_spinning_about_its_end_does_not_sweep_through_an_obstacle(kind: str) -> None:
    shape: BaseGeometry
    if kind == "post":
        shape = _post()
        world = World(Circle(np.array([0.8 * math.cos(BETWEEN), 0.8 * math.sin(BETWEEN)]), 0.02))
    elif kind == "wall":
        shape = _radial_wall()
        world = World(shape)
    else:  # the full kernel (moving obstacles), far from the stick
        shape = _radial_wall()
        world = World([shape], moving=[FAR_BALL])
    # Independently of navkit: the obstacle is clear of the stick at every step end
    # (headings 0, 0.6, 1.2, ...) but lies on the stick's path between the first two.
    step = OMEGA / RATE
    for k in range(6):
        assert not _stick_at(k * step).intersects(shape)
        assert not world.collides(STICK, (0.0, 0.0, k * step))
    assert _stick_at(BETWEEN).intersects(shape)
    bot = Robot(drive=DiffDrive(track=0.3, wheel_radius=0.05), footprint=STICK, encoders=None)
    trace = Simulation(
        world, bot, _spin, start=(0.0, 0.0, 0.0), rate=RATE, control_rate=RATE, duration=0.5
    ).run()
    assert trace.metrics.reason == "collision"
    assert trace.metrics.collisions == 1
    x, y, theta = trace.poses[-1]
    assert world.collides(STICK, (x, y, theta))
    # Stopped on the near side, where it first touches: not past the obstacle.
    assert 0.0 < theta < BETWEEN
    assert np.all(trace.poses[:, 2] < BETWEEN)
