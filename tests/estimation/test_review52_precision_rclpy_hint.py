"""The rclpy ``Time`` hint gives the correctly rounded stamp (review 52, PRECISION).

A time stamp object passed where navkit takes seconds is refused with what to
pass (review 36). For an rclpy ``Time`` that was ``time.nanoseconds * 1e-9``: an
epoch count of nanoseconds (1.78e18) is rounded to a float, 256 ns apart, before
the product, which then lands one float (2.4e-7 s) off the stamp about every
other time, where the bag readers compute ``sec + nsec * 1e-9``, correctly
rounded. The hint now says ``sec, nsec = time.seconds_nanoseconds(); sec + nsec *
1e-9``. Oracle: the stamp as an exact fraction, rounded once.
"""

from __future__ import annotations

import random
from fractions import Fraction

import pytest

from navkit.estimation import PlanarFusion


class RclpyTime:
    """The parts of ``rclpy.time.Time`` the hint reads (rclpy is not installed here)."""

    def __init__(self, nanoseconds: int) -> None:
        self.nanoseconds = nanoseconds

    def seconds_nanoseconds(self) -> tuple[int, int]:
        return divmod(self.nanoseconds, 10**9)


def _hinted(time: RclpyTime) -> float:
    """The hint's expression, as a user would copy it."""
    sec, nsec = time.seconds_nanoseconds()
    return sec + nsec * 1e-9


def test_the_hint_names_the_exact_conversion() -> None:
    with pytest.raises(TypeError, match=r"sec, nsec = time\.seconds_nanoseconds\(\); "):
        PlanarFusion().predict(RclpyTime(1_780_000_000_123_456_789))  # type: ignore[arg-type]


def test_the_hinted_conversion_is_the_correctly_rounded_stamp() -> None:
    rng = random.Random(52)
    stamps = [rng.randrange(1_700_000_000 * 10**9, 1_800_000_000 * 10**9) for _ in range(2000)]
    old_off = 0
    for ns in stamps:
        exact = float(Fraction(ns, 10**9))
        assert _hinted(RclpyTime(ns)) == exact
        old_off += ns * 1e-9 != exact
    assert old_off > 500  # the old hint's product: about half of them a float off
