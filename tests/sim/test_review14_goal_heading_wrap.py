"""The goal's heading check wraps the heading error with navkit's one wrap.

The simulator compared a goal heading by ``abs((a - b + π) % 2π - π)``: adding π
rounds away the low bits of a small error (3e-16 read as 4.4e-16) and turns an
error just below π into π itself. Both the check at the start (Python) and the
one in the run kernel now use the exact wrap, so a goal is reached exactly when
``|angle_diff(heading, goal yaw)| <= yaw_tolerance``.
"""

from __future__ import annotations

import math

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from shapely.geometry import box

from hypothesis_twins import slow_twin
from navkit.geometry import Twist2D, angle_diff
from navkit.kinematics import DiffDrive
from navkit.sim import Robot, Simulation, Trace, World

WORLD = World(box(-5.0, -5.0, 5.0, 5.0).exterior)
ROBOT = Robot(drive=DiffDrive(track=0.3, wheel_radius=0.05), footprint=0.15)
BELOW_PI = math.nextafter(math.pi, 0.0)


def _run(
    start: tuple[float, float, float], goal_yaw: float, tol: float, duration: float = 4.0
) -> Trace:
    return Simulation(
        WORLD, ROBOT, lambda _obs: Twist2D(0.5), start=start, goal=(0.0, 0.0, goal_yaw),
        goal_tolerance=0.1, yaw_tolerance=tol, duration=duration,
    ).run()  # fmt: skip


@pytest.mark.parametrize(
    ("goal_yaw", "tol"),
    [
        (-3e-16, 3.5e-16),  # the old formula read the 3e-16 error as 4.4e-16
        (-BELOW_PI, BELOW_PI),  # and an error one ulp below π as π
    ],
)
@pytest.mark.parametrize("start_x", [0.0, -1.0])  # at the start (Python), on the way (kernel)
def test_heading_error_is_exact(goal_yaw: float, tol: float, start_x: float) -> None:
    # Driving straight keeps the heading exactly 0, so the error is exactly -goal_yaw.
    trace = _run((start_x, 0.0, 0.0), goal_yaw, tol)
    assert set(trace.poses[:, 2]) == {0.0}
    assert trace.metrics.reached and trace.metrics.reason == "goal reached"
    assert (trace.metrics.time_to_goal == 0.0) == (start_x == 0.0)
    # One ulp tighter and the same heading is refused.
    tighter = _run((start_x, 0.0, 0.0), goal_yaw, math.nextafter(abs(goal_yaw), 0.0))
    assert not tighter.metrics.reached and tighter.metrics.reason == "timeout"


@settings(max_examples=40, deadline=None)
@given(
    st.floats(-math.pi, math.pi, exclude_min=True),
    st.floats(-math.pi, math.pi, exclude_min=True),
    st.floats(1e-12, math.pi),
)
def test_start_check_agrees_with_angle_diff(heading: float, goal_yaw: float, tol: float) -> None:
    trace = _run((0.0, 0.0, heading), goal_yaw, tol, duration=0.05)
    expected = abs(angle_diff(heading, goal_yaw)) <= tol
    assert (trace.metrics.time_to_goal == 0.0) == expected


test_start_check_agrees_with_angle_diff_thoroughly = slow_twin(
    test_start_check_agrees_with_angle_diff, max_examples=300
)


@pytest.mark.parametrize("wrap_side", [1.0, -1.0])
def test_turning_through_pi_reaches_a_goal_across_the_cut(wrap_side: float) -> None:
    """A heading that crosses ±π meets a goal yaw on the other side of the cut."""
    goal_yaw = -wrap_side * 3.1  # 0.083 rad past the cut from a heading of +-3.0
    trace = Simulation(
        WORLD, ROBOT, lambda _obs: Twist2D(0.0, 0.0, wrap_side * 0.5),
        start=(0.0, 0.0, wrap_side * 3.0), goal=(0.0, 0.0, goal_yaw), yaw_tolerance=0.01,
        duration=4.0,
    ).run()  # fmt: skip
    m = trace.metrics
    assert m.reached
    # (π - 3.0) + (π - 3.1) = 0.1832 rad to turn at 0.5 rad/s, less the tolerance.
    turn = (math.pi - 3.0) + (math.pi - 3.1) - 0.01
    assert m.time_to_goal == pytest.approx(turn / 0.5, abs=0.03)
    assert abs(angle_diff(float(trace.poses[-1, 2]), goal_yaw)) <= 0.01
