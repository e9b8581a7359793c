"""Review 32 (HEALTH): ``FollowTheCarrot`` drives on when its carrot lands on the robot.

On a path doubling back through the robot (``(0, 0) -> (0.15, 0) -> (0, 0) ->
(0, 2)`` from the origin, carrot distance 0.3 m), the robot is closest to the
path at arc 0 and at arc 0.3; the search took arc 0, so the carrot (0.3 m on)
was the robot's own position and every command was zero: the tracker stood still
until the caller gave up (2000 steps, ``done`` never true). The robot is at the
carrot's arc as well, so the tracker now projects it there and goes on.
"""

from __future__ import annotations

import math

import pytest

from navkit.control import FollowTheCarrot
from navkit.geometry import Pose2D, integrate

DT = 0.05


@pytest.mark.parametrize("drive", ["omni", "diff"])
@pytest.mark.parametrize("back", [0.15, 0.1, 0.05])
def test_a_path_doubling_back_through_the_robot_is_followed_to_its_end(
    drive: str, back: float
) -> None:
    carrot = 2.0 * back
    tracker = FollowTheCarrot(drive=drive, carrot_distance=carrot)  # type: ignore[arg-type]
    tracker.set_path([[0.0, 0.0], [back, 0.0], [0.0, 0.0], [0.0, 2.0]])
    pose = Pose2D(0.0, 0.0, 0.0)
    first = tracker.step(pose, DT)
    assert math.hypot(first.vx, first.vy) > 0.0 or first.omega != 0.0
    for _ in range(2000):
        pose = integrate(pose, tracker.step(pose, DT), DT)
        if tracker.done:
            break
    assert tracker.done
    assert math.hypot(pose.x, pose.y - 2.0) <= tracker.goal_tolerance


def test_a_carrot_off_the_robot_is_unchanged() -> None:
    """The usual case takes the first closest point, as before: the carrot 0.3 m on."""
    tracker = FollowTheCarrot(drive="omni", carrot_distance=0.3)
    tracker.set_path([[0.0, 0.0], [2.0, 0.0]])
    tracker.step(Pose2D(0.5, 0.1, 0.0), DT)
    assert tracker.target_xy == (0.8, 0.0)
