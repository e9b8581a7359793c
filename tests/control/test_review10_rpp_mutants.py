"""Mutation-testing gaps of RegulatedPurePursuit (review 10).

Two mutants of ``navkit/control/_regulated_pure_pursuit.py`` passed the earlier
tests: an omnidirectional robot whose direction of travel snaps to the
lookahead point (step 2 of the class docstring) but still steered on the arc
of the old, large angle instead of heading straight at the point; and
:meth:`set_path` keeping the previous path's last command, which the class
uses as the measured speed (lookahead distance) and turn rate when no
``velocity`` is given, although ``set_path`` promises to clear the "memory of
previous commands".
"""

from __future__ import annotations

import math
from typing import Literal

import pytest

from navkit.control import RegulatedPurePursuit
from navkit.geometry import Pose2D

DT = 0.05


def _world_direction(cmd_vx: float, cmd_vy: float, theta: float) -> float:
    """Direction (rad) of a body-frame velocity in the world frame of a robot heading theta."""
    c, s = math.cos(theta), math.sin(theta)
    return math.atan2(s * cmd_vx + c * cmd_vy, c * cmd_vx - s * cmd_vy)


@pytest.mark.parametrize("theta", [0.0, 0.4, -2.5])
def test_omni_heads_straight_for_the_lookahead_point_after_snapping_to_it(theta: float) -> None:
    tracker = RegulatedPurePursuit(drive="omni")
    tracker.set_path([[0.0, 0.0], [5.0, 0.0]])
    first = tracker.step(Pose2D(0.0, 0.0, theta), DT)
    travel = _world_direction(first.vx, first.vy, theta)
    assert travel == pytest.approx(0.0, abs=1e-9)  # along the path
    # The robot is now well off the path (moved by hand): its lookahead point lies
    # more than rotate_angle (0.785 rad) away from its direction of travel.
    pose = Pose2D(0.5, 1.0, theta)
    cmd = tracker.step(pose, DT)
    assert tracker.target_xy is not None
    tx, ty = tracker.target_xy
    assert ty == pytest.approx(0.0, abs=1e-12)  # on the path
    bearing = math.atan2(ty - pose.y, tx - pose.x)
    assert abs(bearing - travel) > 0.785
    # Snapped: straight at the point (curvature 0), so at full speed and without turning.
    assert cmd.omega == 0.0
    assert math.hypot(cmd.vx, cmd.vy) == pytest.approx(tracker.max_speed, rel=1e-12)
    assert _world_direction(cmd.vx, cmd.vy, theta) == pytest.approx(bearing, abs=1e-9)


@pytest.mark.parametrize("drive", ["diff", "omni"])
def test_set_path_forgets_the_previous_paths_commands(drive: Literal["diff", "omni"]) -> None:
    used = RegulatedPurePursuit(drive=drive)
    used.set_path([[0.0, 0.0], [10.0, 0.0]])
    pose = Pose2D(0.0, 0.0, 0.0)
    for _ in range(20):  # at full speed: the lookahead grows to 1.5 s * 0.5 m/s = 0.75 m
        cmd = used.step(pose, DT)
        pose = Pose2D(pose.x + cmd.vx * DT, 0.0, 0.0)
    assert cmd.vx == pytest.approx(used.max_speed)
    fresh = RegulatedPurePursuit(drive=drive)
    path = [[0.0, 0.0], [1.0, 0.0], [1.0, 3.0]]
    used.set_path(path)
    fresh.set_path(path)
    start = Pose2D(0.0, 0.2, 0.0)
    a = used.step(start, DT)
    b = fresh.step(start, DT)
    assert used.target_xy == fresh.target_xy
    assert (a.vx, a.vy, a.omega) == (b.vx, b.vy, b.omega)
    # From rest the lookahead is min_lookahead (0.3 m): the point 0.3 m from the robot.
    assert fresh.target_xy is not None
    tx, ty = fresh.target_xy
    assert math.hypot(tx - start.x, ty - start.y) == pytest.approx(0.3, abs=1e-9)
