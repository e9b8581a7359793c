"""Heading PID, velocity-limit and tracker rules that no earlier test pinned down.

Found by mutation testing (session 13, second pass over navkit.control): each
test here fails on a one-line change of the code that every other test let
through. Expected values are worked out by hand from the documented rules.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from navkit.control import PotentialFieldController
from navkit.geometry import Pose2D


def test_pid_derivative_uses_the_wrapped_change_of_the_heading_error() -> None:
    # Only the D term: omega = kd * d(error)/dt, the error being an angle. The
    # robot turns 0.1 rad clockwise while its target heading stays at pi - 0.05,
    # so the error grows by 0.1 rad, from pi - 0.05 to pi + 0.05, which is
    # wrapped to -pi + 0.05. Its derivative must be +0.1 rad/s, not the jump of
    # the wrapped values (about -2 pi).
    ctl = PotentialFieldController(kp=0.0, ki=0.0, kd=1.0, max_omega=100.0)
    target = Pose2D(0.0, 0.0, math.pi - 0.05)
    first = ctl.step(Pose2D(0.0, 0.0, 0.0), target, dt=1.0)
    assert first.omega == 0.0  # no previous error: no derivative yet
    second = ctl.step(Pose2D(0.0, 0.0, -0.1), target, dt=1.0)
    assert second.omega == pytest.approx(0.1, abs=1e-9)


@pytest.mark.parametrize("sign", [1.0, -1.0])
def test_heading_integral_is_held_at_the_anti_windup_bound(sign: float) -> None:
    # Only the I term, a constant heading error of 1 rad (the robot is not moved),
    # dt = 0.1 s: the integral grows 0.1 rad·s per step until it reaches
    # integral_limit = 0.5 rad·s, and stays there.
    ctl = PotentialFieldController(kp=0.0, ki=1.0, kd=0.0, integral_limit=0.5, max_omega=100.0)
    pose = Pose2D(0.0, 0.0, 0.0)
    target = Pose2D(0.0, 0.0, sign * 1.0)
    omegas = [ctl.step(pose, target, dt=0.1).omega for _ in range(30)]
    assert omegas[0] == pytest.approx(sign * 0.1)
    assert omegas[2] == pytest.approx(sign * 0.3)
    assert all(w == pytest.approx(sign * 0.5) for w in omegas[5:])


def test_attraction_is_capped_at_max_speed_before_the_repulsion_is_added() -> None:
    # Step 1 normalises an attraction longer than max_speed to max_speed, step 2
    # adds the repulsion, step 3 clips the sum. A cone attraction of 0.8 m/s
    # toward +x and Khatib's push of an obstacle 0.5 m to the left (toward -y):
    # the sum (0.5, -F) is clipped to 0.5 m/s along its own direction.
    from navkit.planning import ConicAttraction

    k_rep, d0, d, max_speed = 0.05, 0.6, 0.5, 0.5
    push = k_rep * (1.0 / d - 1.0 / d0) / d**2  # Khatib's F at distance d
    ctl = PotentialFieldController(ConicAttraction(np.zeros(2), m=0.8), k_rep=k_rep,
                                   influence_radius=d0, max_speed=max_speed)
    v = ctl.desired_velocity([0.0, 0.0, 0.0], (5.0, 0.0), obstacles=[[0.0, d]])
    expected_angle = math.atan2(-push, max_speed)
    assert math.atan2(v[1], v[0]) == pytest.approx(expected_angle, abs=1e-12)
    assert math.hypot(v[0], v[1]) == pytest.approx(max_speed)


def test_scan_repulsion_is_turned_into_the_world_frame() -> None:
    # A scan is taken in the robot frame: a beam straight ahead (0 rad) of a
    # robot facing +y sees an obstacle at world (0, 0.5), which pushes toward -y.
    # The goal is the robot's own position (a cone's force there is zero).
    from navkit.mapping import LaserScan
    from navkit.planning import ConicAttraction

    k_rep, d0, d = 0.05, 0.6, 0.5
    push = k_rep * (1.0 / d - 1.0 / d0) / d**2
    scan = LaserScan(np.array([d]), angle_min=0.0, angle_increment=0.1, range_min=0.05,
                     range_max=10.0)
    ctl = PotentialFieldController(ConicAttraction(np.zeros(2)), k_rep=k_rep, influence_radius=d0)
    v = ctl.desired_velocity([0.0, 0.0, math.pi / 2], (0.0, 0.0), obstacles=scan)
    assert v[0] == pytest.approx(0.0, abs=1e-12)
    assert v[1] == pytest.approx(-push, rel=1e-9)


def _reference_limit(prev: list[float], want: list[float], max_accel: float, max_decel: float,
                     dt: float) -> list[float]:
    """The docstring's rule by enumeration: the farthest point prev + t·u (t <= n) whose
    change is a deceleration (speed at most the previous one) of length <= max_decel·dt
    or an acceleration of length <= max_accel·dt; candidates are the rule's breakpoints."""
    n = math.dist(prev, want)
    u = [(w - p) / n for p, w in zip(prev, want, strict=True)]
    speed0 = math.hypot(*prev)
    t_slow = -2.0 * sum(p * q for p, q in zip(prev, u, strict=True))

    def ok(t: float) -> bool:
        speed = math.hypot(*[p + t * q for p, q in zip(prev, u, strict=True)])
        return t <= n and t <= (max_decel * dt if speed <= speed0 else max_accel * dt)

    t = max(c for c in (0.0, n, max_accel * dt, max_decel * dt, t_slow) if c >= 0.0 and ok(c))
    return [p + t * q for p, q in zip(prev, u, strict=True)]


