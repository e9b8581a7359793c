"""``RegulatedPurePursuit`` finishes with a goal tolerance below the float resolution
of UTM coordinates (review 38, TRACK2).

At a UTM northing of 4.6e6 m a world coordinate moves in steps of 9.3e-10 m
(one ulp). A goal tolerance below that (1e-12 m, as a simulation test at the
origin might use) is met only on the goal itself. A differential
``RegulatedPurePursuit`` never landed there: its last runs are arcs, rounded
to the coordinate grid, and the robot turned in place and crept between two
points one ulp beside the goal for ever, ``done`` never set (every start
tried, 20 of 20; ``FollowTheCarrot``, ``OnOffTracker`` and the omnidirectional
tracker land on the goal exactly). A goal one ulp away now counts as reached.
Fails on the code before (checked); at the origin nothing changes.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from navkit.control import RegulatedPurePursuit
from navkit.geometry import Pose2D, integrate

STARTS = [(0.1, -0.2, 2.5), (-0.3, 0.05, -1.0), (0.2, 0.3, 0.0), (0.0, 0.01, 0.2)]


def _run(origin: float, start: tuple[float, float, float]) -> tuple[RegulatedPurePursuit, float]:
    tracker = RegulatedPurePursuit(goal_tolerance=1e-12)
    path = np.array([[0.0, 0.0], [1.0, 0.3]]) + origin
    tracker.set_path(path)
    pose = Pose2D(origin + start[0], origin + start[1], start[2])
    for _ in range(3000):  # 150 s; about 20 s are needed
        if tracker.done:
            break
        pose = integrate(pose, tracker.step(pose, 0.05), 0.05)
    return tracker, math.hypot(pose.x - path[-1, 0], pose.y - path[-1, 1])


@pytest.mark.parametrize("origin", [4.6e6, 5e5, -1e8])
@pytest.mark.parametrize("start", STARTS)
def test_a_tolerance_below_the_coordinates_resolution_is_met_one_ulp_away(
    origin: float, start: tuple[float, float, float]
) -> None:
    tracker, left = _run(origin, start)
    assert tracker.done
    assert left <= math.ulp(abs(origin) + 1.0)  # at most one ulp: no pose is nearer


@pytest.mark.parametrize("start", STARTS)
def test_at_the_origin_the_tolerance_is_met_as_before(start: tuple[float, float, float]) -> None:
    tracker, left = _run(0.0, start)
    assert tracker.done and left <= 1e-12
