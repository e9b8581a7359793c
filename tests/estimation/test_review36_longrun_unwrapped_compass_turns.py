"""The unwrapped compass yaw over very many turns: the rounding the docstrings give (review 36).

``compass_to_yaw(unwrap=True)`` and ``CompassCalibration(unwrap=True)`` sum their 2π
corrections as :func:`numpy.unwrap` does (bit for bit, which their tests pin), and
that running float sum rounds: a robot turning on the spot for days ends its
unwrapped yaw off the exact multiple of 2π. The docstrings now give the size (about
1e-8 rad after 10^4 turns, 1e-5 rad after 10^6); this checks those figures against
the exact value, computed with integers (the turns) and a 40-digit π.
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


@pytest.mark.parametrize(("turns", "bound"), [(10**4, 2e-8), (10**6, 2e-5)])
def test_the_unwrapped_yaw_after_many_turns_is_within_the_documented_rounding(
    turns: int, bound: float
) -> None:
    getcontext().prec = 50
    raw = _readings(turns)
    whole = compass_to_yaw(raw, unwrap=True)
    cal = CompassCalibration(unwrap=True)
    pieces = np.concatenate([cal(raw[i : i + 4099]) for i in range(0, raw.size, 4099)])
    np.testing.assert_array_equal(pieces, whole)  # in pieces as at once, rounding included
    exact = -2 * PI * turns  # clockwise turns: the yaw decreases
    drift = abs(Decimal(float(whole[-1])) - exact)
    assert drift < Decimal(bound)
    # Wrapped, the heading is back at 0 to within that drift.
    assert abs(wrap_angle(float(whole[-1]))) < bound
