"""The APF motion controller: limits (hypothesis), closed loops with ``integrate``, inputs."""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from navkit.control import PotentialFieldController
from navkit.geometry import Pose2D, Twist2D, integrate
from navkit.mapping import LaserScan
from navkit.planning import ConicAttraction, KhatibRepulsion
from velocity_change_rule import TOL, check_change, period, rate

obstacle_lists = st.lists(st.tuples(st.floats(-4.0, 4.0), st.floats(-4.0, 4.0)), max_size=5)
poses = st.builds(Pose2D, st.floats(-3.0, 3.0), st.floats(-3.0, 3.0),
                  st.floats(-math.pi, math.pi))


def world_velocity(pose: Pose2D, cmd: Twist2D) -> np.ndarray:
    c, s = math.cos(pose.theta), math.sin(pose.theta)
    return np.array([c * cmd.vx - s * cmd.vy, s * cmd.vx + c * cmd.vy])


@settings(max_examples=40, deadline=None)
@given(st.lists(st.tuples(poses, poses, obstacle_lists, period), min_size=2, max_size=25),
       st.floats(0.2, 2.0), rate, rate, st.floats(0.5, 4.0))
def test_omni_commands_never_exceed_limits(
    steps: list[tuple[Pose2D, Pose2D, list[tuple[float, float]], float]],
    max_speed: float, accel: float, decel: float, max_omega: float,
) -> None:
    ctl = PotentialFieldController(max_speed=max_speed, max_accel=accel, max_decel=decel,
                                   max_omega=max_omega, k_rep=0.5, influence_radius=1.0)
    prev = np.zeros(2)
    for pose, target, obstacles, dt in steps:
        cmd = ctl.step(pose, target, dt=dt, obstacles=np.array(obstacles).reshape(-1, 2))
        v = world_velocity(pose, cmd)
        np.testing.assert_allclose(v, ctl.previous_velocity, atol=1e-12)
        assert np.linalg.norm(v) <= max_speed * (1 + 1e-12)
        assert abs(cmd.omega) <= max_omega
        check_change(prev, v, accel, decel, dt)
        prev = v


@settings(max_examples=40, deadline=None)
@given(st.lists(st.tuples(poses, poses, obstacle_lists, period), min_size=2, max_size=25),
       st.floats(0.2, 2.0), rate, rate)
def test_diff_drive_commands_never_exceed_limits(
    steps: list[tuple[Pose2D, Pose2D, list[tuple[float, float]], float]],
    max_speed: float, accel: float, decel: float,
) -> None:
    ctl = PotentialFieldController(max_speed=max_speed, max_accel=accel, max_decel=decel,
                                   drive="diff", k_rep=0.5, influence_radius=1.0)
    prev = 0.0
    for pose, target, obstacles, dt in steps:
        cmd = ctl.step(pose, target, dt=dt, obstacles=np.array(obstacles).reshape(-1, 2),
                       velocity=Twist2D(prev))
        assert cmd.vy == 0.0
        assert 0.0 <= cmd.vx <= max_speed * (1 + 1e-12)
        limit = accel if cmd.vx > prev else decel
        assert abs(cmd.vx - prev) <= limit * dt * (1 + 1e-9) + TOL
        prev = cmd.vx


@settings(max_examples=40, deadline=None)
@given(st.lists(st.tuples(poses, poses, period), min_size=2, max_size=25),
       st.floats(0.2, 2.0), rate, rate)
def test_diff_drive_limits_hold_from_the_previous_command(
    steps: list[tuple[Pose2D, Pose2D, float]], max_speed: float, accel: float, decel: float,
) -> None:
    """Without a measured velocity the base is the last command's ``vx``, however it turned."""
    ctl = PotentialFieldController(max_speed=max_speed, max_accel=accel, max_decel=decel,
                                   drive="diff")
    prev = 0.0
    for pose, target, dt in steps:
        cmd = ctl.step(pose, target, dt=dt)
        limit = accel if cmd.vx > prev else decel
        assert abs(cmd.vx - prev) <= limit * dt * (1 + 1e-9) + TOL, (prev, cmd.vx)
        prev = cmd.vx


