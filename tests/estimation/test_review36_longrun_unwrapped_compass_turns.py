"""The unwrapped compass yaw over very many turns, against the exact value (reviews 36, 53).

``compass_to_yaw(unwrap=True)`` and ``CompassCalibration(unwrap=True)`` summed their
2π corrections as :func:`numpy.unwrap` does, a running float sum that rounds: a
robot turning on the spot for days ended its unwrapped yaw off the exact multiple
of 2π, 59 ulps after 10^4 turns and about 1e-5 rad after 10^6 (review 36
documented it). They count whole turns as integers now (review 53, FOUND6): the
yaw is within 1.61 ulps of the exact value (half an ulp of k·2π's rounding, a
whole ulp of the yaw where k·2π is past a power of two the yaw is not, half an ulp
of the sum's, and k times 2π's own error, 2.45e-16, at most 0.36 ulp; review 53's
FRESH3 corrected the bound, exceeded at k = -41), computed here with integers (the
turns) and a 40-digit π.
"""

from __future__ import annotations

from decimal import Decimal, getcontext

import numpy as np
import pytest

from navkit.estimation import CompassCalibration, compass_to_yaw
from navkit.geometry import wrap_angle

# 40 digits of π: the exact yaw -2π·n is then known far below a float's spacing.
PI = Decimal("3.141592653589793238462643383279502884197")


def _readings(turns: int) -> np.ndarray:
    """Four readings a clockwise turn (0°, 100°, 200°, 300°), ``turns`` times, then 0°."""
    return np.append(np.tile([0.0, 100.0, 200.0, 300.0], turns), 0.0)


@pytest.mark.parametrize("turns", [1, 7, 10**4, 10**6])
def test_the_unwrapped_yaw_is_within_161_hundredths_of_an_ulp_of_the_exact_one(turns: int) -> None:
    getcontext().prec = 50
    raw = _readings(turns)
    whole = compass_to_yaw(raw, unwrap=True)
    cal = CompassCalibration(unwrap=True)
    pieces = np.concatenate([cal(raw[i : i + 4099]) for i in range(0, raw.size, 4099)])
    np.testing.assert_array_equal(pieces, whole)  # in pieces as at once, rounding included
    exact = -2 * PI * turns  # clockwise turns: the yaw decreases
    drift = abs(Decimal(float(whole[-1])) - exact)
    ulp = float(np.spacing(abs(whole[-1])))
    assert drift <= Decimal(1.61 * ulp)
    # Every reading's yaw, not only the last: its wrapped yaw plus 2π times a whole
    # number of turns, within 1.61 ulps (a wrong count would be 2π off).
    wrapped = compass_to_yaw(raw)
    check = np.unique(np.r_[np.linspace(0, raw.size - 1, 50).astype(int), raw.size - 1])
    for i in check:
        count = round((float(whole[i]) - float(wrapped[i])) / (2 * np.pi))
        exact_i = Decimal(float(wrapped[i])) + 2 * PI * count
        bound = Decimal(1.61 * float(np.spacing(abs(whole[i]))))
        assert abs(Decimal(float(whole[i])) - exact_i) <= bound
    # Wrapped, the heading is back at 0 to within those ulps.
    assert abs(wrap_angle(float(whole[-1]))) <= 4 * ulp
