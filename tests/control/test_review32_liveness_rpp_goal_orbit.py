"""Review 32 (LIVENESS): ``RegulatedPurePursuit`` no longer circles a goal it cannot hit.

Within 3.2 cm of its lookahead point (the goal, at the end) the tracker drives
straight (curvature 0, as Nav2), at most the point's distance per step. Driven
straight that far more than 60° off, a robot ends farther away than it started
(``2 d sin(e / 2) > d``); with ``rotate_angle`` above about 1.1 rad, where it no
longer turns in place first, and a goal tolerance of a few millimetres or less,
it circled the goal for ever 3-6 mm away, ``done`` never true (20000 steps of a
2 m path from four starts; ``rotate_angle=1.2``, ``goal_tolerance=1e-6``). Near
the point it now turns in place to within 45° before it drives (each straight
run then ends at most 0.77 times as far); with ``rotate_angle <= π/4`` (the
default 0.785) nothing changes, those turns happening already.
"""

from __future__ import annotations

import math

import pytest

from navkit.control import RegulatedPurePursuit
from navkit.geometry import Pose2D, integrate

DT = 0.05
STARTS = [(0.0, 0.3, 0.0), (0.0, -0.2, 1.0), (-0.5, 0.5, 2.0), (0.3, 0.0, 3.0)]


def _run(tracker: RegulatedPurePursuit, start: tuple[float, float, float]) -> list[Pose2D]:
    tracker.set_path([[0.0, 0.0], [2.0, 0.0]])
    pose = Pose2D(*start)
    poses = [pose]
    for _ in range(5000):
        cmd = tracker.step(pose, DT)
        if tracker.done:
            break
        pose = integrate(pose, cmd, DT)
        poses.append(pose)
    return poses


@pytest.mark.parametrize("drive", ["diff", "omni"])
@pytest.mark.parametrize("rotate_angle", [1.2, 1.5, 2.0, math.pi])
@pytest.mark.parametrize("start", STARTS)
def test_a_wide_rotate_angle_reaches_a_goal_tolerance_of_a_nanometre(
    drive: str, rotate_angle: float, start: tuple[float, float, float]
) -> None:
    tracker = RegulatedPurePursuit(
        drive=drive,  # type: ignore[arg-type]
        rotate_angle=rotate_angle,
        goal_tolerance=1e-9,
    )
    poses = _run(tracker, start)
    assert tracker.done
    assert math.hypot(poses[-1].x - 2.0, poses[-1].y) <= 1e-9


@pytest.mark.parametrize("start", STARTS)
def test_near_the_goal_a_straight_run_never_ends_farther_from_it(
    start: tuple[float, float, float],
) -> None:
    """Inside 3.2 cm every step moves the robot no farther from the goal."""
    tracker = RegulatedPurePursuit(rotate_angle=2.0, goal_tolerance=1e-9)
    poses = _run(tracker, start)
    d = [math.hypot(p.x - 2.0, p.y) for p in poses]
    near = [k for k in range(len(d) - 1) if d[k] <= 0.03]
    assert near
    assert all(d[k + 1] <= d[k] for k in near)


@pytest.mark.parametrize(
    ("start", "steps", "end"),
    [
        (STARTS[2], 857, Pose2D(1.9999999998605436, 7.712948844482348e-10, 2.9376719063808916)),
        (STARTS[0], 795, Pose2D(2.0000000007783356, 5.318086249640253e-10, 1.817405232584204)),
    ],
)
def test_the_default_rotate_angle_is_unchanged(
    start: tuple[float, float, float], steps: int, end: Pose2D
) -> None:
    """At 0.785 rad (< π/4) the robot already turned near the goal: the same run, bit
    for bit (poses and step counts recorded before this change)."""
    poses = _run(RegulatedPurePursuit(goal_tolerance=1e-9), start)
    assert len(poses) == steps
    assert poses[-1] == end
