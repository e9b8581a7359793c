"""``DiffDrive.inverse`` where exactly one wheel speed is beyond float64 (review 33, mutants).

``inverse`` retries an overflowing twist at a scale of 2⁻⁴⁸ and refuses it if a
wheel speed is still infinite. The mutant ``or`` for ``and`` in that last
finiteness test raised only when both wheel speeds overflowed: a twist whose
left wheel stands still while the right wheel would spin at 2e308 rad/s came
back as ``[0.0, inf]``. Oracle: the wheel speeds in exact rational arithmetic on
the float inputs (beyond the largest float, or exactly representable).
Checked: fails on that mutant of ``_diff.py``, passes on HEAD.
"""

from __future__ import annotations

import sys
from fractions import Fraction

import numpy as np
import pytest

from navkit.kinematics import DiffDrive

_MAX = Fraction(sys.float_info.max)


def _exact_wheels(track: float, radius: float, vx: float, omega: float) -> list[Fraction]:
    half = Fraction(omega) * Fraction(track) / 2
    r = Fraction(radius)
    return [(Fraction(vx) - half) / r, (Fraction(vx) + half) / r]


@pytest.mark.parametrize(("vx", "omega", "beyond"), [(1e302, 2e302, 1), (1e302, -2e302, 0)])
def test_one_wheel_beyond_float64_is_refused(vx: float, omega: float, beyond: int) -> None:
    exact = _exact_wheels(1.0, 1e-6, vx, omega)
    assert abs(exact[beyond]) > _MAX  # the oracle: that wheel's speed is no float
    assert abs(exact[1 - beyond]) == 0  # and the other stands still
    drive = DiffDrive(track=1.0, wheel_radius=1e-6)
    with pytest.raises(ValueError, match=r"^twist: the wheel speeds would overflow float64"):
        drive.inverse([vx, 0.0, omega])


def test_the_batch_refuses_the_same_twist() -> None:
    drive = DiffDrive(track=1.0, wheel_radius=1e-6)
    with pytest.raises(ValueError, match=r"^twists: the wheel speeds would overflow float64"):
        drive.inverse_batch(np.array([[1e302, 0.0, 2e302]]))
