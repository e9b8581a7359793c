"""Second-wave review of the simulator core: arguments at the ends of their ranges."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from navkit.geometry import Pose2D, Twist2D
from navkit.kinematics import DiffDrive
from navkit.sim import MovingObstacle, Robot, Simulation, Table, World


def _forward(_obs: object) -> Twist2D:
    return Twist2D(0.5, 0.0, 0.0)


_ROBOT = Robot(drive=DiffDrive(track=0.3, wheel_radius=0.05), footprint=0.2)


@pytest.mark.parametrize(
    "goal",
    [(-1.7e308, 1.7e308), (1e13, 0.0), (0.0, -1e300, 0.5), Pose2D(2e12, 0.0, 0.0)],
)
def test_goal_beyond_the_pose_bound_is_refused_when_built(goal: Pose2D | tuple[float, ...]) -> None:
    # It used to be accepted, and a goal 1.7e308 away failed after the whole run
    # with "final_error must be finite", an argument the caller never gave.
    with pytest.raises(ValueError, match="goal"):
        Simulation(World(), _ROBOT, _forward, start=(0.0, 0.0, 0.0), goal=goal, duration=0.1)


@pytest.mark.parametrize("goal", [(1e12, -1e12), (-1e12, 1e12, 0.0), Pose2D(1e12, 1e12, 0.0)])
def test_goal_at_the_pose_bound_gives_its_final_error(goal: Pose2D | tuple[float, ...]) -> None:
    trace = Simulation(
        World(), _ROBOT, _forward, start=(0.0, 0.0, 0.0), goal=goal, duration=0.1
    ).run()
    gx, gy = (goal.x, goal.y) if isinstance(goal, Pose2D) else goal[:2]
    x, y = trace.poses[-1, :2]
    assert trace.metrics.final_error == math.hypot(x - gx, y - gy)
    assert math.isfinite(trace.metrics.final_error)


@settings(max_examples=60, deadline=None)
@given(
    st.floats(1e3, 1e6),
    st.floats(1e-300, 1e-9),
    st.sampled_from([1e-3, 1.0, 1e3]),
)
def test_scripted_speed_names_a_leg_too_short_to_take_time(
    first: float, second: float, speed: float
) -> None:
    # A leg below the rounding of the time already spent gets the same time as the
    # waypoint before it: refused naming the waypoints (the caller gave no times).
    points = [(-first, 0.0), (first, 0.0), (first, second)]
    legs = np.hypot(*np.diff(np.array(points), axis=0).T)
    stamps = np.concatenate(([0.0], np.cumsum(legs) / speed))
    if stamps[-1] > 1e9:
        return
    if np.all(np.diff(stamps) > 0.0):
        obstacle = MovingObstacle.scripted(0.1, points, speed=speed)
        assert np.array_equal(obstacle.times, stamps)
        return
    with pytest.raises(ValueError, match=r"path_xy\[2\]") as info:
        MovingObstacle.scripted(0.1, points, speed=speed)
    assert "times" not in str(info.value)


def test_scripted_speed_with_a_leg_below_the_rounding() -> None:
    with pytest.raises(ValueError, match=r"path_xy\[2\] is too close to path_xy\[1\]"):
        MovingObstacle.scripted(0.1, [(0.0, 0.0), (1e6, 0.0), (1e6, 1e-11)], speed=1.0)


@pytest.mark.parametrize("digits", [0, 18, -1, 2**70])
def test_table_digits_past_either_end_names_the_documented_range(digits: int) -> None:
    table = Table("t", ("a",), ((1.5,),))
    with pytest.raises(ValueError, match=r"digits must be in \[1, 17\]"):
        table.render(digits=digits)


@pytest.mark.parametrize("digits", [1, 17])
def test_table_digits_at_either_end_render(digits: int) -> None:
    value = 1.0 / 3.0
    assert Table("t", ("a",), ((value,),)).render(digits=digits).splitlines()[-1] == (
        f"{value:.{digits}g}"
    )