@pytest.mark.parametrize(
    ("prev", "want", "max_accel", "max_decel"),
    [
        # Reversing to the same speed: the change keeps the speed, a deceleration,
        # although the acceleration budget (25 m/s) would allow all of it.
        ([1.0, 0.0], [-1.0, 0.0], 100.0, 1.0),
        # Reversing beyond: speed drops along the first t_slow = 2 m/s of the change;
        # max_accel·dt equals t_slow, so no acceleration past it is allowed and the
        # deceleration budget (0.5 m/s) decides.
        ([1.0, 0.0], [-2.0, 0.0], 4.0, 1.0),
        ([0.0, 1.0], [0.0, -3.0], 4.0, 1.0),
        ([1.0, 0.0], [-2.0, 0.0], 8.0, 1.0),
        # Past the equal-speed point (t_slow = 2) the change would be an acceleration
        # longer than max_accel·dt = 1: it stops at t_slow, within max_decel·dt = 3.
        ([1.0, 0.0], [-3.0, 0.0], 2.0, 6.0),
        ([1.0, 0.0], [3.0, 0.0], 1.0, 8.0),
        ([2.0, 0.0], [1.0, 0.0], 8.0, 1.0),
    ],
)
def test_velocity_change_follows_the_acceleration_and_deceleration_rule(
    prev: list[float], want: list[float], max_accel: float, max_decel: float
) -> None:
    from navkit.control import limit_velocity_change

    got = limit_velocity_change(prev, want, max_accel=max_accel, max_decel=max_decel, dt=0.5)
    assert got.tolist() == pytest.approx(_reference_limit(prev, want, max_accel, max_decel, 0.5))


def test_on_off_tracker_rules_at_their_thresholds() -> None:
    from navkit.control import OnOffTracker

    # A waypoint exactly goal_tolerance away is reached ("once within").
    tracker = OnOffTracker(goal_tolerance=0.25)
    tracker.set_path([[0.0, 0.0], [0.5, 0.0], [2.0, 0.0]])
    tracker.step(Pose2D(0.25, 0.0, 0.0), 0.1)
    assert tracker.waypoint == 2

    # A heading error of exactly rotate_angle turns in place ("at least");
    # just under it, the robot drives straight.
    for theta, rotates in ((-0.25, True), (-0.2499, False)):
        tracker = OnOffTracker(rotate_angle=0.25, max_speed=0.2, rotate_omega=0.5)
        tracker.set_path([[0.0, 0.0], [1.0, 0.0]])
        cmd = tracker.step(Pose2D(0.0, 0.0, theta), 0.1)
        assert cmd.vx == (0.0 if rotates else pytest.approx(0.2))
        assert cmd.omega == (pytest.approx(0.5) if rotates else 0.0)

    # The tolerance range is the open (0, π/2).
    with pytest.raises(ValueError, match="rotate_angle"):
        OnOffTracker(rotate_angle=math.pi / 2)


def test_follow_the_carrot_turn_never_overshoots_and_tracks_at_rotate_angle() -> None:
    from navkit.control import FollowTheCarrot

    path = [[0.0, 0.0], [5.0, 0.0]]
    # Carrot at (0.3, 0), heading error 0.05 rad: a high gain asks for 5 rad/s,
    # but no command overshoots within one step, so |omega| <= |error| / dt.
    ftc = FollowTheCarrot(heading_gain=100.0, max_omega=10.0)
    ftc.set_path(path)
    cmd = ftc.step(Pose2D(0.0, 0.0, -0.05), 1.0)
    assert cmd.omega == pytest.approx(0.05)

    # Tracking, the robot goes back to turning in place only when the error
    # exceeds rotate_angle: exactly rotate_angle keeps it driving.
    for theta, drives in ((-0.5, True), (-0.5001, False)):
        ftc = FollowTheCarrot(rotate_angle=0.5, align_tolerance=0.1)
        ftc.set_path(path)
        assert ftc.step(Pose2D(0.0, 0.0, 0.0), 0.1).vx > 0.0  # aligned: tracking
        cmd = ftc.step(Pose2D(0.0, 0.0, theta), 0.1)
        assert (cmd.vx > 0.0) is drives


