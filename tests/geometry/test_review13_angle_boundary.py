"""The angle convention at its boundary: geometry's outputs lie in (-π, π], -π never.

Inputs at π, -π, their float neighbours, multiples of 2π, 1e15 and float32 angles
give wrapped, continuous results: a pose at heading π and one at -π are the same
pose, and neighbours across the cut agree to rounding.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from hypothesis_twins import slow_twin
from navkit.geometry import (
    Pose2D,
    angle_diff,
    integrate,
    quaternion_to_yaw,
    rollout,
    rpy_to_quaternion,
    wrap_angle,
    yaw_to_quaternion,
)

PI = math.pi
BELOW_PI = float(np.nextafter(PI, 0.0))  # the largest float below π
ABOVE_MINUS_PI = float(np.nextafter(-PI, 0.0))
BEYOND_PI = float(np.nextafter(PI, 4.0))  # just past the cut: wraps to about -π
BEYOND_MINUS_PI = float(np.nextafter(-PI, -4.0))  # wraps to about +π
SPECIAL = (
    PI, -PI, BELOW_PI, ABOVE_MINUS_PI, BEYOND_PI, BEYOND_MINUS_PI,
    2.0 * PI, -2.0 * PI, 3.0 * PI, -3.0 * PI, 1e6 * PI, -1e6 * PI, 1e15, -1e15,
    0.0, -0.0, 1.7976931348623157e308, -1.7976931348623157e308,
)  # fmt: skip

angles = st.one_of(
    st.sampled_from(SPECIAL),
    st.floats(-10.0, 10.0),
    st.floats(-1e300, 1e300),
    # Near a multiple of π, where rounding decides the side of the cut.
    st.builds(
        lambda k, ulps: float(k * PI + ulps * 4.440892098500626e-16 * max(1, abs(k))),
        st.integers(-(10**6), 10**6),
        st.integers(-4, 4),
    ),
)


def in_range(a: float) -> bool:
    return -PI < a <= PI


def test_the_cut_itself() -> None:
    # -π and its float neighbours beyond it wrap to (about) +π; the ones inside stay.
    assert wrap_angle(-PI) == PI
    assert wrap_angle(BEYOND_MINUS_PI) == BELOW_PI  # -π - ulp is π - ulp, exactly
    assert wrap_angle(BEYOND_PI) == ABOVE_MINUS_PI
    assert wrap_angle(BELOW_PI) == BELOW_PI
    assert wrap_angle(ABOVE_MINUS_PI) == ABOVE_MINUS_PI
    assert wrap_angle(np.array([-PI, BEYOND_MINUS_PI])).tolist() == [PI, BELOW_PI]
    assert Pose2D(0.0, 0.0, -PI) == Pose2D(0.0, 0.0, PI)
    assert Pose2D(0.0, 0.0, -PI).theta == PI


@settings(max_examples=150, deadline=None)
@given(angles, angles)
def test_pose_operations_stay_in_range(a: float, b: float) -> None:
    p = Pose2D(1.0, -2.0, a)
    q = Pose2D(0.5, 0.25, b)
    thetas = (
        p.theta,
        p.inverse().theta,
        p.compose(q).theta,
        (p @ [0.5, 0.25, b]).theta,
        p.relative_to(q).theta,
        Pose2D.from_array([1.0, -2.0, a]).theta,
        angle_diff(a, b),
        float(angle_diff(np.array([a]), b)[0]),
        wrap_angle(a),
    )
    for theta in thetas:
        assert in_range(theta), (a, b, theta)
    # The scalar and the array forms wrap the same.
    assert wrap_angle(a) == float(wrap_angle(np.array([a]))[0])


test_pose_operations_stay_in_range_thoroughly = slow_twin(
    test_pose_operations_stay_in_range, max_examples=1500
)


@pytest.mark.parametrize(("inside", "outside"), [(PI, -PI), (BELOW_PI, BEYOND_MINUS_PI)])
def test_a_heading_and_its_other_spelling_are_one_pose(inside: float, outside: float) -> None:
    a, b = Pose2D(3.0, -1.0, inside), Pose2D(3.0, -1.0, outside)
    assert a == b
    other = Pose2D(0.5, -0.25, 1.0)
    assert a.compose(other) == b.compose(other)
    assert other.compose(a) == other.compose(b)
    assert a.inverse() == b.inverse()
    assert a.relative_to(other) == b.relative_to(other)
    assert integrate(a, (1.0, 0.0, 0.5), 0.1) == integrate(b, (1.0, 0.0, 0.5), 0.1)


@settings(max_examples=60, deadline=None)
@given(st.integers(1, 8), st.floats(-1.0, 1.0), st.floats(-1.0, 1.0))
def test_neighbours_across_the_cut_agree(ulps: int, x: float, y: float) -> None:
    # Headings ulps·4.4e-16 on either side of ±π: the same pose to rounding.
    spacing = 4.440892098500626e-16
    left = Pose2D(0.0, 0.0, PI - ulps * spacing)
    right = Pose2D(0.0, 0.0, -PI + ulps * spacing)
    assert abs(angle_diff(left.theta, right.theta)) <= 2 * ulps * spacing + 1e-30
    np.testing.assert_allclose(
        left.transform_points([x, y]), right.transform_points([x, y]), rtol=0.0, atol=1e-14
    )
    turned_left = left.compose(Pose2D(x, y, 0.1))
    turned_right = right.compose(Pose2D(x, y, 0.1))
    assert abs(angle_diff(turned_left.theta, turned_right.theta)) < 1e-14
    # The two headings differ by 2·ulps·spacing (up to 7e-15 rad): (x, y) turned by
    # that moves up to |(x, y)| times it, plus rounding.
    apart = 2 * ulps * spacing * math.hypot(x, y) + 8 * 2.2e-16 * (1.0 + math.hypot(x, y))
    assert math.hypot(turned_left.x - turned_right.x, turned_left.y - turned_right.y) <= apart


def test_a_turn_across_the_cut_is_a_small_difference() -> None:
    assert angle_diff(-3.1, 3.1) == pytest.approx(2 * PI - 6.2, abs=1e-15)
    assert angle_diff(3.1, -3.1) == pytest.approx(6.2 - 2 * PI, abs=1e-15)
    assert Pose2D(0.0, 0.0, -3.1).relative_to(Pose2D(0.0, 0.0, 3.1)).theta == pytest.approx(
        2 * PI - 6.2, abs=1e-15
    )


@settings(max_examples=80, deadline=None)
@given(angles, st.floats(-100.0, 100.0), st.floats(0.0, 10.0))
def test_integrated_headings_stay_in_range(theta: float, omega: float, dt: float) -> None:
    p = integrate(Pose2D(0.0, 0.0, theta), (1.0, 0.0, omega), dt)
    assert in_range(p.theta)
    rows = rollout(Pose2D(0.0, 0.0, theta), [[1.0, 0.0, omega]] * 3, dt)
    assert all(in_range(t) for t in rows[:, 2].tolist())
    assert rows[1].tolist() == [p.x, p.y, p.theta]


def test_a_half_turn_ends_at_plus_pi() -> None:
    # Turning by exactly -π (or +π) from 0 ends at +π, never -π.
    assert integrate((0.0, 0.0, 0.0), (0.0, 0.0, -PI), 1.0).theta == PI
    assert integrate((0.0, 0.0, 0.0), (0.0, 0.0, PI), 1.0).theta == PI
    assert rollout((0.0, 0.0, 0.0), [[0.0, 0.0, -PI]], 1.0)[1, 2] == PI
    assert Pose2D(0.0, 0.0, PI / 2).compose(Pose2D(0.0, 0.0, PI / 2)).theta == PI
    assert Pose2D(0.0, 0.0, -PI / 2).compose(Pose2D(0.0, 0.0, -PI / 2)).theta == PI


@pytest.mark.parametrize(
    "quaternion",
    [
        [0.0, 0.0, 1.0, -0.0],
        [-0.0, 0.0, 1.0, 0.0],  # x y = -0.0: atan2(-0.0, -1) is -π
        [0.0, 0.0, -1.0, 0.0],
        [0.0, 0.0, 1.0, -1e-300],  # atan2(-tiny, -1) rounds to -π
        [0.0, 0.0, -1.0, 1e-300],
    ],
)
def test_a_half_turn_quaternion_is_plus_pi(quaternion: list[float]) -> None:
    assert quaternion_to_yaw(quaternion) == PI
    assert quaternion_to_yaw([quaternion]).tolist() == [PI]
    assert quaternion_to_yaw(np.array([quaternion], dtype=np.float32)).tolist() == [PI]


@settings(max_examples=100, deadline=None)
@given(angles, st.floats(-1.5, 1.5), st.floats(-3.0, 3.0))
def test_quaternion_yaws_stay_in_range(yaw: float, pitch: float, roll: float) -> None:
    assert in_range(quaternion_to_yaw(yaw_to_quaternion(yaw)))
    assert in_range(quaternion_to_yaw(rpy_to_quaternion(roll, pitch, yaw)))
    # A level rotation's yaw is the wrapped yaw, to rounding (continuous across ±π).
    if abs(yaw) < 1e6:
        back = quaternion_to_yaw(yaw_to_quaternion(yaw))
        assert abs(angle_diff(back, yaw)) < 1e-9


@settings(max_examples=100, deadline=None)
@given(st.floats(-1e6, 1e6, width=32))
def test_float32_angles_are_wrapped_as_their_float64_values(a: float) -> None:
    single = np.float32(a)
    expected = wrap_angle(float(single))
    assert wrap_angle(single) == expected
    assert float(wrap_angle(np.array([single]))[0]) == expected
    assert Pose2D(0.0, 0.0, single).theta == expected
    assert Pose2D.from_array(np.array([0.0, 0.0, single], dtype=np.float32)).theta == expected
    assert angle_diff(single, np.float32(0.0)) == expected


def test_float32_pi_lies_beyond_the_cut() -> None:
    # float32(π) is 8.7e-8 rad past π: it wraps to just above -π (and float32(-π) to
    # just below π), continuously, not to a value outside (-π, π].
    up = Pose2D(0.0, 0.0, np.float32(PI)).theta
    down = Pose2D(0.0, 0.0, np.float32(-PI)).theta
    assert up == pytest.approx(-PI + 8.742278e-8, abs=1e-14)
    assert down == pytest.approx(PI - 8.742278e-8, abs=1e-14)
    assert in_range(up) and in_range(down)
