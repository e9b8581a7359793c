"""``wrap_angle`` of huge angles is as exact as the float it is given (review 52, PRECISION).

``wrap_angle`` reduces by multiples of the float ``2 * math.pi``, 2.4e-16 less than
2π, so its result drifts from the exact reduction by 2π as the angle grows. The
docstring bounds that drift by the angle's own rounding: about 1.1 times half the
spacing of floats at the angle, whatever its size. Oracle: the exact reduction of
the float by 2π in 2000-bit arithmetic (mpmath).
"""

from __future__ import annotations

import math

import mpmath
from hypothesis import example, given, settings
from hypothesis import strategies as st

from navkit.geometry import wrap_angle

_CTX = mpmath.mp.clone()
_CTX.prec = 2000
_TWO_PI = 2 * _CTX.pi


def _circular_error(angle: float) -> float:
    """Distance around the circle from ``wrap_angle(angle)`` to ``angle`` reduced exactly."""
    a = _CTX.mpf(angle)
    exact = a - _TWO_PI * _CTX.nint(a / _TWO_PI)
    d = abs(_CTX.mpf(wrap_angle(angle)) - exact) % _TWO_PI
    return float(min(d, _TWO_PI - d))


@settings(max_examples=200, deadline=None)
@given(st.floats(-1e300, 1e300, allow_nan=False))
@example(1e6)
@example(3.5)  # (π, 4): the largest ratio, 2.4e-16 against a half-spacing of 2.2e-16
@example(-3 * math.pi)
@example(1e16)
@example(2.0**53)
def test_the_reduction_is_within_the_angles_own_rounding(angle: float) -> None:
    half_spacing = math.ulp(angle) / 2
    assert _circular_error(angle) <= 1.11 * half_spacing


def test_the_documented_figures() -> None:
    # 1e6 rad: 4e-11 off, where floats are 1.2e-10 apart.
    assert 3.8e-11 < _circular_error(1e6) < 4.0e-11
    assert math.ulp(1e6) == 2.0**-33
    # 1e16 rad: 2.637, the exact reduction 2.247, floats 2 rad apart.
    assert round(wrap_angle(1e16), 3) == 2.637
    assert abs(_circular_error(1e16) - (2.637 - 2.247)) < 1e-3
    assert math.ulp(1e16) == 2.0
