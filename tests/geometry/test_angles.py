"""wrap_angle and angle_diff."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from navkit.geometry import angle_diff, wrap_angle

finite_angles = st.floats(-1e6, 1e6, allow_nan=False)


@given(finite_angles)
def test_wrap_in_range_and_idempotent(a: float) -> None:
    w = wrap_angle(a)
    assert -math.pi < w <= math.pi
    assert wrap_angle(w) == w
    # Same direction as the input.
    assert math.isclose(math.cos(w), math.cos(a), abs_tol=1e-6)
    assert math.isclose(math.sin(w), math.sin(a), abs_tol=1e-6)


def test_wrap_boundaries() -> None:
    assert wrap_angle(math.pi) == math.pi
    assert wrap_angle(-math.pi) == math.pi
    assert wrap_angle(3 * math.pi) == pytest.approx(math.pi)
    assert wrap_angle(-1e-300) == -1e-300
    assert wrap_angle(2 * math.pi - 1e-17) == pytest.approx(0.0, abs=1e-15)
    assert isinstance(wrap_angle(1.0), float)


def test_wrap_array_does_not_modify_input() -> None:
    a = np.array([0.0, 4.0, -4.0, 7 * math.pi])
    before = a.copy()
    out = wrap_angle(a)
    np.testing.assert_array_equal(a, before)
    np.testing.assert_allclose(out, [0.0, 4.0 - 2 * math.pi, 2 * math.pi - 4.0, math.pi])
    assert out.shape == a.shape


@given(finite_angles, finite_angles)
def test_angle_diff_matches_direction(a: float, b: float) -> None:
    d = angle_diff(a, b)
    assert -math.pi < d <= math.pi
    assert math.isclose(math.cos(b + d), math.cos(a), abs_tol=1e-6)
    assert math.isclose(math.sin(b + d), math.sin(a), abs_tol=1e-6)


def test_angle_diff_known() -> None:
    assert angle_diff(math.radians(10), math.radians(350)) == pytest.approx(math.radians(20))
    assert angle_diff(math.radians(350), math.radians(10)) == pytest.approx(math.radians(-20))


@pytest.mark.parametrize("bad", [math.nan, math.inf, [0.0, -math.inf]])
def test_non_finite_rejected(bad: object) -> None:
    with pytest.raises(ValueError, match="angle"):
        wrap_angle(bad)  # type: ignore[arg-type]


def test_angle_diff_shapes_that_do_not_broadcast_name_a_and_b() -> None:
    with pytest.raises(ValueError, match=r"a and b must broadcast together.*\(2,\).*\(3,\)"):
        angle_diff([1.0, 2.0], [1.0, 2.0, 3.0])
    # Also where a - b would overflow (the path that wraps both angles first).
    with pytest.raises(ValueError, match="a and b must broadcast together"):
        angle_diff([1e308, 0.0], [-1e308, 0.0, 1.0])
    assert angle_diff([[1.0]], [2.0, 3.0]).shape == (1, 2)  # type: ignore[union-attr]
