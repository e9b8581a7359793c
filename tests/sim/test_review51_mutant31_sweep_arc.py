"""Review 51 (MUTANT31): a swept step checks the poses along its own arc, turning its way.

INLINE's dfaec1d calls ``integrate_scalar`` directly for the poses along a
step that ``_sweep_static`` checks (``arc_pose`` gone). A mutant turning those
poses the other way (``-omega``) passed every test: their steps drive
straight. Here a disc turns left at 1 rad/s in one 1 s step; both ends of the
step are clear, and a post stands on the arc's middle, left of the straight
line: the step must stop on it, at a pose on the arc.
"""

from __future__ import annotations

import math

from navkit.geometry import Twist2D
from navkit.kinematics import DiffDrive
from navkit.sim import Circle, Observation, Robot, Simulation, World

RADIUS = 0.05


def _turning(_obs: Observation) -> Twist2D:
    return Twist2D(1.0, 0.0, 1.0)


def test_a_turning_step_stops_at_a_post_on_its_arc() -> None:
    post = (math.sin(0.5), 1.0 - math.cos(0.5))  # the arc at t = 0.5 s
    world = World([Circle(post, 0.05)])
    bot = Robot(drive=DiffDrive(track=0.3, wheel_radius=0.05), footprint=RADIUS, encoders=None)
    end = (math.sin(1.0), 1.0 - math.cos(1.0), 1.0)
    assert not world.collides(RADIUS, (0.0, 0.0, 0.0))  # the step's ends are free
    assert not world.collides(RADIUS, end)
    assert not world.collides(RADIUS, (post[0], -post[1], -0.5))  # the mirrored arc too
    trace = Simulation(
        world, bot, _turning, start=(0.0, 0.0, 0.0), rate=1.0, control_rate=1.0, duration=1.0
    ).run()
    assert trace.metrics.reason == "collision"
    x, y, theta = trace.poses[-1]
    assert world.collides(RADIUS, (x, y, theta))
    # On the arc of radius 1 about (0, 1), before the post.
    assert abs(math.hypot(x, y - 1.0) - 1.0) < 1e-9
    assert 0.0 < theta < 0.5 and y > 0.0
