"""What every path tracker shares: the path input, step's validation, done, omni motion,
and velocity limits on random paths (hypothesis)."""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from hypothesis_twins import slow_twin
from navkit.control import FollowTheCarrot, OnOffTracker, RegulatedPurePursuit
from navkit.geometry import Pose2D, Twist2D, integrate
from navkit.planning import Path2D

TRACKERS: dict[str, Callable[..., Any]] = {
    "FollowTheCarrot": FollowTheCarrot,
    "OnOffTracker": OnOffTracker,
    "RegulatedPurePursuit": RegulatedPurePursuit,
}
trackers = pytest.mark.parametrize("make", list(TRACKERS.values()), ids=list(TRACKERS))

L_PATH = np.array([[0.0, 0.0], [1.0, 0.0], [1.0, 1.0]])


# ------------------------------------------------------------------ the path
@trackers
def test_step_before_set_path_raises(make: Callable[..., Any]) -> None:
    tracker = make()
    assert tracker.phase == "idle"
    assert not tracker.done
    assert tracker.path_xy is None
    with pytest.raises(RuntimeError, match="set_path"):
        tracker.step((0.0, 0.0, 0.0), 0.05)


@trackers
def test_world_path2d_is_accepted(make: Callable[..., Any]) -> None:
    tracker = make()
    tracker.set_path(Path2D(L_PATH, "world", cost=2.0, length=2.0, expanded=7))
    assert tracker.path_xy.tolist() == L_PATH.tolist()
    assert isinstance(tracker.step(Pose2D(0.0, 0.0, 0.0), 0.05), Twist2D)


@trackers
def test_grid_path2d_is_rejected(make: Callable[..., Any]) -> None:
    tracker = make()
    grid_path = Path2D(L_PATH, "grid", cost=2.0, length=2.0, expanded=7)
    with pytest.raises(ValueError, match="world frame"):
        tracker.set_path(grid_path)
    assert tracker.path_xy is None


@trackers
@pytest.mark.parametrize(
    ("bad", "error"),
    [
        (np.empty((0, 2)), ValueError),
        ([[0.0, 0.0], [np.nan, 1.0]], ValueError),
        ([[0.0, 0.0], [np.inf, 1.0]], ValueError),
        ([1.0, 2.0, 3.0], ValueError),
        ("path", TypeError),
        (None, TypeError),
        (42, ValueError),
    ],
)
def test_bad_paths(make: Callable[..., Any], bad: Any, error: type[Exception]) -> None:
    tracker = make()
    with pytest.raises(error, match="path"):
        tracker.set_path(bad)


@trackers
def test_the_callers_path_is_copied(make: Callable[..., Any]) -> None:
    pts = L_PATH.copy()
    tracker = make()
    tracker.set_path(pts)
    pts[1, 0] = 99.0
    assert tracker.path_xy[1, 0] == 1.0
    assert not tracker.path_xy.flags.writeable


@trackers
@pytest.mark.parametrize(("heading", "error"), [(math.nan, ValueError), ("north", TypeError)])
def test_bad_goal_yaw(make: Callable[..., Any], heading: Any, error: type[Exception]) -> None:
    with pytest.raises(error, match="goal_yaw"):
        make().set_path(L_PATH, goal_yaw=heading)


@trackers
def test_goal_yaw_is_wrapped(make: Callable[..., Any]) -> None:
    tracker = make()
    tracker.set_path(L_PATH, goal_yaw=3 * math.pi / 2)
    assert tracker.goal_yaw == pytest.approx(-math.pi / 2)


# ---------------------------------------------------------------------- step
@trackers
@pytest.mark.parametrize(
    ("dt", "error"),
    [(0.0, ValueError), (-0.05, ValueError), (math.nan, ValueError), (math.inf, ValueError),
     ("0.05", TypeError), (None, TypeError)],
)
def test_bad_dt(make: Callable[..., Any], dt: Any, error: type[Exception]) -> None:
    tracker = make()
    tracker.set_path(L_PATH)
    with pytest.raises(error, match="dt"):
        tracker.step((0.0, 0.0, 0.0), dt)


