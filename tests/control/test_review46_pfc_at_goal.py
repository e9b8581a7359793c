"""Review 46 (PFSTOP): a controller at its target does not spin, and says it is done.

``PotentialFieldController(drive="diff")`` steered by the field's direction up to
the goal itself. With the default ``BlendedAttraction`` the pull near the goal is
not small: ``σ(0) > 0`` leaves a trace of the cone's tip, 7.2 mm/s outward along the
robot's offset however small (out to the field's minimum, 3.75 mm off the goal),
and a ``ConicAttraction`` pulls at full strength up to the goal. A robot 1e-9 m
beside its target, already facing the target's heading, turned round at
``max_omega`` (2 rad/s) to drive those millimetres, then turned back. Within
``goal_tolerance`` the goal is now reached: the heading is the target's (the
trackers' final turn), the controller is :attr:`done`.

The path trackers (follow-the-carrot, ON-OFF, RPP) are checked for the same
defect here too: at ``0 <= distance << goal_tolerance`` they turn to the goal yaw
only, by a rate that does not depend on the distance, and are done once it is met.
"""

from __future__ import annotations

import copy
import math
import pickle
from typing import Any

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from navkit.control import (
    FollowTheCarrot,
    OnOffTracker,
    PotentialFieldController,
    RegulatedPurePursuit,
)
from navkit.geometry import Pose2D, angle_diff, integrate
from navkit.planning import (
    AttractiveField,
    BlendedAttraction,
    ConicAttraction,
    ParaboloidAttraction,
    PiecewiseAttraction,
)

GOAL = (2.0, -1.0)
DT = 0.05

FIELDS: dict[str, Any] = {
    "blended": lambda: BlendedAttraction((0.0, 0.0)),
    "cone": lambda: ConicAttraction((0.0, 0.0), m=0.5),
    "paraboloid": lambda: ParaboloidAttraction((0.0, 0.0)),
    "piecewise": lambda: PiecewiseAttraction((0.0, 0.0)),
}

# Offsets from the goal within the default goal_tolerance (0.05 m): exactly 0, the
# smallest subnormal, tiny ones, and up to just inside the tolerance.
distances = st.one_of(
    st.sampled_from([0.0, 5e-324, 1e-300, 1e-12, 1e-9, 0.049]),
    st.floats(0.0, 0.049, allow_subnormal=True),
)
angles = st.floats(-math.pi, math.pi)
# The trackers' paths start 0.01 m before the goal: within 0.05 m of the robot too.
tracker_distances = st.one_of(
    st.sampled_from([0.0, 5e-324, 1e-300, 1e-12, 1e-9, 0.039]),
    st.floats(0.0, 0.039, allow_subnormal=True),
)


def _near(d: float, bearing: float) -> tuple[float, float]:
    """The point ``d`` from :data:`GOAL` along ``bearing``."""
    return GOAL[0] + d * math.cos(bearing), GOAL[1] + d * math.sin(bearing)


@pytest.mark.parametrize("field", sorted(FIELDS))
@pytest.mark.parametrize("d", [1e-12, 1e-9, 1e-6, 1e-3, 0.04])
@pytest.mark.parametrize("bearing", [0.5, 2.0, -2.5])
def test_a_diff_drive_facing_the_target_heading_does_not_turn_at_its_target(
    field: str, d: float, bearing: float
) -> None:
    # The regression: before the fix the blended field (and the cone) gave
    # omega = ±2 rad/s here, the robot turning toward its offset from the goal.
    theta = 0.3
    ctl = PotentialFieldController(FIELDS[field](), drive="diff")
    x, y = _near(d, bearing)
    cmd = ctl.step(Pose2D(x, y, theta), Pose2D(*GOAL, theta), DT)
    assert cmd.omega == 0.0
    assert ctl.done


@pytest.mark.parametrize("field", sorted(FIELDS))
def test_a_diff_drive_placed_beside_its_target_stays_facing_the_target_heading(
    field: str,
) -> None:
    # Closed loop from 1e-9 m beside the goal: before the fix the robot turned by
    # about a right angle (the blend's push is lateral here) and drove off.
    theta = 0.3
    target = Pose2D(*GOAL, theta)
    ctl = PotentialFieldController(FIELDS[field](), drive="diff")
    x, y = _near(1e-9, theta + math.pi / 2)
    pose = Pose2D(x, y, theta)
    for _ in range(200):
        pose = integrate(pose, ctl.step(pose, target, DT), DT)
        assert abs(angle_diff(pose.theta, theta)) < 1e-9
        assert math.hypot(pose.x - GOAL[0], pose.y - GOAL[1]) <= ctl.goal_tolerance
        assert ctl.done and not ctl.stalled


