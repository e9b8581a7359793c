"""Review 47 mutation review: the goal test's float resolution is the goal's own.

``at_goal`` counts a robot within the float resolution of the *goal's*
coordinates as there (no pose is nearer the goal without being on it). Taking
the robot's coordinates instead survived every test (mutant g13): the two differ
where the goal and the robot lie on either side of a power of two, whose ulp
halves below it.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import pytest

from navkit.control import (
    FollowTheCarrot,
    OnOffTracker,
    RegulatedPurePursuit,
)
from navkit.control._goal import at_goal, resolution
from navkit.control._potential_field_controller import _resting_distance
from navkit.geometry import Pose2D
from navkit.planning import BlendedAttraction

EDGE = 2.0**22  # 4.2e6 m, a UTM-sized coordinate: its ulp is 2**-30 m, below it 2**-31 m
BELOW = math.nextafter(EDGE, 0.0)


def test_a_goal_just_below_a_power_of_two_is_not_reached_from_one_coarse_ulp_away() -> None:
    # Nearer poses exist around this goal (its ulp is 4.7e-10 m): the robot at
    # (EDGE, EDGE), 6.6e-10 m off, has not reached a goal of tolerance 1e-12 m,
    # although its own coordinates' resolution (9.3e-10 m) is larger.
    assert resolution(BELOW, BELOW) == 2.0**-31
    assert resolution(EDGE, EDGE) == 2.0**-30
    assert not at_goal(EDGE, EDGE, BELOW, BELOW, 1e-12)


def test_a_goal_on_a_power_of_two_is_reached_from_the_nearest_poses_below() -> None:
    # The goal's own ulp is 9.3e-10 m: a robot one fine ulp below it on both axes
    # (6.6e-10 m off) has reached it, although its own resolution is 4.7e-10 m.
    assert at_goal(BELOW, BELOW, EDGE, EDGE, 1e-12)
    assert at_goal(BELOW, EDGE, EDGE, EDGE, 1e-12)
    assert not at_goal(math.nextafter(BELOW, 0.0), BELOW, EDGE, EDGE, 1e-12)


def test_exactly_one_resolution_off_is_reached() -> None:
    # The resolution test includes its boundary: a robot one ulp beside a goal of
    # UTM-sized coordinates, with a tolerance below that ulp, has reached it.
    x = 3.0 * 2.0**21  # 6.3e6 m, ulp 2**-30 m on both sides
    assert x - math.nextafter(x, 0.0) == resolution(x, x)
    assert at_goal(math.nextafter(x, 0.0), x, x, x, 1e-12)
    assert at_goal(x, math.nextafter(x, math.inf), x, x, 1e-12)


def _done(cls: Any, pose: Pose2D, goal: tuple[float, float], tolerance: float) -> bool:
    """The tracker's ``done`` after one step at ``pose`` toward ``goal``."""
    tracker = cls(goal_tolerance=tolerance)
    tracker.set_path([list(goal)])
    tracker.step(pose, 0.05)
    return bool(tracker.done)


@pytest.mark.parametrize("cls", [FollowTheCarrot, OnOffTracker, RegulatedPurePursuit])
def test_every_tracker_takes_the_goals_resolution(cls: Any) -> None:
    # Callers passing the robot's position as the goal's took the robot's
    # resolution (FollowTheCarrot's and RegulatedPurePursuit's arguments swapped:
    # mutants c03, c09). PotentialFieldController's goal_tolerance is at least
    # 1e-6 m, above the resolution of any coordinate it accepts.
    assert _done(cls, Pose2D(BELOW, BELOW, 0.0), (EDGE, EDGE), 1e-12)
    assert not _done(cls, Pose2D(EDGE, EDGE, 0.0), (BELOW, BELOW), 1e-12)


@pytest.mark.parametrize("cls", [FollowTheCarrot, OnOffTracker, RegulatedPurePursuit])
def test_every_tracker_measures_from_the_goals_own_coordinates(cls: Any) -> None:
    # A goal off the diagonal: its x and y swapped (OnOffTracker's waypoint read
    # as (y, x): mutant c04) is 4.2 m away.
    assert _done(cls, Pose2D(1.0, -1.98, 0.0), (1.0, -2.0), 0.05)
    assert not _done(cls, Pose2D(-2.0, 1.0, 0.0), (1.0, -2.0), 0.05)


def test_a_blend_pulling_inward_at_once_rests_on_the_goal() -> None:
    # Inward from the first distance examined (1e-12 m): the rest is the goal
    # itself, 0, not that first distance (mutant p18 returned 1e-12 m).
    field = BlendedAttraction(np.zeros(2), threshold_radius=0.0)
    assert _resting_distance(field) == 0.0
