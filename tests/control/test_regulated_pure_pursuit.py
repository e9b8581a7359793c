"""RegulatedPurePursuit: Nav2's rules one by one, and closed loops on analytic paths at 20 Hz.

Derived bounds (Nav2 defaults: 0.5 m/s, lookahead 1.5 s × speed in [0.3, 0.9] m):

* straight line: linearised, pure pursuit's lateral error obeys
  e'' + (2/L) e' + (2/L²) e = 0 in the distance s travelled (L = 0.75 m at
  0.5 m/s), so e = e^{−s/L} (A cos(s/L) + B sin(s/L)) with A = e₀ = 0.1 m and
  B = e₀ + L ψ₀ = 0.25 m for a start heading ψ₀ = 0.2 rad away from the path:
  |e| ≤ 0.27 e^{−s/L} < 2 cm from s = 2 m on;
* circle: the arc that leaves a point of a circle tangentially and passes
  through another point of it is the circle itself, so pure pursuit has no
  steady-state error on a circle (up to the polyline's 0.1 mm sagitta);
* right angle: with the robot a before the corner and the lookahead point b
  after it (a² + b² = L²) the chord between them passes within ab/(a + b) ≤
  L/(2√2) of the legs, and the arc lies between the chord and the corner:
  < 0.32 m for L ≤ 0.9 m;
* S-curve of R = 1 m arcs: a chord of length L of an arc sits L²/(8R) from it;
  across the inflection the arcs bend apart, doubling it: < L²/(4R) = 0.2 m.
"""

from __future__ import annotations

import inspect
import math
from collections.abc import Callable
from typing import Any

import numpy as np
import pytest

from navkit.control import RegulatedPurePursuit
from navkit.geometry import Pose2D, Twist2D, integrate
from navkit.mapping import OccupancyGrid

drives = pytest.mark.parametrize("drive", ["diff", "omni"])
STRAIGHT = np.array([[0.0, 0.0], [4.0, 0.0]])


def make(**options: Any) -> RegulatedPurePursuit:
    options.setdefault("goal_tolerance", 0.05)
    options.setdefault("yaw_tolerance", 0.01)
    return RegulatedPurePursuit(**options)


def test_nav2_defaults() -> None:
    """Nav2's parameter_handler.cpp defaults and SimpleGoalChecker's tolerances."""
    d = {n: p.default for n, p in inspect.signature(RegulatedPurePursuit).parameters.items()}
    assert d["max_speed"] == 0.5  # desired_linear_vel
    assert d["lookahead_time"] == 1.5
    assert (d["min_lookahead"], d["max_lookahead"]) == (0.3, 0.9)
    assert d["rotate_to_heading"] is True
    assert d["rotate_angle"] == 0.785  # rotate_to_heading_min_angle
    assert d["rotate_omega"] == 1.8
    assert d["max_angular_accel"] == 3.2
    assert d["curvature_regulation"] is True
    assert d["slowdown_radius"] == 0.9  # regulated_linear_scaling_min_radius
    assert d["min_regulated_speed"] == 0.25
    assert (d["clearance_distance"], d["clearance_gain"]) == (0.6, 1.0)  # cost_scaling_*
    assert (d["approach_distance"], d["min_approach_speed"]) == (0.6, 0.05)
    assert (d["goal_tolerance"], d["yaw_tolerance"]) == (0.25, 0.25)
    assert d["max_omega"] is None and d["clearance"] is None


# ------------------------------------------------------------ closed loops
@drives
def test_straight_line(drive: str, closed_loop: Callable[..., Any],
                       analytic_paths: dict[str, Any]) -> None:
    run = closed_loop(make(drive=drive), analytic_paths["straight"](), (0.0, 0.1, 0.2),
                      goal_yaw=0.0)
    assert run.done and run.goal_error() <= 0.05 and abs(run.poses[-1, 2]) <= 0.01
    assert run.after(x_min=2.0).max() < 0.02
    assert run.cross_track.max() < 0.27