def test_diff_drive_no_velocity_is_the_previous_command() -> None:
    # Driving +x at 0.5 m/s, then a pose turned by 1 rad: projected on the new
    # heading the previous velocity was 0.27 m/s, a drop ten times max_decel * dt.
    ctls = [PotentialFieldController(drive="diff", max_decel=0.2) for _ in range(2)]
    target = Pose2D(10.0, 0.0, 0.0)
    for ctl in ctls:
        for _ in range(20):
            last = ctl.step(Pose2D(0.0, 0.0, 0.0), target, dt=0.1)
    assert last.vx == 0.5
    turned = Pose2D(0.0, 0.0, 1.0)
    implicit = ctls[0].step(turned, target, dt=0.1)
    explicit = ctls[1].step(turned, target, dt=0.1, velocity=last)
    assert implicit.vx == pytest.approx(explicit.vx, abs=1e-15)
    assert implicit.vx == pytest.approx(0.5 - 0.2 * 0.1)


def run(
    ctl: PotentialFieldController,
    start: Pose2D,
    target: Pose2D,
    obstacles: object = None,
    scan_of: object = None,
    dt: float = 0.05,
    steps: int = 600,
) -> tuple[Pose2D, np.ndarray]:
    """Closed loop: command, integrate the exact SE(2) motion, repeat."""
    pose = start
    path = [(pose.x, pose.y)]
    for _ in range(steps):
        sensed = scan_of(pose) if callable(scan_of) else obstacles
        cmd = ctl.step(pose, target, dt=dt, obstacles=sensed)  # type: ignore[arg-type]
        pose = integrate(pose, cmd, dt)
        path.append((pose.x, pose.y))
        if math.hypot(target.x - pose.x, target.y - pose.y) < 0.02 and ctl.stall_time == 0.0:
            break
    return pose, np.array(path)


@pytest.mark.parametrize("mode", ["omni", "diff"])
def test_reaches_goal_in_free_space(mode: str) -> None:
    ctl = PotentialFieldController(drive=mode, max_speed=0.6)  # type: ignore[arg-type]
    target = Pose2D(2.5, -1.5, 1.0)
    pose, path = run(ctl, Pose2D(0.0, 0.0, 2.0), target, steps=800)
    assert math.hypot(pose.x - target.x, pose.y - target.y) < 0.05
    assert not ctl.stalled
    if mode == "omni":
        assert abs(pose.theta - target.theta) < 0.05
    # Speed limit held along the way.
    assert np.max(np.linalg.norm(np.diff(path, axis=0), axis=1)) <= 0.6 * 0.05 * (1 + 1e-9)


def disc_points(cx: float, cy: float, radius: float, n: int = 24) -> np.ndarray:
    a = np.linspace(0.0, 2.0 * math.pi, n, endpoint=False)
    return np.stack((cx + radius * np.cos(a), cy + radius * np.sin(a)), axis=1)


def disc_scan(pose: Pose2D, cx: float, cy: float, radius: float, n: int = 360) -> LaserScan:
    """Exact ranges from a sensor at ``pose`` to a disc (nothing else in range: +inf)."""
    th = -math.pi + 2.0 * math.pi * np.arange(n) / n
    phi = th + pose.theta
    dx, dy = cx - pose.x, cy - pose.y
    b = np.cos(phi) * dx + np.sin(phi) * dy
    disc = b * b - (dx * dx + dy * dy - radius * radius)
    hit = (disc >= 0.0) & (b > 0.0)
    r = np.where(hit, b - np.sqrt(np.where(hit, disc, 0.0)), math.inf)
    return LaserScan(r, angle_min=-math.pi, angle_increment=2.0 * math.pi / n, range_min=0.05,
                     range_max=8.0)


@pytest.mark.parametrize("sensing", ["points", "scan"])
def test_goes_around_a_single_obstacle(sensing: str) -> None:
    centre = (2.0, 0.08)
    radius = 0.25
    ctl = PotentialFieldController(k_rep=0.05, influence_radius=0.6, max_speed=0.5)
    target = Pose2D(4.0, 0.0, 0.0)
    if sensing == "points":
        pose, path = run(ctl, Pose2D(0.0, 0.0, 0.0), target, obstacles=disc_points(*centre, radius))
    else:
        pose, path = run(ctl, Pose2D(0.0, 0.0, 0.0), target,
                         scan_of=lambda p: disc_scan(p, *centre, radius))
    assert math.hypot(pose.x - target.x, pose.y - target.y) < 0.05
    clearance = np.min(np.hypot(path[:, 0] - centre[0], path[:, 1] - centre[1])) - radius
    assert clearance > 0.05
    # It went around (below, the side away from the offset centre), not through.
    assert np.min(path[:, 1]) < -0.3
    assert not ctl.stalled


