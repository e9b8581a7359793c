"""Issue 12 in navkit.geometry: bad input raises TypeError/ValueError naming it, never NaN."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from hypothesis_twins import slow_twin
from navkit.geometry import Pose2D, Twist2D, angle_diff, integrate, rollout, wrap_angle

finite = st.floats(allow_nan=False, allow_infinity=False)


@pytest.mark.parametrize(
    ("call", "name"),
    [
        (lambda: Pose2D(0, 0, 0).compose(3), "other"),
        (lambda: Pose2D(0, 0, 0).compose(None), "other"),
        (lambda: Pose2D(0, 0, 0) @ "abc", "other"),
        (lambda: Pose2D(0, 0, 0).relative_to("x"), "frame"),
        (lambda: Pose2D(0, 0, 0).relative_to(None), "frame"),
    ],
)
def test_pose_operations_refuse_non_poses_with_type_error(call, name) -> None:  # type: ignore[no-untyped-def]
    with pytest.raises(TypeError, match=name):
        call()


@pytest.mark.parametrize(
    ("call", "name"),
    [
        (lambda: wrap_angle(np.array([1 + 1j, 2])), "angle"),
        (lambda: wrap_angle(1 + 0j), "angle"),
        (lambda: wrap_angle("1.0"), "angle"),
        (lambda: wrap_angle(True), "angle"),
        (lambda: angle_diff(np.array([1 + 1j]), 0.0), "a"),
        (lambda: angle_diff(0.0, "0.5"), "b"),
        (lambda: rollout(Pose2D(0, 0, 0), [[1.0, 0.0, 0.0]], dt="1.0"), "dt"),
        (lambda: rollout(Pose2D(0, 0, 0), [[1.0 + 1j, 0.0, 0.0]], dt=1.0), "twists"),
        (lambda: integrate([0, 0, 0], [1, 0, 0], "0.5"), "dt"),
        (lambda: integrate([0, 0, 0], [1, 0, 0], 1 + 0j), "dt"),
        (lambda: Pose2D(1 + 0j, 0), "x"),
        (lambda: Pose2D(0, "1"), "y"),
        (lambda: Twist2D(True), "vx"),
        (lambda: Pose2D(0, 0, 0).transform_points(np.array([[1 + 1j, 0]])), "points_xy"),
    ],
)
def test_complex_strings_and_bools_are_refused(call, name) -> None:  # type: ignore[no-untyped-def]
    with pytest.raises(TypeError, match=name):
        call()


@pytest.mark.parametrize(
    ("call", "name"),
    [
        (lambda: integrate([0, 0, 0], [1e308, 0, 1e308], 1e10), "overflows"),
        (lambda: rollout([0, 0, 0], [[1e308, 0, 0]] * 3, 1e300), "overflows"),
        (lambda: rollout([0, 0, 0], [[1.0, 0, 1e308]], 1e300), "overflows"),
        (lambda: Pose2D(1e308, 1e308, 1.0).compose([1e308, 1e308, 0]), "other"),
        (lambda: Pose2D(-1.7e308, 1.7e308, 2.0).inverse(), "pose"),
        (lambda: Pose2D(0, 0, 0).relative_to([-1.7e308, 1.7e308, 2.0]), "frame"),
        (lambda: Pose2D(1e308, 0, 0).transform_points([[1e308, 0.0]]), "points_xy"),
    ],
)
def test_overflow_is_a_value_error_not_nan(call, name) -> None:  # type: ignore[no-untyped-def]
    with pytest.raises(ValueError, match=name):
        call()


def test_angle_diff_of_angles_near_the_float_limit_is_finite() -> None:
    # a - b overflows; the angles are wrapped first (before issue 12: NaN).
    want = float(wrap_angle(wrap_angle(1e308) - wrap_angle(-1e308)))
    assert angle_diff(1e308, -1e308) == want
    np.testing.assert_array_equal(angle_diff(np.array([1e308, 0.5]), -1e308)[0], want)
    assert math.isfinite(angle_diff(-1.7976931348623157e308, 1.7976931348623157e308))


@settings(deadline=None)  # the first example may load compiled kernels
@given(st.floats(min_value=-1e6, max_value=1e6) | finite)
def test_scalar_fast_path_matches_the_array_path_bit_for_bit(a: float) -> None:
    scalar = wrap_angle(a)
    array = wrap_angle(np.array([a]))[0]
    assert scalar == array and math.copysign(1.0, scalar) == math.copysign(1.0, array)
    assert -math.pi < scalar <= math.pi


@settings(deadline=None)  # the first example may load compiled kernels
@given(finite, finite)
def test_angle_diff_is_finite_and_wrapped_for_every_finite_input(a: float, b: float) -> None:
    d = angle_diff(a, b)
    assert -math.pi < d <= math.pi
    assert d == angle_diff(np.array([a]), np.array([b]))[0]


@settings(max_examples=40, deadline=None)  # the first example may load compiled kernels
@given(
    st.lists(st.floats(-1e3, 1e3), min_size=3, max_size=3),
    st.lists(st.floats(-1e3, 1e3), min_size=3, max_size=3),
    st.floats(0.0, 1e3),
)
def test_integration_in_range_is_finite(pose: list[float], twist: list[float], dt: float) -> None:
    p = integrate(pose, twist, dt)
    assert all(math.isfinite(v) for v in (p.x, p.y, p.theta))
    assert np.isfinite(rollout(pose, [twist] * 3, dt)).all()


test_integration_in_range_is_finite_thoroughly = slow_twin(
    test_integration_in_range_is_finite, max_examples=100
)