@trackers
@pytest.mark.parametrize(
    ("pose", "error"),
    [((0.0, 0.0), ValueError), ((0.0, math.nan, 0.0), ValueError), ("0 0 0", TypeError),
     (None, TypeError), ((2e9, 0.0, 0.0), ValueError)],
)
def test_bad_pose(make: Callable[..., Any], pose: Any, error: type[Exception]) -> None:
    tracker = make()
    tracker.set_path(L_PATH)
    with pytest.raises(error, match="pose"):
        tracker.step(pose, 0.05)


@trackers
def test_a_failed_step_changes_nothing(make: Callable[..., Any]) -> None:
    a, b = make(), make()
    for t in (a, b):
        t.set_path(L_PATH)
        t.step((0.1, 0.02, 0.1), 0.05)
    with pytest.raises(ValueError):
        a.step((0.3, 0.0, 0.0), -1.0)
    assert a.step((0.2, 0.0, 0.0), 0.05) == b.step((0.2, 0.0, 0.0), 0.05)
    assert a.phase == b.phase and a.progress == b.progress



@trackers
@pytest.mark.parametrize("drive", ["diff", "omni"])
def test_copied_and_unpickled_trackers_step_alike_with_a_read_only_path(
    make: Callable[..., Any], drive: str, duplicate: Callable[[Any], Any]
) -> None:
    tracker = make(drive=drive)
    tracker.set_path(L_PATH, goal_yaw=1.0)
    tracker.step((0.1, 0.02, 0.1), 0.05)
    copy = duplicate(tracker)
    # pickle and deepcopy used to give the copy a writable path.
    with pytest.raises(ValueError, match="read-only"):
        copy.path_xy[0, 0] = 5.0
    np.testing.assert_array_equal(copy.path_xy, tracker.path_xy)
    pose = (0.2, 0.0, 0.0)
    assert copy.step(pose, 0.05) == tracker.step(pose, 0.05)
    assert (copy.phase, copy.progress, copy.target_xy) == (
        tracker.phase, tracker.progress, tracker.target_xy
    )
    copy.set_path([[5.0, 5.0]])  # the original keeps its own path
    assert tracker.path_xy.tolist() == L_PATH.tolist()

@trackers
def test_pose_sequence_and_dt_keyword(make: Callable[..., Any]) -> None:
    a, b = make(), make()
    a.set_path(L_PATH)
    b.set_path(L_PATH)
    assert a.step([0.0, 0.05, 0.1], 0.05) == b.step(Pose2D(0.0, 0.05, 0.1), dt=0.05)


@trackers
@pytest.mark.parametrize(
    ("option", "value", "error"),
    [("goal_tolerance", 0.0, ValueError), ("goal_tolerance", -1.0, ValueError),
     ("goal_tolerance", math.nan, ValueError), ("yaw_tolerance", 4.0, ValueError),
     ("yaw_tolerance", "0.1", TypeError), ("drive", "tank", ValueError),
     ("drive", 2, ValueError), ("drive", None, ValueError)],
)
def test_bad_common_options(
    make: Callable[..., Any], option: str, value: Any, error: type[Exception]
) -> None:
    with pytest.raises(error, match=option):
        make(**{option: value})


@trackers
def test_options_are_keyword_only(make: Callable[..., Any]) -> None:
    with pytest.raises(TypeError):
        make(0.3)


# ---------------------------------------------------------------------- done
@trackers
@pytest.mark.parametrize("drive", ["diff", "omni"])
def test_done_latches_and_set_path_rearms(make: Callable[..., Any], drive: str) -> None:
    tracker = make(drive=drive)
    tracker.set_path(L_PATH, goal_yaw=math.pi / 2)
    pose = Pose2D(0.0, 0.02, 0.0)
    for _ in range(2000):
        cmd = tracker.step(pose, 0.05)
        if tracker.done:
            break
        pose = integrate(pose, cmd, 0.05)
    assert tracker.done and tracker.phase == "done"
    assert math.hypot(pose.x - 1.0, pose.y - 1.0) <= tracker.goal_tolerance
    assert abs(pose.theta - math.pi / 2) <= tracker.yaw_tolerance
    # Latched: even a pose far away gets a zero command.
    assert tracker.step((5.0, 5.0, 0.0), 0.05) == Twist2D(0.0, 0.0, 0.0)
    assert tracker.done
    tracker.set_path(L_PATH)
    assert not tracker.done and tracker.progress == 0.0 and tracker.target_xy is None