@drives
def test_circle(drive: str, closed_loop: Callable[..., Any],
                analytic_paths: dict[str, Any]) -> None:
    run = closed_loop(make(drive=drive), analytic_paths["circle"](), (0.0, -0.05, 0.1),
                      goal_yaw=0.5)
    assert run.done and run.goal_error() <= 0.05
    assert run.after(fraction=0.35).max() < 0.005
    assert run.poses[:, 1].max() > 1.95


@drives
def test_right_angle(drive: str, closed_loop: Callable[..., Any],
                     analytic_paths: dict[str, Any]) -> None:
    run = closed_loop(make(drive=drive), analytic_paths["right_angle"](), (0.0, 0.05, 0.0),
                      goal_yaw=math.pi / 2)
    assert run.done and run.goal_error() <= 0.05
    assert abs(run.poses[-1, 2] - math.pi / 2) <= 0.01
    assert run.cross_track.max() < 0.9 / (2 * math.sqrt(2))  # measured 0.18


@drives
def test_s_curve(drive: str, closed_loop: Callable[..., Any],
                 analytic_paths: dict[str, Any]) -> None:
    run = closed_loop(make(drive=drive), analytic_paths["s_curve"](), (0.0, 0.05, 0.0),
                      goal_yaw=0.0)
    assert run.done and run.goal_error() <= 0.05
    assert run.cross_track.max() < 0.9**2 / 4  # measured 0.12


def test_nav2_goal_tolerance_by_default(closed_loop: Callable[..., Any]) -> None:
    run = closed_loop(RegulatedPurePursuit(), STRAIGHT, (0.0, 0.0, 0.0), goal_yaw=0.0)
    assert run.done and 0.2 < run.goal_error() <= 0.25


# -------------------------------------------------------------- the rules
def test_lookahead_scales_with_speed() -> None:
    tracker = make()
    tracker.set_path(STRAIGHT)
    pose = Pose2D(0.0, 0.0, 0.0)

    def lookahead() -> float:
        tx, ty = tracker.target_xy
        return math.hypot(tx - pose.x, ty - pose.y)

    cmd = tracker.step(pose, 0.05)
    assert lookahead() == pytest.approx(0.3)  # at rest: min_lookahead
    pose = integrate(pose, cmd, 0.05)
    tracker.step(pose, 0.05)
    assert lookahead() == pytest.approx(0.5 * 1.5)  # previous command 0.5 m/s
    tracker.step(pose, 0.05, velocity=Twist2D(0.1, 0.0, 0.0))
    assert lookahead() == pytest.approx(0.3)  # measured 0.15 m clamped up
    tracker.step(pose, 0.05, velocity=(0.8, 0.0, 0.0))
    assert lookahead() == pytest.approx(0.9)  # 1.2 m clamped down
    tracker.step(pose, 0.05, velocity=(-0.4, 0.0, 0.0))
    assert lookahead() == pytest.approx(0.6)  # |v|


def _steady_speed(radius: float, **options: Any) -> float:
    """Speed on a circle of ``radius``, half way round (before the approach slowdown)."""
    t = np.linspace(0.0, 2 * math.pi, 400)
    path = np.column_stack([radius * np.sin(t), radius * (1.0 - np.cos(t))])
    tracker = make(**options)
    tracker.set_path(path)
    pose = Pose2D(0.0, 0.0, 0.0)
    speeds = []
    while tracker.progress < 0.4 * 2 * math.pi * radius:
        cmd = tracker.step(pose, 0.02)
        speeds.append(cmd.vx)
        pose = integrate(pose, cmd, 0.02)
    return float(np.mean(speeds[-10:]))


def test_curvature_regulation() -> None:
    """Radius r < 0.9 m: speed × r / 0.9, but not below 0.25 m/s."""
    assert _steady_speed(2.0) == pytest.approx(0.5, abs=1e-6)
    assert _steady_speed(0.6) == pytest.approx(0.5 * 0.6 / 0.9, rel=2e-3)
    assert _steady_speed(0.3) == pytest.approx(0.25, abs=1e-9)  # floored
    assert _steady_speed(0.3, min_regulated_speed=0.0) == pytest.approx(0.5 / 3, rel=2e-3)
    assert _steady_speed(0.6, curvature_regulation=False) == pytest.approx(0.5, abs=1e-9)