def test_reports_a_local_minimum() -> None:
    # A wall across the straight line, symmetric about it: attraction and repulsion
    # cancel on the axis and the robot stops in front of the wall.
    wall = np.stack((np.full(21, 2.0), np.linspace(-1.0, 1.0, 21)), axis=1)
    ctl = PotentialFieldController(k_rep=0.05, influence_radius=0.6, stall_timeout=1.5)
    pose, _ = run(ctl, Pose2D(0.0, 0.0, 0.0), Pose2D(4.0, 0.0, 0.0), obstacles=wall, steps=300)
    assert ctl.stalled
    assert ctl.stall_time >= 1.5
    assert 1.0 < pose.x < 2.0 and abs(pose.y) < 1e-9
    ctl.reset()
    assert not ctl.stalled and ctl.stall_time == 0.0
    np.testing.assert_array_equal(ctl.previous_velocity, [0.0, 0.0])


def test_invalid_obstacles_are_skipped_and_measured_velocity_is_the_base() -> None:
    a = PotentialFieldController(k_rep=0.5)
    b = PotentialFieldController(k_rep=0.5)
    pose, target = Pose2D(0.0, 0.0, 0.3), Pose2D(3.0, 1.0, 0.0)
    obstacles = np.array([[0.5, 0.2], [math.nan, 1.0], [math.inf, math.inf]])
    np.testing.assert_allclose(
        a.step(pose, target, dt=0.1, obstacles=obstacles).as_array(),
        b.step(pose, target, dt=0.1, obstacles=obstacles[:1]).as_array(),
    )
    # Measured 1 m/s backwards: the command may only brake by max_decel·dt.
    c = PotentialFieldController(max_speed=2.0, max_decel=2.0)
    cmd = c.step(Pose2D(0.0, 0.0, 0.0), Pose2D(5.0, 0.0, 0.0), dt=0.1, velocity=Twist2D(-1.0))
    assert cmd.vx == pytest.approx(-0.8)
    # ... and a 3-sequence works as the measured velocity, as for the poses.
    d = PotentialFieldController(max_speed=2.0, max_decel=2.0)
    seq = d.step([0.0, 0.0, 0.0], (5.0, 0.0, 0.0), dt=0.1, velocity=[-1.0, 0.0, 0.0])
    assert seq == cmd


def test_desired_velocity_is_attraction_plus_repulsion() -> None:
    attraction = ConicAttraction((0.0, 0.0), m=0.25)
    ctl = PotentialFieldController(attraction, k_rep=0.1, influence_radius=1.0, max_speed=1.0)
    pose = Pose2D(0.0, 0.0, 0.0)
    obstacles = np.array([[0.5, 0.5]])
    want = (ConicAttraction((2.0, 0.0), m=0.25).force([0.0, 0.0])[0]
            + KhatibRepulsion(obstacles, k_rep=0.1, influence_radius=1.0).force([0.0, 0.0])[0])
    np.testing.assert_allclose(
        ctl.desired_velocity(pose, (2.0, 0.0), obstacles=obstacles), want
    )
    np.testing.assert_allclose(
        ctl.desired_velocity([0.0, 0.0, 0.0], np.array([2.0, 0.0]), obstacles=obstacles), want
    )
    # Without obstacles: the attraction alone; the controller's state is untouched.
    np.testing.assert_allclose(ctl.desired_velocity(pose, (2.0, 0.0)), [0.25, 0.0])
    np.testing.assert_array_equal(ctl.previous_velocity, [0.0, 0.0])


