"""The trackers' closest-point search window on long paths (review 37, TRACK).

Each step searches 2 m of path ahead of the previous closest point (or up to where
the tracker last steered), ending where the path first leads 0.25 m farther from the
robot than its closest point so far: O(log N) a step on a path of N poses
(``benchmarks/test_bench_trackers.py``), loops followed in order, and one glitching
pose moves the progress 2 m at most. At the first step of a path, though, that
window made a robot starting partway along the path (a replan or a route that begins
behind it) catch up 2 m a step, steered back toward the path's start meanwhile: 100 m
along, ``RegulatedPurePursuit`` turned 2.5 rad round and ``FollowTheCarrot`` 3 rad
before the progress reached the robot. The first step now searches the whole path
(still ending where it first leads away from the robot).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from navkit.control import FollowTheCarrot, RegulatedPurePursuit
from navkit.geometry import Pose2D, integrate

TRACKERS = [FollowTheCarrot, RegulatedPurePursuit]


def _straight(x0: float, x1: float, spacing: float = 0.05) -> np.ndarray:
    x = np.linspace(x0, x1, round((x1 - x0) / spacing) + 1)
    return np.column_stack([x, np.zeros_like(x)])


@pytest.mark.parametrize("make", TRACKERS)
@pytest.mark.parametrize("behind", [2.5, 100.0, 5000.0])
def test_a_robot_partway_along_the_path_carries_on_from_there(make: type, behind: float) -> None:
    tracker = make()
    tracker.set_path(_straight(-behind, 20.0))
    pose = Pose2D(0.0, 0.02, 0.0)
    tracker.step(pose, 0.05)
    assert tracker.progress == pytest.approx(behind, abs=1e-9)
    for _ in range(60):
        cmd = tracker.step(pose, 0.05)
        pose = integrate(pose, cmd, 0.05)
        assert abs(pose.theta) < 0.1  # never turned back toward the path's start
    assert pose.x > 0.5


@pytest.mark.parametrize("make", TRACKERS)
def test_the_first_step_stops_where_the_path_leads_away(make: type) -> None:
    # A closed loop through the robot: at its start, not its end.
    a = np.linspace(0.0, 2.0 * math.pi, 73)
    loop = np.column_stack([np.sin(a), 1.0 - np.cos(a)])
    tracker = make()
    tracker.set_path(loop)
    tracker.step(Pose2D(0.0, 0.0, 0.0), 0.05)
    assert tracker.progress < 0.05
    # A path that passes the robot, leads away and passes it again: the first pass.
    twice = np.array([[-3.0, 0.0], [3.0, 0.0], [3.0, 2.0], [0.0, 2.0], [0.0, -3.0]])
    tracker = make()
    tracker.set_path(twice)
    tracker.step(Pose2D(0.0, 0.0, 0.0), 0.05)
    assert tracker.progress == pytest.approx(3.0)


@pytest.mark.parametrize("make", TRACKERS)
def test_a_glitch_after_the_first_step_still_moves_the_progress_two_metres_at_most(
    make: type,
) -> None:
    tracker = make()
    tracker.set_path(_straight(0.0, 100.0))
    tracker.step(Pose2D(0.0, 0.0, 0.0), 0.05)
    before = tracker.progress
    target = tracker.target_xy
    assert target is not None
    tracker.step(Pose2D(50.0, 0.0, 0.0), 0.05)  # one pose 50 m ahead
    assert tracker.progress <= max(before + 2.0, target[0]) + 1e-9


@pytest.mark.parametrize("make", TRACKERS)
def test_a_robot_pushed_onto_the_return_leg_stays_on_the_outbound_one(make: type) -> None:
    # A hairpin: out along y = 0, back along y = 1. A robot pushed across onto the
    # return leg is not at the later pass of the path: its progress stays outbound.
    hairpin = np.array([[0.0, 0.0], [10.0, 0.0], [10.0, 1.0], [0.0, 1.0]])
    tracker = make()
    tracker.set_path(hairpin)
    pose = Pose2D(0.0, 0.0, 0.0)
    for _ in range(60):
        pose = integrate(pose, tracker.step(pose, 0.05), 0.05)
    s = tracker.progress
    assert 0.5 < s < 8.0
    tracker.step(Pose2D(pose.x, 1.0, 0.0), 0.05)
    assert s <= tracker.progress <= s + 2.0


def _loop_run(make: type, k: float) -> tuple[float, np.ndarray]:
    """A 2 m approach, a closed loop of radius 1 m, 2 m on; everything scaled by ``k``."""
    a = np.linspace(0.0, 2.0 * math.pi, 60)
    path = np.vstack([
        np.column_stack([np.linspace(0.0, 2.0, 20), np.zeros(20)]),
        np.column_stack([2.0 + np.sin(a), 1.0 - np.cos(a)])[1:],
        np.column_stack([np.linspace(2.0, 4.0, 20), np.zeros(20)])[1:],
    ]) * k
    if make is FollowTheCarrot:
        tracker = make(carrot_distance=0.3 * k, max_speed=0.18 * k, goal_tolerance=0.05 * k)
    else:
        tracker = make(max_speed=0.5 * k, min_lookahead=0.3 * k, max_lookahead=0.3 * k,
                       slowdown_radius=0.9 * k, min_regulated_speed=0.25 * k,
                       approach_distance=0.6 * k, min_approach_speed=0.05 * k,
                       goal_tolerance=0.25 * k)
    tracker.set_path(path)
    pose = Pose2D(0.0, 0.0, 0.0)
    poses = []
    for _ in range(3000):
        pose = integrate(pose, tracker.step(pose, 0.05), 0.05)
        poses.append(pose.as_array()[:2] / k)
        if tracker.done:
            break
    track = np.array(poses)
    return float(track[:, 1].max()), track


@pytest.mark.parametrize("make", TRACKERS)
def test_scaled_up_the_path_and_options_give_the_same_run(make: type) -> None:
    # The absolute windows (2 m ahead, 0.25 m detour) do not bind on a larger copy.
    high, track = _loop_run(make, 1.0)
    assert high > 1.9  # the loop is driven round
    for k in (8.0, 64.0):
        _, track_k = _loop_run(make, k)
        assert track_k.shape == track.shape
        assert np.allclose(track_k, track, rtol=0.0, atol=1e-9)


def test_scaled_down_a_small_loop_is_cut() -> None:
    # Documented (PathTracker.progress): the 0.25 m detour does not shrink with the
    # options, so a loop of 0.1 m radius is walked through to the later pass.
    high, _ = _loop_run(FollowTheCarrot, 0.1)
    assert high < 0.05
