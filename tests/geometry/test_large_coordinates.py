"""Poses at large coordinates: UTM-sized positions and the edge of the float range.

References are exact: ``fractions.Fraction`` arithmetic on the float inputs (and on
the float cosine and sine the code itself uses), rounded once at the end.
"""

from __future__ import annotations

import math
import sys
from fractions import Fraction

import numpy as np
import pytest
from hypothesis import example, given, settings
from hypothesis import strategies as st

from hypothesis_twins import slow_twin
from navkit.geometry import Pose2D, angle_diff, integrate, rollout

U = 2.0**-53  # unit roundoff of float64
BIG = sys.float_info.max
# Exact results this close to the float limit may round either way.
SURELY_FINITE = Fraction(BIG) * (1 - Fraction(1, 2**40))
SURELY_OVERFLOWS = Fraction(BIG) * (1 + Fraction(1, 2**40))

headings = st.floats(-math.pi, math.pi)
# Every eighth of a turn too: there cos and sin are equal in size, and a sum of two
# rotated terms can cancel.
turns = headings | st.integers(-3, 4).map(lambda k: k * math.pi / 4)
huge = st.floats(-BIG, BIG, allow_nan=False, allow_infinity=False)
huge_or_zero = huge | st.sampled_from([0.0, 1e308, -1e308, 1.7e308, -1.7e308])


def rotate_exact(
    x: Fraction, y: Fraction, theta: float, sign: int = 1
) -> tuple[Fraction, Fraction]:
    """``R(sign * theta) @ (x, y)`` with the float cosine and sine, exactly."""
    theta = Pose2D(0.0, 0.0, theta).theta  # wrapped as a pose wraps it
    c = Fraction(math.cos(theta))
    s = Fraction(math.sin(theta)) * sign
    return c * x - s * y, s * x + c * y


def check_against(value: float, exact: Fraction, scale: Fraction) -> None:
    """``value`` is ``exact`` to a few roundings of ``scale`` (the size of the terms).

    Plus a few of the smallest subnormal: below 2.2e-308 a float rounds by up to
    2.5e-324 however small it is (``sin(1) * 2.2e-313``), not relative to its size.
    """
    tiny = Fraction(math.ulp(0.0))
    assert abs(Fraction(value) - exact) <= 16 * Fraction(U) * scale + 4 * tiny


# ----------------------------------------------------------------------------------
# relative_to at UTM coordinates (it used to compose with frame.inverse(), whose
# translation is as large as the coordinates and cancels: about 1e-9 m off).

eastings = st.floats(1e5, 1e6)
northings = st.floats(1e6, 1e7)
offsets = st.floats(-1e3, 1e3)


@settings(max_examples=40)
@given(eastings, northings, headings, offsets, offsets, headings)
def test_relative_to_at_utm_coordinates_is_exact_to_rounding(
    fx: float, fy: float, ftheta: float, ox: float, oy: float, theta: float
) -> None:
    frame = Pose2D(fx, fy, ftheta)
    pose = Pose2D(fx + ox, fy + oy, theta)
    rel = pose.relative_to(frame)
    dx = Fraction(pose.x) - Fraction(frame.x)
    dy = Fraction(pose.y) - Fraction(frame.y)
    want_x, want_y = rotate_exact(dx, dy, frame.theta, sign=-1)
    # Accurate to the distance between the poses, not to their 1e6 m coordinates.
    check_against(rel.x, want_x, abs(dx) + abs(dy))
    check_against(rel.y, want_y, abs(dx) + abs(dy))
    want_theta = float(Fraction(pose.theta) - Fraction(frame.theta))
    assert abs(angle_diff(rel.theta, want_theta)) <= 8 * U * math.pi
    assert -math.pi < rel.theta <= math.pi


test_relative_to_at_utm_coordinates_is_exact_to_rounding_thoroughly = slow_twin(
    test_relative_to_at_utm_coordinates_is_exact_to_rounding, max_examples=100
)


