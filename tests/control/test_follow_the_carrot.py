"""FollowTheCarrot on analytic paths at 20 Hz: cross-track bounds, arrival, the paper's limits.

Derived bounds (carrot distance d = 0.3 m, speed v = 0.18 m/s, heading gain k = 3/s):

* straight line: the linearised lateral error obeys e'' + k e' + (k v / d) e = 0,
  poles −0.8 and −2.2 s⁻¹ (overdamped); a 10 cm start offset falls below 2 cm
  within ln(5)/0.8 ≈ 2 s ≈ 0.4 m of travel — checked from x = 1 m on;
* circle of radius R: the carrot is d ahead by arc length, the end of a chord;
  heading straight at it the robot settles inside the circle by R(1 − cos(d/R))
  = 4.47 cm for R = 1 m (proportional steering leaves less);
* S-curve of two R = 1 m quarter circles: the same bound on each arc;
* right angle: the robot heads for a point at most d ahead along the path and
  cuts the corner by less than d.
"""

from __future__ import annotations

import inspect
import math
from collections.abc import Callable
from typing import Any

import numpy as np
import pytest

from navkit.control import FollowTheCarrot
from navkit.geometry import Pose2D

CARROT = 0.3
CIRCLE_BOUND = 1.0 * (1.0 - math.cos(CARROT / 1.0))  # R (1 - cos(d / R)), R = 1 m
drives = pytest.mark.parametrize("drive", ["diff", "omni"])


def test_paper_defaults() -> None:
    params = inspect.signature(FollowTheCarrot).parameters
    defaults = {name: p.default for name, p in params.items()}
    assert defaults["carrot_distance"] == 0.3
    assert defaults["max_speed"] == 0.18
    assert defaults["max_omega"] == 1.5
    assert defaults["goal_tolerance"] == 0.05
    assert defaults["yaw_tolerance"] == 0.01
    tracker = FollowTheCarrot()
    assert (tracker.carrot_distance, tracker.max_speed, tracker.max_omega) == (0.3, 0.18, 1.5)
    assert (tracker.goal_tolerance, tracker.yaw_tolerance, tracker.drive) == (0.05, 0.01, "diff")


@drives
def test_straight_line(drive: str, closed_loop: Callable[..., Any],
                       analytic_paths: dict[str, Any]) -> None:
    run = closed_loop(FollowTheCarrot(drive=drive), analytic_paths["straight"](),
                      (0.0, 0.1, 0.3), goal_yaw=0.0)
    assert run.done
    assert run.goal_error() <= 0.05
    assert abs(run.poses[-1, 2]) <= 0.01
    assert run.after(x_min=1.0).max() < 0.02
    assert run.cross_track.max() <= 0.1 + 1e-9  # never farther than it started


@drives
def test_circle(drive: str, closed_loop: Callable[..., Any],
                analytic_paths: dict[str, Any]) -> None:
    run = closed_loop(FollowTheCarrot(drive=drive), analytic_paths["circle"](),
                      (0.0, -0.05, 0.1), goal_yaw=0.5)
    assert run.done
    assert run.goal_error() <= 0.05
    assert abs(run.poses[-1, 2] - 0.5) <= 0.01
    assert run.after(fraction=0.25).max() <= CIRCLE_BOUND
    # It went all the way round (a closed loop's start is its goal, too).
    assert run.poses[:, 1].max() > 1.9 and run.poses[:, 0].min() < -0.9


@drives
def test_right_angle(drive: str, closed_loop: Callable[..., Any],
                     analytic_paths: dict[str, Any]) -> None:
    run = closed_loop(FollowTheCarrot(drive=drive), analytic_paths["right_angle"](),
                      (0.0, 0.05, 0.0), goal_yaw=math.pi / 2)
    assert run.done
    assert run.goal_error() <= 0.05
    assert abs(run.poses[-1, 2] - math.pi / 2) <= 0.01
    assert run.cross_track.max() < CARROT
    assert run.cross_track.max() < 0.1  # measured 0.075 (diff) and 0.093 (omni)


@drives
def test_s_curve(drive: str, closed_loop: Callable[..., Any],
                 analytic_paths: dict[str, Any]) -> None:
    run = closed_loop(FollowTheCarrot(drive=drive), analytic_paths["s_curve"](),
                      (0.0, 0.05, 0.0), goal_yaw=0.0)
    assert run.done
    assert run.goal_error() <= 0.05
    assert run.after(x_min=0.5).max() <= CIRCLE_BOUND  # settled from its 5 cm start offset


def test_three_phases_and_the_papers_limits(closed_loop: Callable[..., Any]) -> None:
    """Rotate in place to face the path, follow the carrot at 0.18 m/s, rotate to the goal."""
    run = closed_loop(FollowTheCarrot(), np.array([[0.0, 0.0], [2.0, 0.0]]),
                      (0.0, 0.0, 2.0), goal_yaw=-1.0)
    phases = run.phases
    first_track = phases.index("track")
    first_final = phases.index("final")
    assert set(phases[:first_track]) == {"rotate"} and first_track > 5
    assert "rotate" not in phases[first_track:]
    assert set(phases[first_final:]) == {"final"}
    cmds = run.commands
    rotating = np.array([p != "track" for p in phases])
    assert np.all(cmds[rotating, 0] == 0.0)  # in place
    assert cmds[:, 0].max() == 0.18  # full speed on the straight
    assert np.abs(cmds[:, 2]).max() == 1.5  # full turn rate at the start
    assert np.all(np.abs(cmds[:, 2]) <= 1.5)
    assert np.all(cmds[:, 0] <= 0.18)
    assert run.done and abs(run.poses[-1, 2] + 1.0) <= 0.01


