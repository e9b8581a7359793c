"""``DiffDrive.forward`` with very unequal radii: the products' rounding (review 33, mutants).

``forward`` uses the sum-and-difference form with a correction by the radii's
difference only for radii within 1/64 of each other: with very unequal radii its
terms are far larger than the products ``wl*Rl``, ``wr*Rr``, and so their
rounding. Two mutants of that test passed the suite and sent such drives through
it: dropping ``abs`` (any right radius smaller than the left) and ``/`` for
``*`` in ``_CLOSE_RADII * mean`` (any mean radius below about 0.1 m): on the
pinned cases below the twist was then up to 1.7e-10 of its scale off, against
4e-16 on HEAD. Oracle: the twist in exact rational arithmetic on the float
inputs; the error is measured against the twist's scale ``(|wl*Rl| + |wr*Rr|)/2``
(over ``track`` for omega). Checked: fails on both mutants of ``_diff.py``,
passes on HEAD.
"""

from __future__ import annotations

from fractions import Fraction

import pytest

from navkit.kinematics import DiffDrive

_TRACK = 0.3
_CASES = [
    (left_radius, right_radius, left, right)
    for left_radius, right_radius in [(1000.0, 0.001), (0.01, 1e-6), (1e-6, 0.01)]
    for left, right in [
        (3 * right_radius, 3 * left_radius),
        (0.7 * right_radius, 0.7000001 * left_radius),
        (3 * right_radius, -3 * left_radius),
    ]
]


@pytest.mark.parametrize(("left_radius", "right_radius", "left", "right"), _CASES)
def test_the_twist_of_very_unequal_wheels_is_accurate(
    left_radius: float, right_radius: float, left: float, right: float
) -> None:
    drive = DiffDrive(track=_TRACK, left_radius=left_radius, right_radius=right_radius)
    twist = drive.forward([left, right])
    wl, wr = Fraction(left) * Fraction(left_radius), Fraction(right) * Fraction(right_radius)
    scale = (abs(wl) + abs(wr)) / 2
    bound = Fraction(1, 10**14) * scale
    assert abs(Fraction(twist.vx) - (wl + wr) / 2) <= bound
    assert abs(Fraction(twist.omega) - (wr - wl) / Fraction(_TRACK)) <= bound / Fraction(_TRACK)