def test_relative_to_at_utm_coordinates_known_case() -> None:
    frame = Pose2D(512340.111, 5412340.987, 2.1)
    pose = Pose2D(512345.678, 5412345.123, 0.7)
    rel = pose.relative_to(frame)
    dx = Fraction(pose.x) - Fraction(frame.x)
    dy = Fraction(pose.y) - Fraction(frame.y)
    want_x, want_y = rotate_exact(dx, dy, frame.theta, sign=-1)
    # The old frame.inverse() ⊕ pose was 4e-10 m off in x here.
    assert abs(rel.x - float(want_x)) <= 1e-15
    assert abs(rel.y - float(want_y)) <= 1e-14
    assert frame.relative_to(frame) == Pose2D(0.0, 0.0, 0.0)


# ----------------------------------------------------------------------------------
# The edge of the float range: finite inputs with a finite result give that result
# (a partial sum such as x + cos(theta) * dx used to overflow and raise), an
# overflowing result a ValueError naming the argument.


def check_result(call: object, exact: tuple[Fraction, ...], scale: Fraction, name: str) -> None:
    """``call()`` returns values matching ``exact`` or raises when they overflow."""
    assert callable(call)
    peak = max(abs(v) for v in exact)
    if peak >= SURELY_OVERFLOWS:
        with pytest.raises(ValueError, match=name):
            call()
        return
    try:
        got = call()
    except ValueError:
        assert peak > SURELY_FINITE, "a finite result was refused as an overflow"
        return
    for value, want in zip(got, exact, strict=True):
        assert math.isfinite(value)
        check_against(value, want, scale)


@settings(max_examples=40)
@given(huge_or_zero, huge_or_zero, turns, huge_or_zero, huge_or_zero, headings)
@example(0.0, 0.0, 1.0, 0.0, 2.2250738585e-313, 0.0)  # a subnormal result: rounded absolutely
def test_compose_near_the_float_limit(
    x: float, y: float, theta: float, ox: float, oy: float, otheta: float
) -> None:
    pose = Pose2D(x, y, theta)
    rx, ry = rotate_exact(Fraction(ox), Fraction(oy), theta)
    exact = (Fraction(x) + rx, Fraction(y) + ry)
    scale = abs(Fraction(x)) + abs(Fraction(y)) + abs(Fraction(ox)) + abs(Fraction(oy))

    def call() -> tuple[float, float]:
        out = pose.compose([ox, oy, otheta])
        return out.x, out.y

    check_result(call, exact, scale, "other")


test_compose_near_the_float_limit_thoroughly = slow_twin(
    test_compose_near_the_float_limit, max_examples=100
)


@settings(max_examples=40)
@given(huge_or_zero, huge_or_zero, turns, huge_or_zero, huge_or_zero, headings)
def test_relative_to_near_the_float_limit(
    x: float, y: float, theta: float, fx: float, fy: float, ftheta: float
) -> None:
    pose = Pose2D(fx, fy, ftheta)
    dx = Fraction(fx) - Fraction(x)
    dy = Fraction(fy) - Fraction(y)
    exact = rotate_exact(dx, dy, theta, sign=-1)

    def call() -> tuple[float, float]:
        out = pose.relative_to([x, y, theta])
        return out.x, out.y

    check_result(call, exact, abs(dx) + abs(dy), "frame")


test_relative_to_near_the_float_limit_thoroughly = slow_twin(
    test_relative_to_near_the_float_limit, max_examples=100
)


@settings(max_examples=40)
@given(huge_or_zero, huge_or_zero, turns, huge_or_zero, huge_or_zero)
def test_transform_points_near_the_float_limit(
    x: float, y: float, theta: float, px: float, py: float
) -> None:
    pose = Pose2D(x, y, theta)
    rx, ry = rotate_exact(Fraction(px), Fraction(py), theta)
    exact = (Fraction(x) + rx, Fraction(y) + ry)
    scale = abs(Fraction(x)) + abs(Fraction(y)) + abs(Fraction(px)) + abs(Fraction(py))

    def call() -> tuple[float, float]:
        out = pose.transform_points([[px, py]])
        return float(out[0, 0]), float(out[0, 1])

    check_result(call, exact, scale, "points_xy")