@trackers
def test_one_point_path_is_a_go_to_goal(make: Callable[..., Any]) -> None:
    tracker = make(goal_tolerance=0.05)
    tracker.set_path([[1.0, 0.5]])
    pose = Pose2D(0.0, 0.0, 0.0)
    for _ in range(2000):
        cmd = tracker.step(pose, 0.05)
        if tracker.done:
            break
        pose = integrate(pose, cmd, 0.05)
    assert tracker.done
    assert math.hypot(pose.x - 1.0, pose.y - 0.5) <= 0.05


@trackers
def test_start_at_the_goal_is_done_at_once(make: Callable[..., Any]) -> None:
    tracker = make()
    tracker.set_path([[0.0, 0.0], [0.01, 0.0]])
    assert tracker.step((0.0, 0.0, 1.0), 0.05) == Twist2D(0.0, 0.0, 0.0)
    assert tracker.done


@trackers
@pytest.mark.parametrize("drive", ["diff", "omni"])
def test_a_short_closed_loop_is_not_done_at_once(make: Callable[..., Any], drive: str) -> None:
    """A 2 m square loop (start = end) and a robot 1 cm beside its start: the closest point
    is the start, not the end just beside it (both lie within the 2 m search window)."""
    tracker = make(drive=drive)
    tracker.set_path([[0.0, 0.0], [0.5, 0.0], [0.5, 0.5], [0.0, 0.5], [0.0, 0.0]])
    cmd = tracker.step((0.0, 0.01, 0.0), 0.05)
    assert not tracker.done
    assert cmd != Twist2D(0.0, 0.0, 0.0)
    assert tracker.progress < 0.1


# ---------------------------------------------------------------------- omni
@trackers
def test_omni_moves_sideways_without_turning(make: Callable[..., Any]) -> None:
    """A path along +y, the robot facing +x: it slides left, its heading never changes."""
    tracker = make(drive="omni", goal_tolerance=0.05)
    tracker.set_path([[0.0, 0.0], [0.0, 1.0], [0.0, 2.0]])
    pose = Pose2D(0.02, 0.0, 0.0)
    lateral = 0.0
    for _ in range(2000):
        cmd = tracker.step(pose, 0.05)
        if tracker.done:
            break
        assert cmd.omega == 0.0
        assert abs(cmd.vx) <= abs(cmd.vy) + 1e-12  # mostly sideways
        lateral += cmd.vy * 0.05
        pose = integrate(pose, cmd, 0.05)
    assert tracker.done
    assert pose.theta == 0.0
    assert pose.y == pytest.approx(2.0, abs=0.05)
    assert lateral > 1.9


@trackers
def test_diff_commands_no_lateral_speed(make: Callable[..., Any]) -> None:
    tracker = make()
    tracker.set_path([[0.0, 0.0], [0.0, 1.0]])
    pose = Pose2D(0.0, 0.0, 0.0)
    for _ in range(200):
        cmd = tracker.step(pose, 0.05)
        assert cmd.vy == 0.0
        pose = integrate(pose, cmd, 0.05)


# ----------------------------------------------------- limits on random paths
coord = st.floats(-3.0, 3.0, allow_nan=False)
random_paths = st.lists(st.tuples(coord, coord), min_size=1, max_size=6)
starts = st.tuples(st.floats(-0.3, 0.3), st.floats(-0.3, 0.3), st.floats(-math.pi, math.pi))


def _limits_hold(tracker: Any, path: list[tuple[float, float]], start: tuple[float, float, float],
                 dt: float, heading: float | None, check: Callable[[Twist2D, str], None]) -> None:
    pts = np.array(path)
    tracker.set_path(pts, goal_yaw=heading)
    pose = Pose2D(pts[0, 0] + start[0], pts[0, 1] + start[1], start[2])
    length = float(np.sum(np.hypot(*np.diff(pts, axis=0).T))) if len(pts) > 1 else 0.0
    # Generous: 4x the time to drive the path and its turns at the slowest tracking speed.
    steps = int((4.0 * (length + 1.0) / 0.05 + 4.0 * len(pts) * math.pi / 0.3) / dt) + 100
    for _ in range(steps):
        cmd = tracker.step(pose, dt)
        assert all(math.isfinite(v) for v in (cmd.vx, cmd.vy, cmd.omega))
        check(cmd, tracker.phase)
        if tracker.done:
            break
        pose = integrate(pose, cmd, dt)
    assert tracker.done, f"not done after {steps} steps, phase {tracker.phase}"