def test_bad_arguments() -> None:
    ctl = PotentialFieldController()
    pose = Pose2D(0.0, 0.0)
    with pytest.raises(ValueError, match="dt"):
        ctl.step(pose, pose, dt=0.0)
    with pytest.raises(TypeError, match="pose"):
        ctl.step("pose", pose, dt=0.1)  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="pose"):
        ctl.step((0.0, math.nan, 0.0), pose, dt=0.1)
    with pytest.raises(ValueError, match="target_pose"):
        ctl.step(pose, (1.0, 0.0), dt=0.1)
    with pytest.raises(TypeError, match="target_pose"):
        ctl.step(pose, None, dt=0.1)  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="velocity"):
        ctl.step(pose, pose, dt=0.1, velocity=(0.0, 0.0))
    with pytest.raises(TypeError, match="velocity"):
        ctl.step(pose, pose, dt=0.1, velocity="fast")  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="obstacles"):
        ctl.step(pose, pose, dt=0.1, obstacles=np.zeros((2, 3)))
    with pytest.raises(ValueError, match="drive"):
        PotentialFieldController(drive="tank")  # type: ignore[arg-type]
    with pytest.raises(TypeError, match="attraction"):
        PotentialFieldController(KhatibRepulsion([[0.0, 0.0]]))  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="max_accel"):
        PotentialFieldController(max_accel=0.0)
    with pytest.raises(ValueError, match="kp"):
        PotentialFieldController(kp=-1.0)
    with pytest.raises(ValueError, match="influence_radius"):
        PotentialFieldController(influence_radius=0.0)
    # A failed step leaves the state as it was.
    np.testing.assert_array_equal(ctl.previous_velocity, [0.0, 0.0])
    assert ctl.stall_time == 0.0
    # An empty obstacle array is valid: no repulsion.
    free = ctl.step(pose, Pose2D(1.0, 0.0), dt=0.1, obstacles=np.empty((0, 2)))
    assert free.vx > 0.0


def test_options_are_keyword_only() -> None:
    # step(pose, None, target, None, 0.05) was easy to misorder: after dt (positional
    # as in the trackers' step(pose, dt)) obstacles and velocity are named.
    ctl = PotentialFieldController()
    pose = Pose2D(0.0, 0.0)
    with pytest.raises(TypeError, match="positional"):
        ctl.step(pose, pose, 0.05, None)  # type: ignore[misc]
    with pytest.raises(TypeError, match="dt"):
        ctl.step(pose, pose)  # type: ignore[call-arg]
    with pytest.raises(TypeError, match="positional"):
        ctl.desired_velocity(pose, (1.0, 0.0), None)  # type: ignore[misc]
    with pytest.raises(TypeError, match="positional"):
        PotentialFieldController(None, 0.05)  # type: ignore[misc]
    with pytest.raises(TypeError, match="d0"):
        PotentialFieldController(d0=0.6)  # type: ignore[call-arg]


def test_poses_as_sequences_give_the_same_commands() -> None:
    a = PotentialFieldController()
    b = PotentialFieldController()
    obstacles = [[1.0, 0.2]]
    for k in range(5):
        pose = Pose2D(0.1 * k, 0.0, 0.1)
        got = b.step([pose.x, pose.y, pose.theta], np.array([3.0, 1.0, 0.5]), dt=0.05,
                     obstacles=obstacles)
        assert got == a.step(pose, Pose2D(3.0, 1.0, 0.5), dt=0.05, obstacles=obstacles)


def test_desired_velocity_validates_its_inputs() -> None:
    ctl = PotentialFieldController()
    pose = Pose2D(0.0, 0.0)
    with pytest.raises(TypeError, match="pose"):
        ctl.desired_velocity(None, (1.0, 0.0))  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="pose"):
        ctl.desired_velocity((0.0, 0.0), (1.0, 0.0))
    with pytest.raises(ValueError, match="goal_xy"):
        ctl.desired_velocity(pose, (1.0, 0.0, 0.0))
    with pytest.raises(ValueError, match="goal_xy"):
        ctl.desired_velocity(pose, (math.nan, 0.0))
    with pytest.raises(TypeError, match="goal_xy"):
        ctl.desired_velocity(pose, None)  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="obstacles"):
        ctl.desired_velocity(pose, (1.0, 0.0), obstacles=[[1.0, 2.0, 3.0]])


def test_inputs_are_not_modified() -> None:
    ctl = PotentialFieldController(k_rep=0.5)
    obstacles = np.array([[0.5, 0.2], [math.nan, 1.0]])
    goal = np.array([2.0, 0.0])
    pose = [0.0, 0.0, 0.3]
    ctl.desired_velocity(pose, goal, obstacles=obstacles)
    ctl.step(pose, [2.0, 0.0, 0.0], dt=0.1, obstacles=obstacles, velocity=[0.1, 0.0, 0.0])
    np.testing.assert_array_equal(obstacles, [[0.5, 0.2], [math.nan, 1.0]])
    np.testing.assert_array_equal(goal, [2.0, 0.0])
    assert pose == [0.0, 0.0, 0.3]
    assert obstacles.flags.writeable and goal.flags.writeable
    # previous_velocity is a copy.
    ctl.previous_velocity[0] = 99.0
    assert ctl.previous_velocity[0] != 99.0


