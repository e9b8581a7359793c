"""DiffDrive.forward's close-radii branch reaches radii 1/32 apart (review 41).

Up to review 40 the branch (the twist from the sum and the difference of the
wheel speeds, corrected by the radii's difference) served radii at most 1/64
apart (half their difference over their mean); radii 1/64 to 1/32 apart, a
worn or mis-sized tyre of 3-6 %, took the difference of rounded products, whose
error is a few ulps of the products rather than of the difference they leave.
Review 40 (MUTANT11) measured the branch more accurate there; review 41 moved
the bound. Oracle: the twist in exact rational arithmetic on the float inputs,
against the scale a correctly rounded evaluation of ``wr - wl`` and ``wr + wl``
answers to: ``(|r - l| mean + |r + l| |half_diff|)`` (over the track for the turn
rate). The products' difference misses it by up to 13 of those ulps on slow
turns and spot turns; the branch stays within 2 (its roundings: the mean's, two
products', the sum's and the division's, about 1.5 ulps in all, the difference
and ``half_diff`` being exact by Sterbenz where the component cancels).
"""

from __future__ import annotations

from fractions import Fraction

from hypothesis import example, given, settings
from hypothesis import strategies as st

from navkit.kinematics import DiffDrive

_EPS = 2.0**-52


def _worst_ulps(
    left_radius: float, right_radius: float, track: float, left: float, right: float
) -> float:
    """The larger of vx's and omega's error in ulps of their scale."""
    twist = DiffDrive(track=track, left_radius=left_radius, right_radius=right_radius).forward(
        [left, right]
    )
    wl = Fraction(left) * Fraction(left_radius)
    wr = Fraction(right) * Fraction(right_radius)
    mean = 0.5 * right_radius + 0.5 * left_radius
    half_diff = abs(0.5 * right_radius - 0.5 * left_radius)
    scale_v = abs(right + left) * mean + abs(right - left) * half_diff
    scale_w = (abs(right - left) * mean + abs(right + left) * half_diff) / track
    err_v = abs(Fraction(twist.vx) - (wr + wl) / 2) / Fraction(_EPS * scale_v)
    err_w = abs(Fraction(twist.omega) - (wr - wl) / Fraction(track)) / Fraction(_EPS * scale_w)
    return float(max(err_v, err_w))


@settings(max_examples=200, deadline=None)
@given(
    left_radius=st.floats(0.02, 0.2),
    apart=st.floats(1 / 64, 1 / 32),
    wider_right=st.booleans(),
    track=st.floats(0.1, 1.0),
    left=st.floats(-10.0, 10.0).filter(lambda x: abs(x) > 1e-3),
    relative=st.floats(-1e-6, 1e-6),
    spot=st.booleans(),
)
@example(  # radii 2.4 % apart, a slow turn: 12.9 ulps by the products' difference
    left_radius=0.05, apart=0.024, wider_right=True, track=0.3, left=7.25,
    relative=3e-7, spot=False,
)  # fmt: skip
def test_radii_up_to_1_32_apart_keep_the_twist_to_two_ulps_of_its_scale(
    left_radius: float,
    apart: float,
    wider_right: bool,
    track: float,
    left: float,
    relative: float,
    spot: bool,
) -> None:
    # half_diff / mean = apart: the right radius from the left one.
    factor = (1 + apart) / (1 - apart) if wider_right else (1 - apart) / (1 + apart)
    right_radius = left_radius * factor
    # Nearly straight (wr ~ wl) or nearly on the spot (wr ~ -wl): where one of
    # the two components cancels.
    right = (-1.0 if spot else 1.0) * left * left_radius / right_radius * (1.0 + relative)
    assert _worst_ulps(left_radius, right_radius, track, left, right) <= 2.0


def test_the_bound_is_inclusive_at_1_32() -> None:
    # Dyadic radii exactly 1/32 apart (half their difference is 1/32 of their
    # mean): the branch, whose slow turn keeps its rate to 2 ulps of its scale
    # (the products' difference: 3.4 ulps at left = 7.3).
    worst = max(
        _worst_ulps(31 / 1024, 33 / 1024, 0.3, left, left * 31 / 33 * (1 + 1e-7 * k))
        for k, left in enumerate([0.75, -3.5, 9.125, 1.0625, -6.25, 7.3], start=1)
    )
    assert worst <= 2.0
