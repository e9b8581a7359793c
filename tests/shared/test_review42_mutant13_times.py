"""Times float64 would round are refused at their exact bounds (review 42, MUTANT13).

A mutation review of ``navkit._shared.times`` found these mutants passing every
test: the 1 ms resolution doubled (float32 times in [2**14, 2**15) s, 1.95 ms
coarse, accepted), integers refused from 2**53 itself (exact in float64), a 0-d
array not unwrapped (a 0-d integer array of nanoseconds read as seconds), an
integer array refused only when it also held a value below -2**53, an object
array never looked at, the ROS 1 and rclpy hints given for an object with one of
their two attributes, and the huge-integer message's decimal exponent computed
with the wrong logarithm. Each test here fails with one of them and passes on
the real code; the bounds come from the rule as documented (float64 holds every
integer up to 2**53; a time must resolve 1 ms), not from the code.
"""

from __future__ import annotations

from types import SimpleNamespace
from typing import Any

import numpy as np
import pytest

from navkit._shared.times import as_time, as_times

EXACT = 2**53


def _first_coarse(dtype: type[np.floating[Any]]) -> np.floating[Any]:
    """The smallest positive ``dtype`` value whose float step exceeds 1 ms, found by doubling."""
    value = dtype(1.0)
    while float(np.spacing(value)) < 1e-3:
        value = dtype(value * 2)
    return value


@pytest.mark.parametrize("dtype", [np.float32, np.float16])
def test_a_low_precision_time_is_refused_from_the_first_step_coarser_than_a_millisecond(
    dtype: type[np.floating[Any]],
) -> None:
    at = _first_coarse(dtype)
    below = np.nextafter(at, dtype(0))
    # float32 from 2**14 s on (as the module says), float16 from 2 s: steps are powers
    # of two, 2**-10 s (0.98 ms) below the bound, 2**-9 s (1.95 ms) from it.
    assert float(at) == {np.float32: 2.0**14, np.float16: 2.0}[dtype]
    assert float(np.spacing(below)) == 2.0**-10 and float(np.spacing(at)) == 2.0**-9
    for sign in (1, -1):
        assert as_time(dtype(sign * below), "t") == sign * float(below)
        assert as_time(np.array(sign * below, dtype=dtype), "t") == sign * float(below)
        with pytest.raises(ValueError, match=r"^t must resolve time to 1 ms, got the "):
            as_time(dtype(sign * at), "t")
        # A 0-d array is looked at as its scalar.
        with pytest.raises(ValueError, match=r"^t must resolve time to 1 ms, got the "):
            as_time(np.array(sign * at, dtype=dtype), "t")
    times = np.array([-below, 0.0, below], dtype=dtype)
    assert as_times(times, "t").tolist() == [-float(below), 0.0, float(below)]
    with pytest.raises(ValueError, match=r"^t, element 1, must resolve time to 1 ms"):
        as_times(np.array([below, at], dtype=dtype), "t")


@pytest.mark.parametrize("sign", [1, -1])
def test_integers_are_taken_up_to_2_53_and_refused_beyond(sign: int) -> None:
    # 2**53 is exact in float64; 2**53 + 1 is the first integer it rounds.
    assert as_time(sign * EXACT, "t") == sign * float(EXACT)
    assert as_time(np.int64(sign * EXACT), "t") == sign * float(EXACT)
    assert as_time(np.array(sign * EXACT), "t") == sign * float(EXACT)
    for value in (sign * (EXACT + 1), np.int64(sign * (EXACT + 1)), np.array(sign * (EXACT + 1))):
        with pytest.raises(ValueError, match=r"^t must be a time in seconds, got the integer -?9"):
            as_time(value, "t")
    assert as_times(np.array([0, sign * EXACT]), "t").tolist() == [0.0, sign * float(EXACT)]
    assert as_times([0.5, sign * EXACT], "t").tolist() == [0.5, sign * float(EXACT)]
    # An array with one value beyond on one side only: each side is refused alone.
    for times in (
        np.array([0, sign * (EXACT + 1)]),
        np.array([0, sign * (EXACT + 1)], dtype=np.uint64 if sign > 0 else np.int64),
        np.array([0, sign * (EXACT + 1)], dtype=object),
        [0.5, sign * (EXACT + 1)],
    ):
        with pytest.raises(ValueError, match=r"^t, element 1, must be a time in seconds"):
            as_times(times, "t")


def test_an_object_array_of_times_is_looked_at_item_by_item() -> None:
    # An object array converts to float64 without a word, rounding 2**60 ns to seconds.
    times = np.array([1.5, 2**60, 3], dtype=object)
    with pytest.raises(ValueError, match=r"^t, element 1, .* 1152921504606846976, beyond 2\*\*53"):
        as_times(times, "t")
    assert as_times(np.array([1.5, EXACT, 3], dtype=object), "t").tolist() == [1.5, EXACT, 3.0]


def test_a_huge_integer_is_shown_whole_below_10_100_and_by_its_exponent_from_there() -> None:
    with pytest.raises(ValueError, match=rf"got the integer {10**100 - 1}, beyond 2\*\*53"):
        as_time(10**100 - 1, "t")
    for exponent in (100, 150, 400):
        for value in (10**exponent, -(10**exponent)):
            with pytest.raises(ValueError, match=rf"got the integer of about 10\*\*{exponent}, "):
                as_time(value, "t")


@pytest.mark.parametrize(
    "value",
    [
        SimpleNamespace(secs=1),
        SimpleNamespace(nsecs=1),
        SimpleNamespace(nanoseconds=1),
        SimpleNamespace(seconds_nanoseconds=lambda: (0, 1)),
        SimpleNamespace(nanosec=1),
    ],
)
def test_an_object_with_one_of_a_stamps_two_attributes_gets_no_stamp_hint(value: Any) -> None:
    with pytest.raises(TypeError, match=r"^t must be a real number, got SimpleNamespace$"):
        as_time(value, "t")
