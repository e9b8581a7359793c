"""``compass_to_yaw``'s reduction of the heading difference (session 39, SMALLS).

The function kept a guard ``np.where(rel >= 360.0, 0.0, rel)`` whose comment ("np.mod
can round a tiny negative difference up to exactly 360") described an older formula
(``np.mod(raw - theta0, 360)``). With the present one the guard was dead: both reduced
angles lie in [0, 360], their difference plus 360 in [0, 720] (never -0.0), and the
remainder of a non-negative float is exact, so ``rel`` is in [0, 360). (And were it 360,
the yaw would be ``360 - 360 = +0.0``, the guard's own answer.) The guard is removed; these
tests hold the results to an exact rational reference on the values nearest the edges,
before and after.
"""

from __future__ import annotations

import math
from fractions import Fraction

import numpy as np
from hypothesis import example, given, settings
from hypothesis import strategies as st

from navkit.estimation import compass_to_yaw

_EDGES = [
    0.0, -0.0, 5e-324, -5e-324, 1e-300, -1e-300, 1e-20, -1e-20,
    180.0, -180.0, 360.0, -360.0, 540.0, 720.0, 1e20, -1e20, 1.7e308, -1.7e308,
    math.nextafter(360.0, 0.0), math.nextafter(360.0, 720.0),
    math.nextafter(-360.0, 0.0), math.nextafter(180.0, 0.0), math.nextafter(180.0, 360.0),
    math.nextafter(0.0, -1.0), math.nextafter(720.0, 0.0),
]  # fmt: skip

angles = st.one_of(
    st.sampled_from(_EDGES),
    st.floats(allow_nan=False, allow_infinity=False),
    st.floats(-1000.0, 1000.0),
    st.floats(-1e-10, 1e-10),
)


def _reference(raw: float, initial: float) -> float:
    """The yaw (degrees) of the paper's formula in exact rational arithmetic."""
    rel = (Fraction(raw) - Fraction(initial)) % 360
    return float(-rel if rel < 180 else 360 - rel)


@settings(max_examples=400, deadline=None)
@given(raw=angles, initial=angles)
@example(raw=-1e-20, initial=0.0)  # the reduced raw is 360 itself
@example(raw=0.0, initial=-1e-20)  # the reduced initial heading is 360
@example(raw=-5e-324, initial=-5e-324)
@example(raw=-0.0, initial=0.0)
def test_yaw_matches_the_exact_formula(raw: float, initial: float) -> None:
    yaw = compass_to_yaw(raw, initial_deg=initial)
    assert -math.pi < yaw <= math.pi
    want = math.radians(_reference(raw, initial))
    # Two roundings of values up to 720 degrees, then one of the conversion: apart
    # from the ±π seam, where either side is the same heading.
    error = abs(math.remainder(yaw - want, 2.0 * math.pi))
    assert error <= 1e-15 * 8, (yaw, want)
    # The array path computes the same bits as the scalar one.
    both = compass_to_yaw(np.array([raw, initial]), initial_deg=initial)
    assert both[0] == yaw and math.copysign(1.0, both[0]) == math.copysign(1.0, yaw)
    assert both[1] == 0.0 and math.copysign(1.0, both[1]) == 1.0  # +0.0, never -0.0


def test_a_reading_a_hair_below_a_multiple_of_360_is_yaw_plus_zero() -> None:
    # The readings whose reduced value is 360 itself: the yaw is +0.0 (not -0.0, not 2π).
    for raw in (-1e-20, -5e-324, -1e-300, -1e-14):
        assert np.mod(raw, 360.0) == 360.0
        yaw = compass_to_yaw(raw)
        assert yaw == 0.0 and math.copysign(1.0, yaw) == 1.0
        # ... with the initial heading reduced to 360 too, or instead.
        assert compass_to_yaw(0.0, initial_deg=raw) == 0.0
        assert compass_to_yaw(raw, initial_deg=raw) == 0.0