def test_controller_is_slotted() -> None:
    ctl = PotentialFieldController()
    assert not hasattr(ctl, "__dict__")
    with pytest.raises(AttributeError):
        ctl.d0 = 0.6  # type: ignore[attr-defined]
    assert ctl.influence_radius == 0.6


def test_copies_step_on_their_own(duplicate: Callable[[Any], Any]) -> None:
    # A shallow copy used to share the PID: its steps and reset moved the
    # original's integrator and last heading error.
    def run(ctl: PotentialFieldController, pose: Pose2D) -> Twist2D:
        return ctl.step(pose, Pose2D(2.0, 1.0, 0.5), dt=0.1)

    original = PotentialFieldController(ki=1.0, kd=0.5)
    twin = PotentialFieldController(ki=1.0, kd=0.5)
    for ctl in (original, twin):
        run(ctl, Pose2D(0.0, 0.0, 0.0))
    copy = duplicate(original)
    assert run(copy, Pose2D(0.1, 0.0, 0.2)) == run(twin, Pose2D(0.1, 0.0, 0.2))
    for _ in range(3):
        run(copy, Pose2D(-1.0, 2.0, -2.5))
    copy.reset()
    reference = PotentialFieldController(ki=1.0, kd=0.5)
    run(reference, Pose2D(0.0, 0.0, 0.0))
    assert run(original, Pose2D(0.1, 0.0, 0.2)) == run(reference, Pose2D(0.1, 0.0, 0.2))


def test_numerically_on_an_obstacle_flees_at_full_speed() -> None:
    ctl = PotentialFieldController(max_speed=0.4, max_accel=100.0)
    cmd = ctl.step(Pose2D(0.0, 1e-200, 0.0), Pose2D(0.0, 0.0, 0.0), dt=0.1,
                   obstacles=[[0.0, 0.0]])
    np.testing.assert_allclose([cmd.vx, cmd.vy], [0.0, 0.4])


OPTIONS = (
    "attraction", "k_rep", "influence_radius", "max_speed", "max_accel", "max_decel",
    "max_omega", "drive", "goal_tolerance", "stall_radius", "stall_timeout",
)


@pytest.mark.parametrize("name", OPTIONS)
@pytest.mark.parametrize("value", [-1.0, math.nan, 0.3, "diff", None])
def test_options_are_read_only(name: str, value: Any) -> None:
    # They used to be plain attributes: ``ctl.max_speed = -1`` or ``= nan`` was
    # accepted unchecked and broke later steps (NaN commands, a reversed clip).
    ctl = PotentialFieldController(ConicAttraction(np.zeros(2)), drive="omni")
    before = getattr(ctl, name)
    with pytest.raises(AttributeError):
        setattr(ctl, name, value)
    assert getattr(ctl, name) is before


def test_options_read_back_as_given() -> None:
    att = ConicAttraction(np.zeros(2))
    ctl = PotentialFieldController(
        att, k_rep=0.2, influence_radius=0.7, max_speed=0.8, max_accel=1.5, max_decel=2.5,
        max_omega=3.0, drive="diff", goal_tolerance=0.03, stall_radius=0.04, stall_timeout=1.5,
    )
    assert ctl.attraction is att
    assert (ctl.k_rep, ctl.influence_radius, ctl.max_speed, ctl.max_accel, ctl.max_decel,
            ctl.max_omega, ctl.drive, ctl.goal_tolerance, ctl.stall_radius,
            ctl.stall_timeout) == (0.2, 0.7, 0.8, 1.5, 2.5, 3.0, "diff", 0.03, 0.04, 1.5)
    # They drive the commands: the speed clip and the stall timeout.
    cmd = ctl.step(Pose2D(0.0, 0.0, 0.0), Pose2D(5.0, 0.0, 0.0), dt=10.0)
    assert cmd.vx == pytest.approx(0.8)