@pytest.mark.parametrize("tolerance", [0.005, 0.05])
@pytest.mark.parametrize("target_theta", [0.0, math.pi / 2, -2.0])
def test_a_diff_drive_arrives_within_goal_tolerance_facing_the_target_heading(
    tolerance: float, target_theta: float
) -> None:
    # The price of not steering by the field at the goal: a target heading across
    # the approach stops the robot where it turns to it, within goal_tolerance
    # (as the trackers stop), not on the field's minimum 3.75 mm off the goal.
    ctl = PotentialFieldController(drive="diff", goal_tolerance=tolerance)
    target = Pose2D(*GOAL, target_theta)
    pose = Pose2D(0.0, 0.0, 0.0)
    for _ in range(600):
        pose = integrate(pose, ctl.step(pose, target, DT), DT)
    assert ctl.done and not ctl.stalled
    assert math.hypot(pose.x - GOAL[0], pose.y - GOAL[1]) <= tolerance
    assert abs(angle_diff(target_theta, pose.theta)) < 1e-9


@settings(max_examples=150, deadline=None)
@given(
    field=st.sampled_from(sorted(FIELDS)),
    drive=st.sampled_from(["diff", "omni"]),
    d=distances,
    bearing=angles,
    theta=angles,
    target_theta=angles,
)
def test_at_its_target_the_controller_turns_to_the_target_heading_only(
    field: str, drive: str, d: float, bearing: float, theta: float, target_theta: float
) -> None:
    def first_step(dist: float) -> Any:
        ctl = PotentialFieldController(FIELDS[field](), drive=drive)  # type: ignore[arg-type]
        x, y = _near(dist, bearing)
        cmd = ctl.step(Pose2D(x, y, theta), Pose2D(*GOAL, target_theta), DT)
        assert ctl.done and not ctl.stalled
        return cmd, ctl

    cmd, ctl = first_step(d)
    assert all(math.isfinite(v) for v in (cmd.vx, cmd.vy, cmd.omega))
    # The PID toward the target heading, as from any other pose at the goal: the
    # turn does not depend on where within goal_tolerance the robot is (the limit
    # as the distance goes to 0 is the command at 0, exactly).
    at_goal, _ = first_step(0.0)
    assert cmd.omega == at_goal.omega
    error = angle_diff(target_theta, theta)
    assert cmd.omega == pytest.approx(min(max(3.0 * error, -2.0), 2.0), abs=1e-12)
    speed = math.hypot(cmd.vx, cmd.vy)
    # No faster than the field pushes (the blend's 7.2 mm/s at most, near the goal).
    x, y = _near(d, bearing)
    push = ctl.desired_velocity((x, y, theta), GOAL)
    assert speed <= math.hypot(*push) * (1.0 + 1e-12) + 1e-300
    if field in ("paraboloid", "piecewise"):
        # These fields vanish at the goal: so does the command as the robot nears it
        # (the offset as rounded in the pose: 2 + 1e-12 is not 1e-12 off 2 exactly).
        assert speed <= 2.0 * math.hypot(x - GOAL[0], y - GOAL[1]) * (1.0 + 1e-9)


def _done(ctl: PotentialFieldController) -> bool:
    """``ctl.done``, read afresh (mypy would narrow the property between steps)."""
    return ctl.done


def test_done_is_the_last_step_within_goal_tolerance() -> None:
    ctl = PotentialFieldController(drive="diff", goal_tolerance=0.05)
    assert not _done(ctl)  # no step yet
    target = Pose2D(2.0, 0.0, 0.0)
    pose = Pose2D(0.0, 0.0, 0.0)
    seen = []
    for _ in range(200):
        cmd = ctl.step(pose, target, DT)
        inside = math.hypot(pose.x - target.x, pose.y - target.y) <= 0.05
        assert _done(ctl) == inside
        assert not (_done(ctl) and ctl.stalled)
        seen.append(inside)
        pose = integrate(pose, cmd, DT)
    assert not seen[0] and seen[-1]
    # Copies and pickles keep it (it is read from the stall state they hold).
    assert _done(copy.copy(ctl)) and _done(copy.deepcopy(ctl))
    assert _done(pickle.loads(pickle.dumps(ctl)))
    # Not latched: a target that moves away is not done; reset forgets it.
    ctl.step(pose, Pose2D(3.0, 0.0, 0.0), DT)
    assert not _done(ctl)
    ctl.step(pose, target, DT)
    assert _done(ctl)
    ctl.reset()
    assert not _done(ctl)


