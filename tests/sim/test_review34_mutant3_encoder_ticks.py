"""Wheel encoder ticks on and beside their boundaries (review 34, mutation testing of _sensors).

The class's rule: a counter reads the largest ``k`` whose boundary angle
``(k / ticks_per_rev) * (2 * math.pi)`` (each operation rounded in float64) is
at most the angle, then modulo ``2**bits`` (unsigned) below 64 bits. The oracle
here searches ``k`` directly by that rule in Python integers, on angles that
sit exactly on a boundary, one float below and one above it, for whole and
fractional ``ticks_per_rev`` and both signs; the modulo is Python's ``%``.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from navkit.sim import EncoderReading, WheelEncoders

_TWO_PI = 2.0 * math.pi


def _rule(angle: float, tpr: float) -> int:
    """Largest k with (k / tpr) * 2π <= angle, found by a search around the estimate."""
    k = math.floor(angle / _TWO_PI * tpr) + 3
    while (k / tpr) * _TWO_PI > angle:
        k -= 1
    return k


def _angles(tpr: float, rng: np.random.Generator) -> list[float]:
    out = []
    for k in [*rng.integers(-(10**6), 10**6, 40).tolist(), 0, 1, -1, int(tpr), -int(tpr)]:
        b = (int(k) / tpr) * _TWO_PI  # a boundary, as the rule rounds it
        out += [b, math.nextafter(b, -math.inf), math.nextafter(b, math.inf)]
    out += list(rng.uniform(-1e5, 1e5, 30))
    return out


@pytest.mark.parametrize("tpr", [1024.0, 1000.7, 1.0, 4096.0, 3.3])
@pytest.mark.parametrize("bits", [None, 2, 16, 63, 64])
def test_ticks_follow_the_boundary_rule(tpr: float, bits: int | None) -> None:
    rng = np.random.default_rng(int(tpr * 10) + (bits or 0))
    angles = _angles(tpr, rng)
    got = WheelEncoders(ticks_per_rev=tpr, bits=bits).ticks(np.array(angles))
    assert got.dtype == np.int64
    for a, g in zip(angles, got.tolist(), strict=True):
        k = _rule(a, tpr)
        if bits is None or bits == 64:
            assert g == k, (a, tpr)
        else:
            assert g == k % (1 << bits), (a, tpr, bits)


def test_an_encoder_reading_holds_a_read_only_int64_copy() -> None:
    source = np.array([10, -3], dtype=np.int32)
    reading = EncoderReading(0.02, source)
    assert reading.ticks.dtype == np.int64
    assert not reading.ticks.flags.writeable
    source[0] = 99  # the caller's array stays the caller's
    assert reading.ticks.tolist() == [10, -3]


@pytest.mark.parametrize("ticks", [np.array([1.5, 2.0]), np.array([True, False]), [1.0, 2.0]])
def test_an_encoder_reading_refuses_ticks_that_are_not_integers(ticks: object) -> None:
    with pytest.raises(TypeError, match="ticks"):
        EncoderReading(0.02, ticks)  # type: ignore[arg-type]


def test_an_older_pickle_of_an_encoder_reading_loads_read_only() -> None:
    # What unpickling a slotted dataclass pickled before ``__reduce__`` does: a bare
    # instance, then BUILD, which calls __setstate__ with the field values in order.
    reading = EncoderReading.__new__(EncoderReading)
    reading.__setstate__([0.25, np.array([7, -2], dtype=np.int64)])
    assert reading.stamp == 0.25
    assert reading.ticks.tolist() == [7, -2]
    assert not reading.ticks.flags.writeable
