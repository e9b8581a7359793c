"""``DiffDrive.forward`` on a slow turn with close but unequal radii (review 33, mutants).

For radii within 1/64 of each other ``forward`` takes the turn rate from the sum
and difference of the wheel speeds with a correction by the radii's difference,
not from the difference of the rounded products ``wr*Rr - wl*Rl``, which cancel
on a slow turn. The mutant that never took that branch passed the suite: on the
pinned slow turns below its turn rate was 1e-10 to 3e-10 off (relative), the
branch's is at most 2.5e-12 off. Oracle: the twist in exact rational arithmetic
on the float inputs. Checked: fails on that mutant of ``_diff.py`` (if-guard of
the close-radii branch never taken), passes on HEAD.
"""

from __future__ import annotations

from fractions import Fraction

import pytest

from navkit.kinematics import DiffDrive

_LEFT, _RIGHT, _TRACK = 0.05, 0.0501, 0.3


def _exact_omega(left: float, right: float) -> Fraction:
    return (Fraction(right) * Fraction(_RIGHT) - Fraction(left) * Fraction(_LEFT)) / Fraction(
        _TRACK
    )


@pytest.mark.parametrize(
    ("left", "right"), [(10.02, 10.000001), (-10.02, -10.000001), (1.002, 1.0000001)]
)
def test_a_slow_turn_keeps_its_turn_rate(left: float, right: float) -> None:
    drive = DiffDrive(track=_TRACK, left_radius=_LEFT, right_radius=_RIGHT)
    exact = _exact_omega(left, right)
    assert 1e-8 < abs(exact) < 1e-6  # a slow turn: products cancel to 7 digits
    omega = drive.forward([left, right]).omega
    assert abs(Fraction(omega) - exact) <= Fraction(1, 10**11) * abs(exact)