@pytest.mark.parametrize(
    ("clearance", "speed"),
    [(0.45, 0.5 * 0.45 / 0.6), (0.7, 0.5), (math.inf, 0.5), (0.1, 0.25), (-1.0, 0.25),
     (10**400, 0.5), (-(10**400), 0.25)],  # integers beyond float64 are ±inf
)  # fmt: skip
def test_clearance_regulation(clearance: float, speed: float) -> None:
    """Closer than 0.6 m to an obstacle: speed × gain × c / 0.6, not below 0.25 m/s."""
    calls = []

    def clearance_fn(x: float, y: float) -> float:
        calls.append((x, y))
        return clearance

    tracker = make(clearance=clearance_fn)
    tracker.set_path(STRAIGHT)
    assert tracker.step((1.0, 0.0, 0.0), 0.05).vx == pytest.approx(speed)
    assert calls == [(1.0, 0.0)]  # read at the robot, as Nav2 reads the cost


def test_clearance_gain() -> None:
    tracker = make(clearance=lambda x, y: 0.45, clearance_gain=0.8)
    tracker.set_path(STRAIGHT)
    assert tracker.step((1.0, 0.0, 0.0), 0.05).vx == pytest.approx(0.5 * 0.8 * 0.45 / 0.6)


def test_clearance_from_an_occupancy_grid(closed_loop: Callable[..., Any]) -> None:
    """A wall 10 cells (0.5 m) beside the path: 0.5 × 0.5 / 0.6 m/s along it."""
    occupied = np.zeros((40, 100), dtype=bool)
    occupied[30, :] = True  # cell centres at y = 1.525
    grid = OccupancyGrid.from_occupancy(occupied, resolution=0.05)
    path = np.array([[0.2, 1.0], [4.5, 1.0]])  # the robot's cells are in row 20
    run = closed_loop(make(clearance=grid), path, (0.2, 1.0, 0.0))
    assert run.done
    middle = run.commands[20:60, 0]
    assert np.allclose(middle, 0.5 * 0.5 / 0.6)
    # Off the map is unknown space: no slowdown.
    tracker = make(clearance=grid)
    tracker.set_path([[10.0, 10.0], [12.0, 10.0]])
    assert tracker.step((10.0, 10.0, 0.0), 0.05).vx == pytest.approx(0.5)


def test_numpy_clearance_values() -> None:
    for value in (np.float32(0.45), np.array(0.45), np.int64(1)):
        tracker = make(clearance=lambda x, y, v=value: v)
        tracker.set_path(STRAIGHT)
        expected = min(0.5, 0.5 * float(value) / 0.6)
        assert tracker.step((1.0, 0.0, 0.0), 0.05).vx == pytest.approx(expected, rel=1e-6)


def test_empty_grid_means_no_obstacle() -> None:
    tracker = make(clearance=OccupancyGrid.empty(width=2.0, height=2.0, resolution=0.1))
    tracker.set_path(STRAIGHT)
    assert tracker.step((1.0, 0.0, 0.0), 0.05).vx == pytest.approx(0.5)


@pytest.mark.parametrize(("value", "error"), [(math.nan, ValueError), ("far", TypeError),
                                              ("0.5", TypeError), (True, TypeError),
                                              (None, TypeError), (np.array([0.5]), TypeError)])
def test_bad_clearance_values(value: Any, error: type[Exception]) -> None:
    tracker = make(clearance=lambda x, y: value)
    tracker.set_path(STRAIGHT)
    with pytest.raises(error, match="clearance"):
        tracker.step((0.0, 0.0, 0.0), 0.05)
    assert tracker.progress == 0.0 and tracker.target_xy is None  # nothing changed


def test_approach_slowdown(closed_loop: Callable[..., Any]) -> None:
    """Within 0.6 m of path left: speed × distance / 0.6, not below 0.05 m/s."""
    run = closed_loop(make(), STRAIGHT, (0.0, 0.0, 0.0))
    x = run.poses[:-1, 0]
    v = run.commands[:, 0]
    assert np.all(v[x < 3.4 - 0.01] == 0.5)
    near = (x > 3.41) & (4.0 - x > 0.05 / 0.5 * 0.6)
    assert np.allclose(v[near], 0.5 * (4.0 - x[near]) / 0.6, rtol=1e-3)
    assert np.all(v[4.0 - x < 0.06] >= 0.05 - 1e-12)
    assert np.all(np.diff(v[x > 3.41]) <= 1e-12)