def test_sharp_turn_stops_and_rotates(closed_loop: Callable[..., Any]) -> None:
    """A 10 cm wide hairpin puts the carrot behind: the robot rotates in place again."""
    path = np.array([[0.0, 0.0], [1.0, 0.0], [1.0, 0.1], [0.0, 0.1]])
    run = closed_loop(FollowTheCarrot(), path, (0.0, 0.0, 0.0))
    first_track = run.phases.index("track")
    assert "rotate" in run.phases[first_track:]
    assert run.done and run.goal_error() <= 0.05


def test_carrot_is_ahead_along_the_path() -> None:
    tracker = FollowTheCarrot()
    tracker.set_path([[0.0, 0.0], [0.2, 0.0], [0.2, 1.0]])
    tracker.step(Pose2D(0.1, 0.0, 0.0), 0.05)
    assert tracker.progress == pytest.approx(0.1)
    assert tracker.target_xy == pytest.approx((0.2, 0.2))  # 0.3 m on by arc length


def test_carrot_farther_than_the_search_window() -> None:
    """A carrot more than 2 m ahead: the closest point is searched up to the last carrot."""
    tracker = FollowTheCarrot(carrot_distance=5.0, max_speed=10.0)
    tracker.set_path([[0.0, 0.0], [20.0, 0.0]])
    assert tracker.step(Pose2D(0.0, 0.0, 0.0), 1.0).vx == 5.0  # drives onto the carrot
    tracker.step(Pose2D(5.0, 0.0, 0.0), 1.0)
    assert tracker.progress == 5.0
    assert tracker.target_xy == pytest.approx((10.0, 0.0))


def test_reaching_a_far_carrot_on_a_hairpin_does_not_stall(
    closed_loop: Callable[..., Any],
) -> None:
    # The carrot, 3 m on, lies on the way back; once the robot stood on it, its
    # closest point within 2 m of path was the same point as before, and so was
    # the carrot: a zero command for ever.
    path = np.array([[0.0, 0.0], [2.0, 0.0], [0.0, 0.4]])
    run = closed_loop(FollowTheCarrot(carrot_distance=3.0), path, (0.0, 0.0, 0.0), t_max=60.0)
    assert run.done and run.goal_error() <= 0.05


@drives
def test_a_short_closed_loop_is_driven_round(closed_loop: Callable[..., Any], drive: str) -> None:
    # A 2 m square loop, the robot 1 cm beside its start: the end of the loop, in the
    # 2 m search window too, was nearer than the start, so the robot was done at once.
    path = np.array([[0.0, 0.0], [0.5, 0.0], [0.5, 0.5], [0.0, 0.5], [0.0, 0.0]])
    run = closed_loop(FollowTheCarrot(drive=drive), path, (0.0, 0.01, 0.0))
    assert run.done and run.goal_error() <= 0.05
    travelled = np.hypot(*np.diff(run.poses[:, :2], axis=0).T).sum()
    assert travelled > 1.3  # round the loop, cutting its last corner by at most the carrot
    assert run.poses[:, 0].max() > 0.4 and run.poses[:, 1].max() > 0.4
    assert run.cross_track.max() < CARROT


def test_no_goal_yaw_ends_at_the_position(closed_loop: Callable[..., Any]) -> None:
    run = closed_loop(FollowTheCarrot(), np.array([[0.0, 0.0], [1.0, 0.0]]), (0.0, 0.0, 0.0))
    assert run.done and "final" not in run.phases


def test_slower_control_rate_still_converges(closed_loop: Callable[..., Any],
                                             analytic_paths: dict[str, Any]) -> None:
    run = closed_loop(FollowTheCarrot(), analytic_paths["right_angle"](), (0.0, 0.05, 0.0),
                      dt=0.2, goal_yaw=math.pi / 2)
    assert run.done and run.goal_error() <= 0.05
    assert run.cross_track.max() < CARROT


@pytest.mark.parametrize(
    ("option", "value", "error"),
    [("carrot_distance", 0.0, ValueError), ("carrot_distance", -0.3, ValueError),
     ("max_speed", 0.0, ValueError), ("max_speed", 1e3, ValueError),
     ("max_omega", math.inf, ValueError), ("heading_gain", -1.0, ValueError),
     ("rotate_angle", 4.0, ValueError), ("align_tolerance", 1.0, ValueError),
     ("max_speed", "fast", TypeError), ("carrot_distance", True, TypeError)],
)
def test_bad_options(option: str, value: Any, error: type[Exception]) -> None:
    with pytest.raises(error, match=option):
        FollowTheCarrot(**{option: value})
