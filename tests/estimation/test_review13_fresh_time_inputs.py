"""Fresh-eyes review 13: time inputs the new stamp check (``navkit._shared.times``) mishandled.

``time_error`` takes every ``numbers.Integral`` as an integer number of seconds, and
NumPy registers ``np.timedelta64`` as one (it subclasses ``np.signedinteger``): a
``timedelta64`` in nanoseconds below 2**53 is read as that many seconds (as at
6f6c674), and one in seconds (or NaT) raises ``int()``'s own ``TypeError``, which
names no argument. A huge Python integer's refusal now prints all its digits (548
characters for 10**400; 6f6c674 said "an integer of about 10**400"). Each is now
refused naming the argument, a ``timedelta64`` with the way to pass seconds, and a
list of NumPy floats or of integers is checked at a type check an item (it was a
full check an item: 7-9x slower than a list of Python floats).
"""

from __future__ import annotations

import numpy as np
import pytest

from navkit.estimation import MeasurementLog, PlanarFusion


def test_a_nanosecond_timedelta_is_not_read_as_seconds() -> None:
    with pytest.raises(TypeError, match=r"^t0 must be a time in seconds.*timedelta64\(1, 's'\)"):
        PlanarFusion(t0=np.timedelta64(5, "ns"))
    with pytest.raises(
        TypeError, match=r"^odometry\[0\] \(times\), element 1, must be a time in seconds"
    ):
        MeasurementLog.from_streams(
            odometry=([0.0, np.timedelta64(5, "ns")], [1.0, 1.0], [0.0, 0.0])
        )


def test_lists_of_numpy_scalars_and_integers_are_read_as_before() -> None:
    seconds = [0.0, 0.5, 1.25]
    for items in (
        seconds,
        [np.float64(v) for v in seconds],
        [0, 1, 2],
        [np.int64(v) for v in (0, 1, 2)],
    ):
        log = MeasurementLog.from_streams(odometry=(items, [1.0] * 3, [0.0] * 3))
        assert log.times.tolist() == [float(v) for v in items]
    with pytest.raises(ValueError, match=r"^odometry\[0\] \(times\), element 2, must be a time"):
        MeasurementLog.from_streams(odometry=([0.0, 1.0, 2**53 + 1], [1.0] * 3, [0.0] * 3))


# NaT with a unit: numpy 2.5 deprecates the generic unit ``np.timedelta64("NaT")``.
@pytest.mark.parametrize("value", [np.timedelta64(5, "s"), np.timedelta64("NaT", "s")])
def test_a_timedelta_refusal_names_the_argument(value: np.timedelta64) -> None:
    with pytest.raises(TypeError, match="t0"):
        PlanarFusion(t0=value)


def test_a_huge_integer_refusal_is_short() -> None:
    with pytest.raises(ValueError, match="t0") as info:
        PlanarFusion(t0=10**400)
    assert len(str(info.value)) < 300


def test_the_refusals_the_change_made_still_hold() -> None:
    # What the change meant to refuse is refused, naming the argument.
    with pytest.raises(ValueError, match="t0 must be a time in seconds"):
        PlanarFusion(t0=np.int64(1_780_000_000_000_000_000))
    with pytest.raises(ValueError, match="t0 must resolve time to 1 ms"):
        PlanarFusion(t0=np.float32(1.78e9))
