"""The angle convention at its boundary in the controllers.

Heading errors are taken across the cut (a robot at heading 3.1 steering to π
turns left by 0.04 rad, one at -3.1 turns right by as much), a goal yaw or a
pose heading of π and of -π is one heading, and a robot just either side of
±π gets mirrored commands on a path symmetric about its heading.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

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
from navkit.geometry import Pose2D, Twist2D

PI = math.pi

TRACKERS: dict[str, Callable[[], Any]] = {
    "carrot": FollowTheCarrot,
    "on_off": OnOffTracker,
    "rpp": RegulatedPurePursuit,
}
# A path straight along -x from the origin: its direction is π (atan2(0, -1)).
WEST = [[0.0, 0.0], [-5.0, 0.0]]


def _mirrored(a: Twist2D, b: Twist2D) -> None:
    assert b.vx == pytest.approx(a.vx, abs=1e-12)
    assert b.vy == pytest.approx(-a.vy, abs=1e-12)
    assert b.omega == pytest.approx(-a.omega, abs=1e-12)


@pytest.mark.parametrize("name", sorted(TRACKERS))
@pytest.mark.parametrize("offset", [0.02, 0.3, 1.0, 2.5])
def test_trackers_mirror_across_the_cut(name: str, offset: float) -> None:
    # Headings π - offset and -π + offset mirror each other about the path (the x
    # axis): mirrored commands, never a turn the long way round.
    left = TRACKERS[name]()
    right = TRACKERS[name]()
    left.set_path(WEST)
    right.set_path(WEST)
    a = left.step(Pose2D(0.0, 0.0, PI - offset), 0.05)
    b = right.step(Pose2D(0.0, 0.0, -PI + offset), 0.05)
    _mirrored(a, b)
    # Turned clockwise of π (heading π - offset): the path lies counter-clockwise.
    assert a.omega >= 0.0
    assert a.omega > 0.0 or name == "on_off"  # on/off drives straight within its tolerance


@pytest.mark.parametrize("name", sorted(TRACKERS))
@pytest.mark.parametrize("heading", [PI, -PI, float(np.nextafter(-PI, -4.0)), 3.0 * PI])
def test_trackers_treat_every_spelling_of_pi_alike(name: str, heading: float) -> None:
    reference = TRACKERS[name]()
    reference.set_path(WEST)
    tracker = TRACKERS[name]()
    tracker.set_path(WEST)
    expected = reference.step(Pose2D(0.0, 0.0, PI), 0.05)
    got = tracker.step((0.0, 0.0, heading), 0.05)
    # nextafter(-π, -inf) wraps to the float below π: the same command to rounding.
    assert got.vx == pytest.approx(expected.vx, abs=1e-12)
    assert got.omega == pytest.approx(expected.omega, abs=1e-9)


@pytest.mark.parametrize("name", sorted(TRACKERS))
@pytest.mark.parametrize("goal_yaw", [PI, -PI, 3.0 * PI, -1e6 * PI - PI, np.float32(-PI)])
def test_goal_yaw_at_the_cut_is_stored_wrapped(name: str, goal_yaw: float) -> None:
    tracker = TRACKERS[name]()
    tracker.set_path(WEST, goal_yaw=goal_yaw)
    assert -PI < tracker.goal_yaw <= PI
    assert abs(tracker.goal_yaw - PI) < 1e-6 or abs(tracker.goal_yaw + PI) < 1e-6


@pytest.mark.parametrize("name", sorted(TRACKERS))
@pytest.mark.parametrize(("heading", "sign"), [(3.1, 1.0), (-3.1, -1.0)])
def test_final_turn_to_pi_takes_the_short_way(name: str, heading: float, sign: float) -> None:
    # At the goal (within its tolerance) with goal yaw -π, that is π: from 3.1 turn
    # left, from -3.1 turn right, each 0.04 rad across the cut, not 6.24 rad round.
    tracker = TRACKERS[name](yaw_tolerance=0.01)
    tracker.set_path([[0.01, 0.0], [0.0, 0.0]], goal_yaw=-PI)
    cmd = tracker.step((0.0, 0.0, heading), 0.05)
    assert tracker.phase == "final"
    assert cmd.vx == 0.0
    assert math.copysign(1.0, cmd.omega) == sign and cmd.omega != 0.0
    mirror = TRACKERS[name](yaw_tolerance=0.01)
    mirror.set_path([[0.01, 0.0], [0.0, 0.0]], goal_yaw=PI)
    _mirrored(cmd, mirror.step((0.0, 0.0, -heading), 0.05))


@pytest.mark.parametrize("name", sorted(TRACKERS))
def test_final_turn_within_tolerance_across_the_cut_is_done(name: str) -> None:
    # 0.083 rad from the goal yaw across the cut, tolerance 0.1: done, no turn.
    tracker = TRACKERS[name](yaw_tolerance=0.1)
    tracker.set_path([[0.01, 0.0], [0.0, 0.0]], goal_yaw=3.1)
    assert tracker.step((0.0, 0.0, -3.1), 0.05) == Twist2D(0.0, 0.0, 0.0)
    assert tracker.done


@pytest.mark.parametrize("drive", ["omni", "diff"])
@pytest.mark.parametrize("offset", [0.02, 0.5])
def test_field_controller_heading_error_across_the_cut(drive: str, offset: float) -> None:
    # Target heading π behind-left of the x axis: headings π - offset and -π + offset
    # get mirrored commands, the turn the short way (toward π).
    target = Pose2D(-2.0, 0.0, PI)
    left = PotentialFieldController(drive=drive)
    right = PotentialFieldController(drive=drive)
    a = left.step(Pose2D(0.0, 0.0, PI - offset), target, 0.05)
    b = right.step(Pose2D(0.0, 0.0, -PI + offset), target, 0.05)
    _mirrored(a, b)
    assert a.omega > 0.0


@settings(max_examples=40, deadline=None)
@given(st.floats(0.001, 0.2))
def test_field_controller_derivative_sees_the_small_step_across_the_cut(step: float) -> None:
    # The heading error jumps from just below +π to just above -π when the target's
    # heading crosses behind the robot: a change of `step` rad, which the PID's
    # derivative must see as such (kd * step / dt), not as a jump of about -2π.
    ctl = PotentialFieldController(kp=0.0, ki=0.0, kd=1.0, max_omega=1e6)
    ctl.step(Pose2D(0.0, 0.0, 0.0), Pose2D(0.0, 0.0, PI - step / 2), 0.1)
    cmd = ctl.step(Pose2D(0.0, 0.0, 0.0), Pose2D(0.0, 0.0, -PI + step / 2), 0.1)
    assert cmd.omega == pytest.approx(step / 0.1, rel=1e-9)