def test_a_stalled_controller_is_not_done() -> None:
    ctl = PotentialFieldController(stall_timeout=0.5)
    for _ in range(8):  # the robot does not move, 2 m from its goal
        ctl.step((0.0, 0.0, 0.0), (2.0, 0.0, 0.0), 0.1)
    assert ctl.stalled and not ctl.done


def test_the_blend_pushes_off_the_goal_itself() -> None:
    # Why the field's direction means nothing at the goal: the default blend's
    # force does not vanish as the goal nears (σ(0) > 0 leaves the cone's tip),
    # it points away from the goal along the offset, whatever its length.
    field: AttractiveField = BlendedAttraction((0.0, 0.0))
    for d in (1e-12, 1e-9, 1e-6):
        for bearing in (0.0, 1.0, -2.0):
            f = field.force([[d * math.cos(bearing), d * math.sin(bearing)]])[0]
            assert math.hypot(*f) > 7e-3
            assert math.atan2(f[1], f[0]) == pytest.approx(bearing, abs=1e-6)
    assert field.force([[0.0, 0.0]]).tolist() == [[0.0, 0.0]]


# ------------------------------------------------------------------ the trackers


def _tracker(kind: str, drive: str) -> Any:
    if kind == "carrot":
        return FollowTheCarrot(drive=drive)  # type: ignore[arg-type]
    if kind == "onoff":
        return OnOffTracker(drive=drive)  # type: ignore[arg-type]
    return RegulatedPurePursuit(drive=drive, goal_tolerance=0.05)  # type: ignore[arg-type]


@settings(max_examples=150, deadline=None)
@given(
    kind=st.sampled_from(["carrot", "onoff", "rpp"]),
    drive=st.sampled_from(["diff", "omni"]),
    d=tracker_distances,
    bearing=angles,
    theta=angles,
    goal_yaw=st.one_of(st.none(), angles),
)
def test_a_tracker_at_its_goal_turns_to_the_goal_yaw_only(
    kind: str, drive: str, d: float, bearing: float, theta: float, goal_yaw: float | None
) -> None:
    # The path ends at GOAL; its first point is within the ON-OFF tracker's
    # waypoint tolerance too (it takes its waypoints in order).
    path = [[GOAL[0] - 0.01, GOAL[1]], list(GOAL)]

    def first_step(dist: float) -> Any:
        tracker = _tracker(kind, drive)
        tracker.set_path(path, goal_yaw=goal_yaw)
        x, y = _near(dist, bearing)
        return tracker.step(Pose2D(x, y, theta), DT), tracker

    cmd, tracker = first_step(d)
    assert all(math.isfinite(v) for v in (cmd.vx, cmd.vy, cmd.omega))
    assert cmd.vx == 0.0 and cmd.vy == 0.0
    at_goal, _ = first_step(0.0)
    assert cmd.omega == at_goal.omega  # continuous (constant) as the distance goes to 0
    if goal_yaw is None:
        assert cmd.omega == 0.0 and tracker.done
        return
    error = angle_diff(goal_yaw, theta)
    if tracker.done:  # no spin once done
        assert cmd.omega == 0.0 and abs(error) <= tracker.yaw_tolerance + 1e-12
    else:
        assert tracker.phase == "final"
        assert cmd.omega * error > 0.0  # toward the goal yaw
        pose = Pose2D(*_near(d, bearing), theta)
        for _ in range(400):
            pose = integrate(pose, tracker.step(pose, DT), DT)
            if tracker.done:
                break
        assert tracker.done
        assert abs(angle_diff(goal_yaw, pose.theta)) <= tracker.yaw_tolerance + 1e-9
        assert tracker.step(pose, DT) == type(cmd)(0.0, 0.0, 0.0)