def test_rotate_to_heading() -> None:
    """The path behind: turn in place, accelerating at 3.2 rad/s² up to 1.8 rad/s, and
    decelerating to stop on the path's direction."""
    tracker = make()
    tracker.set_path([[0.0, 0.0], [-2.0, 0.0]])
    pose = Pose2D(0.0, 0.0, 0.0)
    rates = []
    while True:
        cmd = tracker.step(pose, 0.05)
        if tracker.phase != "rotate":
            break
        assert cmd.vx == 0.0
        rates.append(cmd.omega)
        pose = integrate(pose, cmd, 0.05)
    assert rates[0] == pytest.approx(3.2 * 0.05)
    assert np.all(np.abs(np.diff(rates)) <= 3.2 * 0.05 + 1e-12)
    assert max(rates) == pytest.approx(1.8)
    assert abs(pose.theta) > math.pi - 0.785  # within the angle: tracking takes over
    assert cmd.vx > 0.0


def test_no_rotate_to_heading() -> None:
    # A path behind and to the left: pure pursuit curves forward into it at once.
    tracker = make(rotate_to_heading=False)
    tracker.set_path([[0.0, 0.0], [-2.0, 0.5]])
    cmd = tracker.step((0.0, 0.0, 0.0), 0.05)
    assert cmd.vx > 0.0 and cmd.omega > 0.0
    assert tracker.phase == "track"
    # Straight behind, the curvature 2y/d² is zero (the documented trap).
    tracker.set_path([[0.0, 0.0], [-2.0, 0.0]])
    cmd = tracker.step((0.0, 0.0, 0.0), 0.05)
    assert cmd.vx > 0.0 and abs(cmd.omega) < 1e-12


def test_omni_never_rotates_to_the_path() -> None:
    """Holonomic: the path behind is followed by backing straight up, heading unchanged."""
    tracker = make(drive="omni")
    tracker.set_path([[0.0, 0.0], [-2.0, 0.0]])
    cmd = tracker.step((0.0, 0.0, 0.0), 0.05)
    assert cmd.vx == pytest.approx(-0.5) and cmd.vy == pytest.approx(0.0, abs=1e-12)
    assert cmd.omega == 0.0 and tracker.phase == "track"


def test_final_rotation_uses_the_rotate_profile(closed_loop: Callable[..., Any]) -> None:
    run = closed_loop(make(), STRAIGHT, (0.0, 0.0, 0.0), goal_yaw=2.0)
    final = np.array([p == "final" for p in run.phases])
    assert final.any()
    assert np.all(run.commands[final, 0] == 0.0)
    assert np.abs(run.commands[final, 2]).max() == pytest.approx(1.8)
    speeds = np.abs(run.commands[final, 2])
    # Speeding up is limited by max_angular_accel; slowing down follows sqrt(2 a |angle|).
    assert np.all(np.diff(speeds) <= 3.2 * 0.05 + 1e-12)
    assert abs(run.poses[-1, 2] - 2.0) <= 0.01


def test_a_turn_the_wrong_way_slows_at_the_acceleration_limit() -> None:
    """Turning away from the goal heading at 1 rad/s, 0.1 rad short of it.

    The stop cap (sqrt(2 · 3.2 · 0.1) = 0.8 rad/s) applies to turns toward the
    target; applied here as in Nav2 it commanded +0.8 rad/s, a change of
    1.8 rad/s in one 0.05 s step against the limit of 0.16.
    """
    tracker = make()
    tracker.set_path([[0.0, 0.0], [1.0, 0.0]], goal_yaw=0.1)
    cmd = tracker.step((1.0, 0.0, 0.0), 0.05, velocity=Twist2D(0.0, 0.0, -1.0))
    assert tracker.phase == "final"
    assert cmd.omega == pytest.approx(-1.0 + 3.2 * 0.05)
    toward = make()
    toward.set_path([[0.0, 0.0], [1.0, 0.0]], goal_yaw=0.1)
    cmd = toward.step((1.0, 0.0, 0.0), 0.05, velocity=Twist2D(0.0, 0.0, 1.0))
    assert cmd.omega == pytest.approx(0.8)  # toward it: capped to stop on it, as before


