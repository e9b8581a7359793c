"""``PlanarFusion(pose=)``: the start pose by the name the rest of navkit uses (review 20).

A new user's app met ``PlanarFusion(x0=[x, y, θ, 0, 0, 0])`` beside
``OmniOdometry(pose=)``, ``DiffOdometry(pose=)`` and ``Simulation(start=)``.
``pose=`` is ``x0`` with zero rates: the same filter, bit for bit.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from navkit.estimation import PlanarFusion
from navkit.geometry import Pose2D

coordinates = st.floats(-1e7, 1e7, allow_nan=False)
angles = st.floats(-10.0, 10.0, allow_nan=False)


@settings(max_examples=40, deadline=None)
@given(coordinates, coordinates, angles, st.booleans())
def test_pose_is_x0_with_zero_rates(x: float, y: float, theta: float, as_pose: bool) -> None:
    given_pose = Pose2D(x, y, theta) if as_pose else (x, y, theta)
    by_pose = PlanarFusion(pose=given_pose, t0=0.0)
    by_x0 = PlanarFusion([x, y, theta, 0.0, 0.0, 0.0], t0=0.0)
    np.testing.assert_array_equal(by_pose.x, by_x0.x)
    assert -math.pi < by_pose.x[2] <= math.pi
    for k in range(1, 6):
        a = by_pose.update_odometry(0.1 * k, 0.5, 0.2, v_variance=1e-3, omega_variance=1e-3)
        b = by_x0.update_odometry(0.1 * k, 0.5, 0.2, v_variance=1e-3, omega_variance=1e-3)
        assert a.accepted == b.accepted
    np.testing.assert_array_equal(by_pose.x, by_x0.x)
    np.testing.assert_array_equal(by_pose.P, by_x0.P)


def test_x0_and_pose_together_are_refused() -> None:
    with pytest.raises(ValueError, match="give x0 or pose, not both"):
        PlanarFusion(np.zeros(6), pose=(0.0, 0.0, 0.0))


@pytest.mark.parametrize(
    ("pose", "error"),
    [((1.0, 2.0), ValueError), ((1.0, math.nan, 0.0), ValueError), ("origin", TypeError)],
)
def test_a_bad_pose_is_named(pose: object, error: type[Exception]) -> None:
    with pytest.raises(error, match="pose"):
        PlanarFusion(pose=pose)  # type: ignore[arg-type]