_TOL = 1e-12
hypothesis_settings = settings(
    max_examples=40, deadline=None, suppress_health_check=[HealthCheck.too_slow]
)


@hypothesis_settings
@given(random_paths, starts, st.floats(0.01, 0.2), st.sampled_from(["diff", "omni"]),
       st.one_of(st.none(), st.floats(-math.pi, math.pi)))
def test_follow_the_carrot_limits(path: Any, start: Any, dt: float, drive: str,
                                  heading: float | None) -> None:
    """The delivery robot's limits: 0.18 m/s and 1.5 rad/s, every command."""
    tracker = FollowTheCarrot(drive=drive)

    def check(cmd: Twist2D, phase: str) -> None:
        assert math.hypot(cmd.vx, cmd.vy) <= 0.18 + _TOL
        assert abs(cmd.omega) <= 1.5 + _TOL
        if drive == "diff":
            assert cmd.vy == 0.0 and cmd.vx >= 0.0
            if phase in ("rotate", "final"):
                assert cmd.vx == 0.0
        elif phase == "track":
            assert cmd.omega == 0.0

    _limits_hold(tracker, path, start, dt, heading, check)


# Slow ON-OFF settings take thousands of steps: fewer examples by default.
@settings(hypothesis_settings, max_examples=15)
@given(random_paths, starts, st.floats(0.01, 0.2), st.sampled_from(["diff", "omni"]),
       st.one_of(st.none(), st.floats(-math.pi, math.pi)),
       st.floats(0.05, 1.0), st.floats(0.1, 2.0))
def test_on_off_limits(path: Any, start: Any, dt: float, drive: str, heading: float | None,
                       speed: float, turn_rate: float) -> None:
    """ON-OFF: either turning at most at rotate_omega or driving straight at most at max_speed."""
    tracker = OnOffTracker(drive=drive, max_speed=speed, rotate_omega=turn_rate)

    def check(cmd: Twist2D, phase: str) -> None:
        assert math.hypot(cmd.vx, cmd.vy) <= speed + _TOL
        assert abs(cmd.omega) <= turn_rate + _TOL
        assert cmd.omega == 0.0 or (cmd.vx == 0.0 and cmd.vy == 0.0)  # never both
        if drive == "diff":
            assert cmd.vy == 0.0 and cmd.vx >= 0.0

    _limits_hold(tracker, path, start, dt, heading, check)


test_on_off_limits_thoroughly = slow_twin(test_on_off_limits, max_examples=40)


@hypothesis_settings
@given(random_paths, starts, st.floats(0.01, 0.2), st.sampled_from(["diff", "omni"]),
       st.one_of(st.none(), st.floats(-math.pi, math.pi)),
       st.floats(0.1, 1.5), st.floats(0.5, 3.0))
def test_regulated_pure_pursuit_limits(path: Any, start: Any, dt: float, drive: str,
                                       heading: float | None, max_speed: float,
                                       max_omega: float) -> None:
    tracker = RegulatedPurePursuit(drive=drive, max_speed=max_speed, max_omega=max_omega,
                                   goal_tolerance=0.05, yaw_tolerance=0.05)

    previous = [0.0]

    def check(cmd: Twist2D, phase: str) -> None:
        assert math.hypot(cmd.vx, cmd.vy) <= max_speed + _TOL
        assert abs(cmd.omega) <= max_omega + _TOL
        if phase != "track":
            # In-place turns at 1.8 rad/s, unless still braking (3.2 rad/s²) from faster.
            limit = max(min(max_omega, 1.8), abs(previous[0]) - 3.2 * dt)
            assert abs(cmd.omega) <= limit + _TOL
        previous[0] = cmd.omega
        if drive == "diff":
            assert cmd.vy == 0.0 and cmd.vx >= 0.0
        elif phase == "track":
            assert cmd.omega == 0.0

    _limits_hold(tracker, path, start, dt, heading, check)
