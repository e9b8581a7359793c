"""DiffDrive.forward is accurate to a few ulps when the wheel terms cancel (exact rationals).

``omega = (wr*R - wl*R) / D`` rounded both products before subtracting them:
when driving nearly straight (or ``vx`` when turning nearly on the spot) the
result came out up to 1e9 ulps (relative 1e-7) off, e.g. ``forward([10,
10.000001])`` on ``DiffDrive(track=0.3, wheel_radius=0.05)``. With close radii the
twist is now taken from the sum and the difference of the wheel speeds, which are
exact where they cancel.
"""

from __future__ import annotations

from fractions import Fraction

import numpy as np
from hypothesis import example, given, settings
from hypothesis import strategies as st

from navkit.kinematics import DiffDrive

lengths = st.floats(1e-3, 10.0)
speeds = st.floats(-50.0, 50.0).filter(lambda v: v == 0.0 or abs(v) > 1e-200)
nudges = st.floats(-1e-6, 1e-6)


def ulps(got: float, exact: Fraction) -> float:
    if exact == 0:
        return 0.0 if got == 0.0 else float("inf")
    return float(abs(Fraction(got) - exact) / Fraction(np.spacing(abs(float(exact)))))


@settings(max_examples=60, deadline=None)
@given(lengths, lengths, speeds, nudges, st.booleans())
@example(0.3, 0.05, 10.0, 1e-7, False)
@example(0.3, 0.05, 10.0, 1e-7, True)
def test_forward_with_equal_radii_is_accurate_when_terms_cancel(
    track: float, radius: float, wl: float, nudge: float, spin: bool
) -> None:
    # Nearly straight (wr close to wl) or nearly on the spot (wr close to -wl).
    wr = (-wl if spin else wl) * (1.0 + nudge)
    drive = DiffDrive(track=track, wheel_radius=radius)
    exact_vx = (Fraction(wr) + Fraction(wl)) * Fraction(radius) / 2
    exact_omega = (Fraction(wr) - Fraction(wl)) * Fraction(radius) / Fraction(track)
    twist = drive.forward([wl, wr])
    assert ulps(twist.vx, exact_vx) <= 3.0
    assert ulps(twist.omega, exact_omega) <= 3.0
    batch = drive.forward_batch([[wl, wr]])
    np.testing.assert_array_equal(batch[0], twist.as_array())


@settings(max_examples=60, deadline=None)
@given(lengths, lengths, st.floats(-1.0 / 70.0, 1.0 / 70.0), speeds, speeds)
def test_forward_with_close_radii_stays_within_a_few_roundings(
    track: float, left: float, spread: float, wl: float, wr: float
) -> None:
    right = left * (1.0 + spread)
    drive = DiffDrive(track=track, left_radius=left, right_radius=right)
    pl, pr = Fraction(wl) * Fraction(left), Fraction(wr) * Fraction(right)
    size = abs(pl) + abs(pr)
    twist = drive.forward([wl, wr])
    # Never worse than rounding the products (a few ulps of their size).
    assert abs(Fraction(twist.vx) - (pl + pr) / 2) <= size * Fraction(1, 2**50)
    assert abs(Fraction(twist.omega) - (pr - pl) / Fraction(track)) <= (
        size / Fraction(track) * Fraction(1, 2**50)
    )
