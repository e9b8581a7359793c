"""``OmniDrive.forward`` where only a partial sum overflows (review 33, mutants).

``forward`` multiplies the wheel speeds by its forward matrix and, where a partial
sum overflowed, computes the product again at a scale where none does. The
suite's huge speeds either give a twist beyond float64 (refused before the
rescaled product is read) or none that overflows, so the mutant that read row 1
instead of row 0 of the rescaled (1, 3) product passed it: a robot spinning on
the spot at 1e303 rad/s of each wheel (wheel radius and base radius 1e6 m: terms
of 6.7e308 that cancel) raised ``IndexError``. Oracle: the product in exact
rational arithmetic on the stored forward matrix, and the closed form
``omega = r * w / L`` of turning on the spot. Checked: fails on that mutant of
``_omni.py``, passes on HEAD.
"""

from __future__ import annotations

from fractions import Fraction

import pytest

from navkit.kinematics import OmniDrive


@pytest.mark.parametrize("speed", [1e303, -1.5e303])
def test_a_finite_twist_with_overflowing_partial_sums(speed: float) -> None:
    drive = OmniDrive.three_wheel(wheel_radius=1e6, base_radius=1e6)
    speeds = [speed, speed, speed]
    matrix = drive.forward_matrix.tolist()
    assert max(abs(m * speed) for row in matrix for m in row) == float("inf")
    twist = drive.forward(speeds).as_array().tolist()
    for got, row in zip(twist, matrix, strict=True):
        terms = [Fraction(m) * Fraction(speed) for m in row]
        assert abs(Fraction(got) - sum(terms)) <= Fraction(1, 10**15) * sum(map(abs, terms))
    assert twist[2] == pytest.approx(speed, rel=1e-12)  # omega = r * w / L, r = L