def test_max_omega_keeps_the_arc() -> None:
    free, capped = make(), make(max_omega=0.5)
    for t in (free, capped):
        t.set_path([[0.0, 0.0], [0.4, 0.3], [0.4, 2.0]])
    a = free.step((0.0, 0.0, 0.0), 0.05)
    b = capped.step((0.0, 0.0, 0.0), 0.05)
    assert abs(a.omega) > 0.5 and abs(b.omega) == pytest.approx(0.5)
    assert b.omega / b.vx == pytest.approx(a.omega / a.vx)


@pytest.mark.parametrize(
    ("option", "value", "error"),
    [("max_speed", 0.0, ValueError), ("lookahead_time", -1.0, ValueError),
     ("min_lookahead", 0.0, ValueError), ("max_lookahead", 0.2, ValueError),
     ("rotate_to_heading", 1, TypeError), ("curvature_regulation", "yes", TypeError),
     ("rotate_angle", 3.5, ValueError), ("rotate_omega", 0.0, ValueError),
     ("max_angular_accel", math.inf, ValueError), ("slowdown_radius", -0.9, ValueError),
     ("min_regulated_speed", -0.1, ValueError), ("clearance", 0.5, TypeError),
     ("clearance", np.ones((3, 3)), TypeError), ("clearance_distance", 0.0, ValueError),
     ("clearance_gain", math.nan, ValueError), ("approach_distance", 0.0, ValueError),
     ("min_approach_speed", 0.0, ValueError), ("max_omega", 0.0, ValueError),
     ("max_omega", "1", TypeError)],
)
def test_bad_options(option: str, value: Any, error: type[Exception]) -> None:
    with pytest.raises(error, match=option):
        make(**{option: value})


@pytest.mark.parametrize(("velocity", "error"), [((0.1, 0.0), ValueError),
                                                 ((math.nan, 0.0, 0.0), ValueError),
                                                 ("fast", TypeError)])
def test_bad_velocity(velocity: Any, error: type[Exception]) -> None:
    tracker = make()
    tracker.set_path(STRAIGHT)
    with pytest.raises(error, match="velocity"):
        tracker.step((0.0, 0.0, 0.0), 0.05, velocity=velocity)


@pytest.mark.parametrize("goal_yaw", [None, math.pi / 2])
def test_goal_reached_at_exactly_the_tolerance(goal_yaw: float | None) -> None:
    """Nav2's SimpleGoalChecker: reached when dx² + dy² <= xy_goal_tolerance²."""
    tracker = RegulatedPurePursuit()  # goal_tolerance 0.25
    tracker.set_path([[0.0, 0.0], [1.0, 0.0]], goal_yaw=goal_yaw)
    cmd = tracker.step((0.75, 0.0, 0.0), 0.05)  # 0.25 m from the goal, exactly
    assert cmd.vx == 0.0
    assert tracker.phase == ("done" if goal_yaw is None else "final")


@pytest.mark.parametrize("measured", [3.0, -3.0])
def test_max_omega_bounds_in_place_turns_from_a_faster_measured_turn(measured: float) -> None:
    """A measured turn above max_omega: the acceleration limit alone kept 2.84 rad/s."""
    rotate = make(max_omega=1.0)
    rotate.set_path([[0.0, 0.0], [0.0, -2.0]])  # a quarter turn to the right
    cmd = rotate.step((0.0, 0.0, 0.0), 0.05, velocity=Twist2D(0.0, 0.0, measured))
    assert rotate.phase == "rotate"
    assert cmd.omega == math.copysign(1.0, measured)
    final = make(max_omega=1.0)
    final.set_path([[0.0, 0.0], [1.0, 0.0]], goal_yaw=math.pi)
    cmd = final.step((1.0, 0.0, 0.0), 0.05, velocity=Twist2D(0.0, 0.0, measured))
    assert final.phase == "final"
    assert cmd.omega == math.copysign(1.0, measured)
