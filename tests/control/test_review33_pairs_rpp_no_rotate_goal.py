"""Review 33 (PAIRS): ``rotate_to_heading=False`` with a tight ``goal_tolerance``.

Within 3.2 cm of its lookahead point (the goal, at the end) the tracker drives
straight (curvature 0, as Nav2), at most the point's distance per step. Review 32
made a robot there turn to within 45° of the point before driving, but only with
``rotate_to_heading=True``: with ``rotate_to_heading=False`` and a goal tolerance
below about 0.1 mm, a robot that reached the goal a hair to its side (the goal
then more than 90° off) drove straight on, away from it, then had the goal right
behind (the arc through it a straight line away) and never came back: 14 to 55 m
from the goal of a 2 m path after 20,000 steps, ``done`` never true, speeding up
as the approach scaling saw the goal recede. The straight-line zone has no arc to
follow instead of turning, so the turn (or, omnidirectional, the snap of the
direction of travel) there now happens whatever ``rotate_to_heading``.

Checked: against ``_regulated_pure_pursuit.py`` of HEAD the first two tests fail
for seven of their ten (drive, start) cases each (the robot metres away after 3000
steps; the distance growing inside 3.2 cm); the third passes (unchanged).
"""

from __future__ import annotations

import math

import pytest
from test_review32_liveness_rpp_goal_orbit import _run

from navkit.control import RegulatedPurePursuit
from navkit.geometry import Pose2D

DT = 0.05
GOAL = (2.0, 0.0)
STARTS = [(0.0, 0.3, 0.0), (0.0, -0.2, 1.0), (-0.5, 0.5, 2.0), (0.3, 0.0, 3.0), (0.0, 0.0, 0.0)]
# The 2 m path to GOAL, run until done (at most 5000 steps), as review 32's orbit test does.


def _to_goal(pose: Pose2D) -> float:
    return math.hypot(pose.x - GOAL[0], pose.y - GOAL[1])


@pytest.mark.parametrize("drive", ["diff", "omni"])
@pytest.mark.parametrize("start", STARTS)
def test_without_rotate_to_heading_a_tight_goal_tolerance_is_reached(
    drive: str, start: tuple[float, float, float]
) -> None:
    tracker = RegulatedPurePursuit(
        drive=drive,  # type: ignore[arg-type]
        rotate_to_heading=False,
        goal_tolerance=1e-6,
    )
    poses = _run(tracker, start)
    assert tracker.done
    assert _to_goal(poses[-1]) <= 1e-6


@pytest.mark.parametrize("drive", ["diff", "omni"])
@pytest.mark.parametrize("start", STARTS)
def test_without_rotate_to_heading_no_step_near_the_goal_leaves_it(
    drive: str, start: tuple[float, float, float]
) -> None:
    """Inside 3.2 cm every step moves the robot no farther from the goal."""
    tracker = RegulatedPurePursuit(
        drive=drive,  # type: ignore[arg-type]
        rotate_to_heading=False,
        goal_tolerance=1e-9,
    )
    d = [_to_goal(p) for p in _run(tracker, start)]
    near = [k for k in range(len(d) - 1) if d[k] <= 0.03]
    assert near
    assert all(d[k + 1] <= d[k] for k in near)


def test_far_from_the_point_rotate_to_heading_false_still_steers_on_the_arc() -> None:
    """The documented trap stays: a path right behind, 2 m away, is driven away from
    (the arc through it is a straight line); only the 3.2 cm zone turns."""
    tracker = RegulatedPurePursuit(rotate_to_heading=False)
    tracker.set_path([[0.0, 0.0], [-2.0, 0.0]])
    cmd = tracker.step((0.0, 0.0, 0.0), DT)
    assert cmd.vx > 0.0 and abs(cmd.omega) < 1e-12
    assert tracker.phase == "track"