test_transform_points_near_the_float_limit_thoroughly = slow_twin(
    test_transform_points_near_the_float_limit, max_examples=100
)


@settings(max_examples=40)
@given(huge_or_zero, huge_or_zero, turns, huge_or_zero, huge_or_zero, st.floats(0.0, 4.0))
def test_straight_integration_near_the_float_limit(
    x: float, y: float, theta: float, vx: float, vy: float, dt: float
) -> None:
    # omega = 0: the exact motion is the straight line (x, y) + R(theta) (vx, vy) dt.
    rx, ry = rotate_exact(Fraction(vx) * Fraction(dt), Fraction(vy) * Fraction(dt), theta)
    exact = (Fraction(x) + rx, Fraction(y) + ry)
    scale = abs(Fraction(x)) + abs(Fraction(y)) + (abs(Fraction(vx)) + abs(Fraction(vy))) * 4

    def call() -> tuple[float, float]:
        out = integrate([x, y, theta], [vx, vy, 0.0], dt)
        return out.x, out.y

    check_result(call, exact, scale, "twist")

    def call_rollout() -> tuple[float, float]:
        out = rollout([x, y, theta], [[vx, vy, 0.0]], dt)
        assert tuple(out[0]) == (x, y, Pose2D(0.0, 0.0, theta).theta)
        return float(out[1, 0]), float(out[1, 1])

    check_result(call_rollout, exact, scale, "twists")


test_straight_integration_near_the_float_limit_thoroughly = slow_twin(
    test_straight_integration_near_the_float_limit, max_examples=100
)


def test_compose_with_an_overflowing_partial_sum_known_case() -> None:
    # 1.7e308 + cos(π/4) * 1e308 overflows; the sine term brings the sum back.
    out = Pose2D(1.7e308, 0.0, math.pi / 4).compose([1e308, 1e308, 0.5])
    want_x, want_y = rotate_exact(Fraction(1e308), Fraction(1e308), math.pi / 4)
    check_against(out.x, Fraction(1.7e308) + want_x, Fraction(1.7e308) + 2 * Fraction(1e308))
    check_against(out.y, want_y, 2 * Fraction(1e308))
    assert out.theta == math.pi / 4 + 0.5


def test_integrate_and_rollout_with_an_overflowing_partial_sum() -> None:
    start = [1.7e308, 0.0, math.pi / 4]
    end = integrate(start, [1e308, 1e308, 0.0], 1.0)
    assert end == Pose2D(1.7e308, 0.0, math.pi / 4).compose([1e308, 1e308, 0.0])
    # Out to beyond 1.4e308 in y and partly back in x: every pose is finite.
    twists = np.array([[1e308, 1e308, 0.0], [-1e308, 1e308, 0.0]])
    before = twists.copy()
    traj = rollout(start, twists, 1.0)
    np.testing.assert_array_equal(twists, before)  # the input is not modified
    assert np.isfinite(traj).all()
    np.testing.assert_array_equal(traj[0], start)
    assert traj[1, 0] == end.x and traj[1, 1] == end.y
    assert traj[2, 0] == pytest.approx(1.7e308 - math.sqrt(2) * 1e308, rel=1e-12)


def test_rollout_out_of_range_and_back_is_still_an_error() -> None:
    # The middle pose (3e308, 0) is beyond the float range, though the last is not.
    with pytest.raises(ValueError, match="twists"):
        rollout([0.0, 0.0, 0.0], [[1e308, 0.0, 0.0], [-1e308, 0.0, 0.0]], 3.0)
