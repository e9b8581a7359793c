"""The controllers' scalar ``wrap`` agrees with ``wrap_angle`` bit for bit."""

from __future__ import annotations

import math

from hypothesis import given, settings
from hypothesis import strategies as st

from navkit.control._path_following import wrap
from navkit.geometry import wrap_angle


def test_wrap_near_a_turn_is_exact_and_odd() -> None:
    # -6.28 is 2048 ulps off with pi - ((pi - a) % 2pi); fmod is exact.
    assert wrap(-6.28) == -6.28 + 2.0 * math.pi == wrap_angle(-6.28)
    assert wrap(-6.28) == -wrap(6.28)


@settings(max_examples=60, deadline=None)
@given(st.floats(-1e20, 1e20, allow_nan=False, allow_infinity=False))
def test_wrap_matches_wrap_angle(a: float) -> None:
    got = wrap(a)
    assert math.copysign(1.0, got) == math.copysign(1.0, wrap_angle(a))
    assert got == wrap_angle(a)
    assert -math.pi < got <= math.pi


@settings(max_examples=60, deadline=None)
@given(
    st.floats(-math.pi, math.pi, exclude_min=True),
    st.floats(-math.pi, math.pi, exclude_min=True),
)
def test_wrap_of_heading_differences_matches_wrap_angle(a: float, b: float) -> None:
    # What the controllers wrap: differences and sums of two headings.
    assert wrap(a - b) == wrap_angle(a - b)
    assert wrap(a + b) == wrap_angle(a + b)
