"""The angle convention at its boundary in the wheel odometry steps.

A step's heading change lies in (-π, π]: a half turn either way is +π, larger
turns are wrapped, and the arc itself (dx, dy) is that of the whole turn.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from navkit.geometry import Pose2D, angle_diff
from navkit.kinematics import DiffDrive

PI = math.pi
TRACK = 0.5
HALF_TURN = PI * TRACK  # the lead of one wheel that turns the robot by π
METHODS = ("arc", "midpoint", "first_order")


@pytest.mark.parametrize("method", METHODS)
@pytest.mark.parametrize(("d_left", "d_right"), [(0.0, HALF_TURN), (HALF_TURN, 0.0)])
def test_a_half_turn_either_way_is_plus_pi(method: str, d_left: float, d_right: float) -> None:
    drive = DiffDrive(track=TRACK, wheel_radius=0.1)
    step = drive.odometry_step(d_left, d_right, method=method)
    assert step.theta == PI
    row = drive.odometry_step_batch([d_left], [d_right], method=method)[0]
    assert row.tolist() == [step.x, step.y, step.theta]


@settings(max_examples=100, deadline=None)
@given(
    st.floats(-100.0, 100.0),
    st.floats(-100.0, 100.0),
    st.sampled_from(METHODS),
    st.one_of(st.sampled_from([PI, -PI, 3.1, -3.1]), st.floats(-1e6, 1e6)),
)
def test_step_headings_stay_in_range(
    d_left: float, d_right: float, method: str, heading: float
) -> None:
    drive = DiffDrive(track=TRACK, wheel_radius=0.1)
    step = drive.odometry_step(d_left, d_right, method=method)
    turn = (d_right - d_left) / TRACK
    assert -PI < step.theta <= PI
    assert abs(angle_diff(step.theta, turn)) < 1e-12
    after = Pose2D(0.0, 0.0, heading).compose(step)
    assert -PI < after.theta <= PI
    row = drive.odometry_step_batch([d_left], [d_right], method=method)[0]
    assert row.tolist() == [step.x, step.y, step.theta]


def test_a_full_turn_in_place_ends_where_it_started() -> None:
    # Wheels rolling ±π·track each: a turn of 2π, wrapped to 0, and the arc's
    # chord of a turn in place is zero.
    drive = DiffDrive(track=TRACK, wheel_radius=0.1)
    step = drive.odometry_step(-HALF_TURN, HALF_TURN)
    assert abs(step.theta) < 1e-15
    assert math.hypot(step.x, step.y) < 1e-15
    rows = drive.odometry_step_batch(np.full(3, -HALF_TURN), np.full(3, HALF_TURN))
    assert np.abs(rows).max() < 1e-15
