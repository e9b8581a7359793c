"""The controllers command the same wherever the problem is translated (review 37, TRACK).

``FollowTheCarrot`` built its carrot as a world point (``point_at(s)``) and only then
subtracted the robot's position; ``RegulatedPurePursuit`` did the same with its
lookahead point and closest point, and its closest-point search and lookahead circle
measured distances from interpolated world points. At UTM coordinates (x ~ 5e5 m,
y ~ 4.6e6 m) a world point carries 1e-9 m of rounding, which a 0.3 m carrot turns into
a few 1e-9 rad of heading error: commands differed from the same problem at the origin
by up to 2.5e-8 (rad/s, m/s). The path kernels now take every point as an offset from
the robot, subtracted first (``(a - p) + t (b - a)``).

The problems here are exactly translatable: every coordinate is a multiple of 2**-16 m
and so is the translation, so ``P + T`` is exact and a difference in the commands is
the controllers' own rounding. ``OnOffTracker`` and ``PotentialFieldController``
(which subtract first already) are checked too.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from navkit.control import (
    FollowTheCarrot,
    OnOffTracker,
    PotentialFieldController,
    RegulatedPurePursuit,
)
from navkit.geometry import Pose2D, Twist2D, integrate

_GRID = 2.0**-16
_UTM = (500_000.0 + 12345 * _GRID, 4_600_000.0 - 6789 * _GRID)  # multiples of 2**-16
_TOL = 1e-12


def _q(value: float) -> float:
    """``value`` on the 2**-16 m grid: translated by ``_UTM`` without rounding."""
    return round(value / _GRID) * _GRID


coordinate = st.integers(-8 * 2**16, 8 * 2**16).map(lambda k: k * _GRID)
paths = st.lists(st.tuples(coordinate, coordinate), min_size=2, max_size=7)


def _shifted(pose: Pose2D, off: tuple[float, float]) -> Pose2D:
    x, y = pose.x + off[0], pose.y + off[1]
    assert x - off[0] == pose.x and y - off[1] == pose.y  # the translation is exact
    return Pose2D(x, y, pose.theta)


def _close(a: Twist2D, b: Twist2D) -> bool:
    return all(abs(u - v) <= _TOL for u, v in zip(a.as_array(), b.as_array(), strict=True))


def _run_tracker(make: type, path: np.ndarray, start: Pose2D, drive: str) -> None:
    here = make(drive=drive)
    there = make(drive=drive)
    here.set_path(path, goal_yaw=0.5)
    there.set_path(path + np.array(_UTM), goal_yaw=0.5)
    pose = start
    for _ in range(40):
        a = here.step(pose, 0.05)
        b = there.step(_shifted(pose, _UTM), 0.05)
        assert _close(a, b), (make.__name__, drive, pose, a, b)
        assert here.phase == there.phase
        assert abs(here.progress - there.progress) <= _TOL
        if here.done:
            break
        moved = integrate(pose, a, 0.05)
        # Back on the grid, so that the next pose translates exactly too.
        pose = Pose2D(_q(moved.x), _q(moved.y), moved.theta)


@pytest.mark.parametrize("make", [FollowTheCarrot, RegulatedPurePursuit, OnOffTracker])
@pytest.mark.parametrize("drive", ["diff", "omni"])
@settings(max_examples=40, deadline=None)
@given(
    raw=paths,
    dx=st.integers(-2**15, 2**15),
    dy=st.integers(-2**15, 2**15),
    theta=st.floats(-3.0, 3.0),
)
def test_trackers_command_the_same_at_utm_as_at_the_origin(
    make: type, drive: str, raw: list[tuple[float, float]], dx: int, dy: int, theta: float
) -> None:
    path = np.array(raw)
    start = Pose2D(path[0, 0] + dx * _GRID, path[0, 1] + dy * _GRID, theta)
    _run_tracker(make, path, start, drive)


@pytest.mark.parametrize("make", [FollowTheCarrot, RegulatedPurePursuit])
def test_a_utm_route_gives_the_origin_commands(make: type) -> None:
    # A plain example of the hypothesis test above, which failed before (by 5e-9):
    # a bend, the robot beside it, three steps.
    path = np.array([[0.0, 0.0], [1.25, 0.5], [2.0, 2.75]])
    start = Pose2D(0.125, 0.1875, 0.25)
    _run_tracker(make, path, start, "diff")


@settings(max_examples=60, deadline=None)
@given(
    goal=st.tuples(coordinate, coordinate),
    obstacle=st.tuples(coordinate, coordinate),
    theta=st.floats(-3.0, 3.0),
    drive=st.sampled_from(["diff", "omni"]),
)
def test_the_potential_field_controller_commands_the_same_at_utm(
    goal: tuple[float, float], obstacle: tuple[float, float], theta: float, drive: str
) -> None:
    here = PotentialFieldController(drive=drive, influence_radius=2.0)
    there = PotentialFieldController(drive=drive, influence_radius=2.0)
    obstacles = np.array([obstacle])
    pose = Pose2D(0.0, 0.0, theta)
    for _ in range(20):
        a = here.step(pose, (goal[0], goal[1], 0.25), 0.05, obstacles=obstacles)
        b = there.step(
            _shifted(pose, _UTM),
            (goal[0] + _UTM[0], goal[1] + _UTM[1], 0.25),
            0.05,
            obstacles=obstacles + np.array(_UTM),
        )
        assert _close(a, b), (pose, a, b)
        assert here.stalled == there.stalled
        moved = integrate(pose, a, 0.05)
        pose = Pose2D(_q(moved.x), _q(moved.y), moved.theta)
    assert math.isfinite(pose.x)
