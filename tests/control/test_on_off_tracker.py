"""OnOffTracker on analytic paths at 20 Hz: the ON-OFF rule and its cross-track bound.

Derived bound. While driving, the heading error to the waypoint stays below
β = 10° (the robot turns back under it whenever it reaches it), so in polar
coordinates around the waypoint dφ/dr ≥ −tan β / r: starting at distance r₀ the
robot's distance from its initial line of sight is at most
max_u r₀ e^{−u} sin(u tan β) = r₀ sin β · e^{−β / tan β} = 0.0645 r₀. A segment
starts with the robot within tol = 0.05 m of its first waypoint, so on a
segment of length ℓ the cross-track error is below tol + (ℓ + tol) · 0.0645
(plus the heading error's growth within one step: 1 mm is allowed).
"""

from __future__ import annotations

import inspect
import math
from collections.abc import Callable
from typing import Any

import numpy as np
import pytest

from navkit.control import OnOffTracker
from navkit.geometry import Pose2D, integrate

BETA = math.radians(10.0)
SPIRAL = math.sin(BETA) * math.exp(-BETA / math.tan(BETA))
TOL = 0.05


def segment_bound(length: float) -> float:
    return TOL + (length + TOL) * SPIRAL + 1e-3


def test_spiral_constant() -> None:
    assert abs(SPIRAL - 0.0645) < 1e-4


def test_paper_defaults() -> None:
    params = inspect.signature(OnOffTracker).parameters
    assert params["rotate_angle"].default == pytest.approx(math.radians(10.0))
    assert params["goal_tolerance"].default == 0.05
    tracker = OnOffTracker()
    assert tracker.rotate_angle == pytest.approx(BETA)
    assert (tracker.max_speed, tracker.rotate_omega, tracker.goal_tolerance) == (0.2, 0.5, 0.05)


def _max_segment(path: np.ndarray) -> float:
    return float(np.max(np.hypot(*np.diff(path, axis=0).T)))


@pytest.mark.parametrize("name", ["straight", "circle", "right_angle", "s_curve"])
def test_cross_track_bound_on_analytic_paths(
    name: str, closed_loop: Callable[..., Any], analytic_paths: dict[str, Any]
) -> None:
    path = analytic_paths[name]()
    run = closed_loop(OnOffTracker(), path, (0.0, 0.03, 0.4), goal_yaw=0.3)
    assert run.done
    assert run.goal_error() <= TOL
    assert abs(run.poses[-1, 2] - 0.3) <= 0.01
    assert run.cross_track.max() <= segment_bound(_max_segment(path))


def test_sparse_straight_line_rides_the_cone(closed_loop: Callable[..., Any]) -> None:
    """One 3 m segment: the robot drives at just under 10° and spirals onto the goal."""
    path = np.array([[0.0, 0.0], [3.0, 0.0]])
    run = closed_loop(OnOffTracker(), path, (0.0, 0.0, 0.6))
    assert run.done and run.goal_error() <= TOL
    assert run.cross_track.max() <= segment_bound(3.0)
    assert run.cross_track.max() > 0.5 * 3.0 * SPIRAL  # the bound is nearly reached


def test_on_off_rule(closed_loop: Callable[..., Any]) -> None:
    """Each command turns in place (|error| >= 10°) or drives straight (|error| < 10°)."""
    tracker = OnOffTracker()
    tracker.set_path([[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.5]])
    pose = Pose2D(0.0, 0.0, -1.0)
    seen = set()
    while not tracker.done:
        cmd = tracker.step(pose, 0.05)
        if tracker.done:
            break
        tx, ty = tracker.target_xy
        err = abs(math.remainder(math.atan2(ty - pose.y, tx - pose.x) - pose.theta, 2 * math.pi))
        if cmd.omega != 0.0:
            assert cmd.vx == 0.0 and err >= BETA
            assert abs(cmd.omega) == pytest.approx(0.5)
            seen.add("rotate")
        else:
            assert err < BETA and cmd.vx == pytest.approx(0.2)
            seen.add("track")
        pose = integrate(pose, cmd, 0.05)
    assert seen == {"rotate", "track"}
    assert tracker.waypoint == 4


def test_waypoints_are_taken_in_order() -> None:
    tracker = OnOffTracker()
    tracker.set_path([[0.0, 0.0], [1.0, 0.0], [2.0, 0.0]])
    tracker.step((0.0, 0.0, 0.0), 0.05)  # within 5 cm of waypoint 0: on to waypoint 1
    assert tracker.waypoint == 1 and tracker.target_xy == (1.0, 0.0)
    tracker.step((1.96, 0.0, 0.0), 0.05)  # near waypoint 2, but waypoint 1 is not reached
    assert tracker.waypoint == 1


def test_omni_drives_straight_at_each_waypoint(closed_loop: Callable[..., Any],
                                              analytic_paths: dict[str, Any]) -> None:
    run = closed_loop(OnOffTracker(drive="omni"), analytic_paths["right_angle"](),
                      (0.0, 0.03, 0.4), goal_yaw=0.3)
    assert run.done and run.goal_error() <= TOL
    track = np.array([p == "track" for p in run.phases])
    assert np.all(run.commands[track, 2] == 0.0)
    assert np.allclose(np.hypot(run.commands[track, 0], run.commands[track, 1])[:-1], 0.2)
    assert np.all(run.poses[:-1][track, 2] == 0.4)  # the heading waits for the final turn
    # Holonomic: no in-place turn on the way, so it stays on the segments.
    assert run.cross_track.max() <= TOL + 1e-9


def test_big_steps_do_not_overshoot() -> None:
    tracker = OnOffTracker(rotate_omega=2.0, max_speed=1.0)
    tracker.set_path([[0.0, 0.0], [0.3, 0.0]])
    cmd = tracker.step((0.0, 0.0, 0.5), 1.0)  # one second at 2 rad/s would pass the target
    assert cmd.omega == pytest.approx(-0.5)
    pose = integrate(Pose2D(0.0, 0.0, 0.5), cmd, 1.0)
    cmd = tracker.step(pose, 1.0)
    assert cmd.vx == pytest.approx(0.3)  # stops on the waypoint


@pytest.mark.parametrize(
    ("option", "value", "error"),
    [("max_speed", 0.0, ValueError), ("max_speed", -0.2, ValueError),
     ("rotate_omega", 0.0, ValueError), ("rotate_omega", math.nan, ValueError),
     ("rotate_angle", 0.0, ValueError), ("rotate_angle", math.pi / 2, ValueError),
     ("max_speed", "slow", TypeError)],
)
def test_bad_options(option: str, value: Any, error: type[Exception]) -> None:
    with pytest.raises(error, match=option):
        OnOffTracker(**{option: value})
