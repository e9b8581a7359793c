"""Odometry fast paths wrap headings with ``wrap_float`` (issue 17, session 26).

``OmniOdometry.update`` and ``DiffOdometry.update`` take their one-step fast
path with Python floats and wrap the heading with ``wrap_float`` directly
(their operands are finite there) instead of ``wrap_angle``. These tests drive
headings across ±π and many turns away (compass yaws of hundreds of radians,
encoder steps of several turns) and check each fast-path pose against
``update_batch`` on a twin, bit for bit, with headings in (-π, π].
"""

from __future__ import annotations

import math

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from navkit.estimation import DiffOdometry, OmniOdometry
from navkit.kinematics import DiffDrive, OmniDrive

_yaws = st.one_of(
    st.floats(-math.pi, math.pi),
    st.floats(-1e3, 1e3),
    st.sampled_from([math.pi, -math.pi, 2 * math.pi, -3 * math.pi, math.nextafter(math.pi, 4)]),
)


@settings(max_examples=60, deadline=None)
@given(
    steps=st.lists(
        st.tuples(st.lists(st.floats(-5.0, 5.0), min_size=3, max_size=3), _yaws),
        min_size=1,
        max_size=8,
    ),
    theta0=st.floats(-math.pi, math.pi),
)
def test_omni_fast_path_equals_batch(
    steps: list[tuple[list[float], float]], theta0: float
) -> None:
    drive = OmniDrive.three_wheel(wheel_radius=0.05, base_radius=0.2)
    fast = OmniOdometry(drive, pose=(1.0, -2.0, theta0))
    batch = OmniOdometry(drive, pose=(1.0, -2.0, theta0))
    for wheels, yaw in steps:
        inc = np.array(wheels)
        pose = fast.update(inc, yaw)
        row = batch.update_batch(inc[None, :], [yaw])[-1]
        assert (pose.x, pose.y, pose.theta) == tuple(row.tolist())
        assert -math.pi < pose.theta <= math.pi
    assert fast.pose == batch.pose


@settings(max_examples=60, deadline=None)
@given(
    readings=st.lists(
        st.tuples(st.integers(-30_000, 30_000), st.integers(-30_000, 30_000)),
        min_size=2,
        max_size=8,
    ),
    method=st.sampled_from(["first_order", "midpoint", "arc"]),
    theta0=st.floats(-math.pi, math.pi),
)
def test_diff_fast_path_equals_batch(
    readings: list[tuple[int, int]], method: str, theta0: float
) -> None:
    # A 0.1 m track: 30,000 ticks on one wheel turn the robot through many turns.
    drive = DiffDrive(track=0.1, wheel_radius=0.1)
    kwargs = {"ticks_per_rev": 1000, "bits": 16, "method": method, "pose": (0.5, 0.5, theta0)}
    fast = DiffOdometry(drive, **kwargs)  # type: ignore[arg-type]
    batch = DiffOdometry(drive, **kwargs)  # type: ignore[arg-type]
    for left, right in readings:
        pose = fast.update(left, right)
        row = batch.update_batch([left], [right])[-1]
        assert (pose.x, pose.y, pose.theta) == tuple(row.tolist())
        assert -math.pi < pose.theta <= math.pi
    assert fast.pose == batch.pose
