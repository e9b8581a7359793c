"""wrap_angle reduces by the float 2π exactly: no rounding at all (exact rational checks).

The old formula ``pi - ((pi - a) % 2pi)`` rounded ``pi - a`` and the divisor that
``%`` adds to a negative remainder: up to 1.6e4 ulps of the result for angles in
(-2π, -π) (a sum of two headings: ``wrap_angle(-6.28)`` was 2048 ulps off, and not
``-wrap_angle(6.28)``), 6.5e4 below 100 rad, and every bit of it beyond 1e19 rad
(``wrap_angle(1e20)`` was -1.246, the exact reduction by the float 2π is 1.896).
``fmod`` by the float 2π and one fold are both exact, so the result is
``a - k * 2 * math.pi`` for an integer ``k``, as a rational number.
"""

from __future__ import annotations

import math
from fractions import Fraction

import numpy as np
from hypothesis import example, given, settings
from hypothesis import strategies as st

from navkit._shared.angles import wrap_float as _wrap_float
from navkit._shared.se2 import wrap_scalar
from navkit.geometry import angle_diff, wrap_angle

TWO_PI = Fraction(2 * math.pi)
angles = st.one_of(
    st.floats(-20.0, 20.0),
    st.floats(-1e300, 1e300),
    st.floats(-1.7e308, 1.7e308),
)


def assert_exact_reduction(angle: float, got: float) -> None:
    turns = (Fraction(angle) - Fraction(got)) / TWO_PI
    assert turns.denominator == 1, (angle, got, float(turns))
    assert -math.pi < got <= math.pi, (angle, got)


@settings(max_examples=60, deadline=None)
@given(st.lists(angles, min_size=1, max_size=20))
@example([-4.0, 4.0, -2 * math.pi + 1e-9, 100.0, 1e20, -1e300, 3 * math.pi, -math.pi])
def test_wrap_angle_is_an_exact_reduction_by_the_float_two_pi(values: list[float]) -> None:
    wrapped = np.asarray(wrap_angle(np.array(values)))
    for angle, got in zip(values, wrapped.tolist(), strict=True):
        assert_exact_reduction(angle, got)
        # One rule in every form: the scalar path, the array path and the kernels' wrap.
        for other in (wrap_angle(angle), _wrap_float(angle), wrap_scalar(angle)):
            assert other == got and math.copysign(1.0, other) == math.copysign(1.0, got)


def test_documented_values() -> None:
    assert wrap_angle(-math.pi) == math.pi
    assert wrap_angle(2 * math.pi) == 0.0  # the float 2π is one turn
    assert wrap_angle(-2 * math.pi) == 0.0
    # -6.28 + 2π: the old formula rounded π + 6.28 first, 2048 ulps (8.9e-16 rad) off,
    # and unlike wrap_angle(6.28) (exact then as now): not odd.
    assert Fraction(wrap_angle(-6.28)) == Fraction(-6.28) + TWO_PI
    assert wrap_angle(-6.28) == -wrap_angle(6.28)
    assert Fraction(wrap_angle(100.0)) == Fraction(100.0) - 16 * TWO_PI  # was 32 ulps off
    assert Fraction(angle_diff(3.0, -3.0)) == Fraction(6.0) - TWO_PI


@settings(max_examples=60, deadline=None)
@given(angles)
def test_wrap_angle_is_odd_away_from_pi(angle: float) -> None:
    got = wrap_angle(angle)
    if got != math.pi:  # (-π, π] is not symmetric: π is its own image
        assert wrap_angle(-angle) == -got