def test_final_turn_stops_exactly_at_the_yaw_tolerance() -> None:
    # At the last waypoint the tracker turns to goal_yaw "until within
    # yaw_tolerance": an error of exactly yaw_tolerance is done.
    from navkit.control import OnOffTracker

    for theta, done in ((0.25, True), (0.2499, False)):
        tracker = OnOffTracker(yaw_tolerance=0.25, goal_tolerance=2.0)  # every waypoint reached
        tracker.set_path([[0.0, 0.0], [1.0, 0.0]], goal_yaw=0.5)
        tracker.step(Pose2D(1.0, 0.0, theta), 0.1)
        assert tracker.done is done


def test_circle_exit_returns_s_from_when_its_point_is_exactly_radius_away() -> None:
    # "Returns s_from when that point already is radius away": the path starts on
    # the circle, dips inside it and leaves it again later; the first point at
    # least radius away is the start itself.
    from navkit.control._path_following_kernels import circle_exit

    pts = np.array([[1.0, 0.0], [0.0, 0.5], [0.0, 2.0]])
    cum = np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(pts, axis=0).T))])
    assert circle_exit(0.0, 0.0, pts, cum, 0.0, 1.0) == 0.0


def _stall_run(poses: list[tuple[float, float]], goal: tuple[float, float]) -> list[bool]:
    """``stalled`` after each step of a controller (goal_tolerance = stall_radius =
    0.25 m, stall_timeout = 0.5 s, dt = 0.25 s) at the given positions."""
    ctl = PotentialFieldController(goal_tolerance=0.25, stall_radius=0.25, stall_timeout=0.5)
    out = []
    for x, y in poses:
        ctl.step(Pose2D(x, y, 0.0), Pose2D(goal[0], goal[1], 0.0), dt=0.25)
        out.append(ctl.stalled)
    return out


def test_stall_detection_at_its_thresholds() -> None:
    # Standing still far from the goal: stalled once still for stall_timeout
    # (0.5 s: the third step, 0 + 0.25 + 0.25), not before.
    assert _stall_run([(0.0, 0.0)] * 4, (10.0, 0.0)) == [False, False, True, True]
    # Exactly goal_tolerance from the goal counts as at the goal: never stalled.
    assert not any(_stall_run([(0.0, 0.0)] * 6, (0.25, 0.0)))
    # Moving exactly stall_radius back and forth does not leave the radius.
    back_and_forth = [(0.0, 0.0), (0.25, 0.0)] * 3
    assert _stall_run(back_and_forth, (10.0, 0.0))[2:] == [True] * 4
    # Leaving the radius restarts the clock around the new spot.
    moved = [(0.0, 0.0), (0.0, 0.0), (1.0, 0.0), (1.0, 0.0), (1.0, 0.0)]
    assert _stall_run(moved, (10.0, 0.0)) == [False, False, False, False, True]


def test_diff_drive_faces_the_target_heading_below_a_thousandth_of_max_speed() -> None:
    # A cone attraction of 1e-4 m/s (below 1e-3 * max_speed = 5e-4 m/s) toward
    # +x: the field's direction counts as noise, so the robot turns to the
    # target's heading (1 rad, omega = kp * 1 = 0.5) rather than to +x (omega 0).
    from navkit.planning import ConicAttraction

    ctl = PotentialFieldController(ConicAttraction(np.zeros(2), m=1e-4), drive="diff",
                                   kp=0.5, kd=0.0, max_speed=0.5)
    cmd = ctl.step(Pose2D(0.0, 0.0, 0.0), Pose2D(1.0, 0.0, 1.0), dt=0.1)
    assert cmd.omega == pytest.approx(0.5)


@pytest.mark.parametrize("sign", [1.0, -1.0])
def test_turn_rate_is_clipped_to_max_omega_both_ways(sign: float) -> None:
    ctl = PotentialFieldController(kp=3.0, max_omega=0.5)
    cmd = ctl.step(Pose2D(0.0, 0.0, 0.0), Pose2D(0.0, 0.0, sign * 2.0), dt=0.1)
    assert cmd.omega == sign * 0.5


def test_previous_velocity_is_a_copy() -> None:
    ctl = PotentialFieldController()
    ctl.step(Pose2D(0.0, 0.0, 0.0), Pose2D(2.0, 0.0, 0.0), dt=0.1)
    before = ctl.previous_velocity.tolist()
    got = ctl.previous_velocity
    got += 100.0
    assert ctl.previous_velocity.tolist() == before
    # The next step limits the change from the true previous command, not from
    # the caller's edit: the same as a fresh twin's second step.
    twin = PotentialFieldController()
    twin.step(Pose2D(0.0, 0.0, 0.0), Pose2D(2.0, 0.0, 0.0), dt=0.1)
    a = ctl.step(Pose2D(0.0, 0.0, 0.0), Pose2D(2.0, 0.0, 0.0), dt=0.1)
    b = twin.step(Pose2D(0.0, 0.0, 0.0), Pose2D(2.0, 0.0, 0.0), dt=0.1)
    assert a == b
