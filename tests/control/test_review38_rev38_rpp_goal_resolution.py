"""``RegulatedPurePursuit``'s goal one ulp away: the ulp of the finer coordinate
(review 38, REV38).

Review 38 (TRACK2) let a goal tolerance below the float resolution of the
goal's coordinates be met one ulp away, taking the ulp of the larger
coordinate. Where the other coordinate is finer (a goal on a UTM northing
with a small easting, or a UTM easting and northing of different sizes),
poses much nearer than that ulp exist, and the robot reached them: with
``goal_tolerance=1e-12`` at (4.6e6, 0.5) every run of 12 finished within
3e-13 to 1e-12 m before that change, and after it stopped 5e-10 to 8e-10 m
away (700 times the tolerance); at (4.6e6, 5e5) with 1e-10 m, 6e-10 to
8e-10 m away where it had finished on the goal or one ulp (5.8e-11 m) beside
it. The resolution is now the ulp of the finer coordinate: no pose other than
the goal is nearer (as the docstring says), a tolerance the robot can meet is
met, and TRACK2's runs (both coordinates of one size) finish as they did.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from navkit.control import RegulatedPurePursuit
from navkit.geometry import Pose2D, integrate

STARTS = [(1.5, -0.8, 2.5), (-1.2, 0.9, -1.0), (0.7, 1.6, 0.0)]


def _left(goal: tuple[float, float], tolerance: float, start: tuple[float, float, float]) -> float:
    """How far from ``goal`` a run from ``start`` (offsets from the goal) finished."""
    tracker = RegulatedPurePursuit(goal_tolerance=tolerance)
    gx, gy = goal
    tracker.set_path(np.array([[gx + start[0], gy + start[1]], [gx, gy]]))
    pose = Pose2D(gx + start[0], gy + start[1], start[2])
    for _ in range(3000):  # 150 s; about 50 s are needed
        if tracker.done:
            break
        pose = integrate(pose, tracker.step(pose, 0.05), 0.05)
    assert tracker.done
    return math.hypot(pose.x - gx, pose.y - gy)


@pytest.mark.parametrize(
    ("goal", "tolerance"),
    [
        ((4.6e6, 0.5), 1e-12),  # a northing with a small easting
        ((0.25, -4.6e6), 1e-12),
        ((4.6e6 + 0.4, 5e5 - 0.3), 1e-10),  # one ulp of the easting: 5.8e-11 m
    ],
)
@pytest.mark.parametrize("start", STARTS)
def test_a_tolerance_the_robot_can_meet_is_met(
    goal: tuple[float, float], tolerance: float, start: tuple[float, float, float]
) -> None:
    assert tolerance < math.ulp(max(abs(goal[0]), abs(goal[1])))  # below the larger's ulp
    assert _left(goal, tolerance, start) <= tolerance


@pytest.mark.parametrize("start", STARTS)
def test_below_the_finer_coordinates_ulp_one_ulp_away_is_reached(
    start: tuple[float, float, float],
) -> None:
    goal = (4.6e6 + 0.4, 5e5 - 0.3)
    assert _left(goal, 1e-12, start) <= math.ulp(5e5)
