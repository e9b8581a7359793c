"""DiffDrive.forward's close-radii branch holds up to radii 1/64 apart (the bound until review 41).

Review 39 (mutation testing, MUTANT10). Review 33 pinned slow turns with radii
0.2 % apart; ``_CLOSE_RADII`` halved (1/128) and the bound's ``<=`` read as ``<``
still passed every test, though they send radii between 1/128 and 1/64 apart (and
exactly 1/64, with dyadic radii) to the difference of rounded products, whose
turn rate on a slow turn (a millionth of the speed over the track) came out up to
1.6e-8 off (relative) where the branch's is at most 5.6e-10. Oracle: the turn
rate in exact rational arithmetic on the float inputs.
"""

from __future__ import annotations

from fractions import Fraction

import numpy as np
import pytest

from navkit.kinematics import DiffDrive


@pytest.mark.parametrize(
    ("left_radius", "right_radius"),
    [
        (0.05, 0.051),  # half their difference is 1/101 of their mean
        (0.1, 0.1025),  # 1/81
        (63 / 1024, 65 / 1024),  # 1/64 exactly: the bound until review 41 (now 1/32)
    ],
)
def test_a_slow_turn_keeps_its_turn_rate_up_to_the_bound(
    left_radius: float, right_radius: float
) -> None:
    track = 0.3
    drive = DiffDrive(track=track, left_radius=left_radius, right_radius=right_radius)
    rng = np.random.default_rng(39)
    worst = Fraction(0)
    for _ in range(200):
        left = float(rng.uniform(-20.0, 20.0))
        right = left * left_radius / right_radius * (1.0 + float(rng.normal()) * 1e-6)
        exact = Fraction(right) * Fraction(right_radius) - Fraction(left) * Fraction(left_radius)
        exact /= Fraction(track)
        if exact == 0:
            continue
        omega = drive.forward([left, right]).omega
        worst = max(worst, abs(Fraction(omega) - exact) / abs(exact))
    assert worst <= Fraction(2, 10**9)
