"""Review 32 (LIVENESS): ``RegulatedPurePursuit`` drives on when its lookahead point meets it.

On an out-and-back path shorter than the lookahead (``(10, 0) -> (-10, 0) ->
(10, 0)`` from ``(10, 0)`` facing it, lookahead 30 m), the rest of the path lies
inside the lookahead circle, so the lookahead point is 30 m further along the
path than the robot's closest point: on the way back, the robot's mirror image
about ``x = 5``. Robot and point met at ``(5, 0)``; the closest-point search kept
the first pass (the robot is at arc 5 and at arc 35), so the lookahead point was
the robot's own position: a diff robot turned a third of a turn toward a point
6e-16 m away, then crept toward it at 1e-14 m/s and less, for ever, ``done``
never true. Whether it escaped depended on rounding (at 0.5 m/s it did, at
10 m/s it did not). The robot is at the lookahead point's arc too: the tracker
now projects it there, as ``FollowTheCarrot`` does (commit 94aa269).
"""

from __future__ import annotations

import math

import pytest

from navkit.control import RegulatedPurePursuit
from navkit.geometry import Pose2D, integrate

DT = 0.05


@pytest.mark.parametrize("drive", ["diff", "omni"])
@pytest.mark.parametrize(
    ("half", "lookahead", "speed"),
    [(10.0, 30.0, 10.0), (100.0, 300.0, 10.0), (100.0, 300.0, 50.0), (1000.0, 3000.0, 100.0)],
)
def test_an_out_and_back_path_inside_the_lookahead_is_followed_to_its_end(
    drive: str, half: float, lookahead: float, speed: float
) -> None:
    tracker = RegulatedPurePursuit(
        drive=drive,  # type: ignore[arg-type]
        max_speed=speed,
        min_lookahead=lookahead,
        max_lookahead=lookahead,
        goal_tolerance=0.05,
    )
    tracker.set_path([[half, 0.0], [-half, 0.0], [half, 0.0]])
    pose = Pose2D(half, 0.0, math.pi)
    for _ in range(5000):
        cmd = tracker.step(pose, DT)
        if tracker.done:
            break
        pose = integrate(pose, cmd, DT)
    assert tracker.done
    assert math.hypot(pose.x - half, pose.y) <= tracker.goal_tolerance
    assert tracker.progress > 1.5 * (2.0 * half)  # on the way back, not at the first pass


def test_the_lookahead_point_jumps_to_the_second_pass_only_when_the_robot_is_on_it() -> None:
    """From the meeting point the tracker looks ahead from the second pass; before it, not."""
    tracker = RegulatedPurePursuit(min_lookahead=30.0, max_lookahead=30.0, max_speed=10.0)
    tracker.set_path([[5.5, 0.0], [-10.0, 0.0], [10.0, 0.0]])
    tracker.step(Pose2D(5.5, 0.0, math.pi), DT)
    assert tracker.progress == 0.0
    assert tracker.target_xy == (4.5, 0.0)  # 30 m on: the way back, 1 m short of the robot
    tracker.set_path([[5.0, 0.0], [-10.0, 0.0], [10.0, 0.0]])
    tracker.step(Pose2D(5.0, 0.0, math.pi), DT)
    assert tracker.progress == 30.0  # the robot's own point on the way back
    assert tracker.target_xy == (10.0, 0.0)  # the goal, 30 m on from there (clamped)
