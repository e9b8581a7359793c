"""A numpy.datetime64 passed as a time: the hint gives the correctly rounded seconds (review 54).

Review 36 made a ``datetime64`` given where navkit takes seconds say what to pass,
``(value - np.datetime64(0, 's')) / np.timedelta64(1, 's')``. NumPy divides the
count of nanoseconds as a float, rounded to a multiple of 256 ns first at epoch
stamps (1.7e18 ns), so for a nanosecond stamp those seconds were a float off
(2.4e-7 s) about one time in four, as review 52 found of the rclpy hint. The hint
now splits the nanoseconds into seconds and the rest, ``sec + nsec * 1e-9`` as the
bag readers compute a stamp: the float nearest the stamp. An *array* of
``datetime64`` (what pandas gives for a bag's stamps) was refused as "must hold
real numbers, got dtype datetime64[ns]" with no hint at all; it gets the same one,
and an array of ``timedelta64`` the timedelta's. A naive ``datetime`` was told
``value.timestamp()``, which reads it as the machine's local time: a UTC one (what
``datetime.utcfromtimestamp`` gave) came out hours off; the hint now says how to
read it as UTC. Each hint is run as written.
"""

from __future__ import annotations

import datetime
from fractions import Fraction
from typing import Any

import numpy as np
import pytest

from navkit.estimation import MeasurementLog, PlanarFusion


def _run_hint(message: str, marker: str, value: Any) -> Any:
    """The code after ``marker`` in ``message``, run with ``value`` bound: its last expression."""
    code = message.split(marker, 1)[1].split("; ")
    namespace: dict[str, Any] = {"value": value, "np": np}
    for statement in code[:-1]:
        exec(statement, namespace)
    return eval(code[-1], namespace)


def _refusal(t: Any) -> str:
    with pytest.raises(TypeError, match=r"^t must be a time in seconds \(a real number\)") as info:
        PlanarFusion().update_yaw(t, 0.0, variance=1.0)
    return str(info.value)


def test_a_nanosecond_stamp_the_old_hint_put_a_float_off() -> None:
    ns = 1_733_400_000_250_000_003
    stamp = np.datetime64(ns, "ns")
    old = (stamp - np.datetime64(0, "s")) / np.timedelta64(1, "s")
    assert float(old) == 1733400000.2500002  # a float above the stamp
    seconds = _run_hint(_refusal(stamp), "pass seconds since the epoch: ", stamp)
    assert float(seconds) == float(Fraction(ns, 10**9)) == 1733400000.25
    fusion = PlanarFusion()
    fusion.update_yaw(seconds, 0.0, variance=1.0)
    assert fusion.t == 1733400000.25


@pytest.mark.parametrize("unit", ["ns", "us", "ms", "s"])
def test_the_hint_gives_the_nearest_float_to_every_epoch_stamp(unit: str) -> None:
    rng = np.random.default_rng(54)
    ns = rng.integers(1_000_000_000 * 10**9, 4_000_000_000 * 10**9, 2000)
    stamps = ns.astype("datetime64[ns]").astype(f"datetime64[{unit}]")
    hint = _refusal(stamps[0])
    for stamp in stamps:
        exact = Fraction(int(stamp.astype("datetime64[ns]").astype(np.int64)), 10**9)
        assert float(_run_hint(hint, "pass seconds since the epoch: ", stamp)) == float(exact)


def test_an_array_of_datetime64_gets_the_hint_and_it_works() -> None:
    ns = np.array([1_733_400_000_250_000_003, 1_733_400_000_260_000_003], dtype=np.int64)
    stamps = ns.astype("datetime64[ns]")
    with pytest.raises(
        TypeError,
        match=r"^yaw\[0\] \(times\) must hold real numbers, got dtype datetime64\[ns\]: "
        r"pass seconds since the epoch: ",
    ) as info:
        MeasurementLog.from_streams(yaw=(stamps, np.zeros(2)))
    seconds = _run_hint(str(info.value), "pass seconds since the epoch: ", stamps)
    log = MeasurementLog.from_streams(yaw=(seconds, np.zeros(2)))
    assert log.times.tolist() == [float(Fraction(int(n), 10**9)) for n in ns]


def test_an_array_of_timedelta64_gets_the_timedelta_hint_and_it_works() -> None:
    since_start = np.array([0, 5, 10], dtype="timedelta64[ms]")
    with pytest.raises(
        TypeError, match=r"^yaw\[0\] \(times\) must hold real numbers, got dtype timedelta64"
    ) as info:
        MeasurementLog.from_streams(yaw=(since_start, np.zeros(3)))
    seconds = _run_hint(str(info.value), "pass seconds: ", since_start)
    assert MeasurementLog.from_streams(yaw=(seconds, np.zeros(3))).times.tolist() == [
        0.0,
        0.005,
        0.01,
    ]


def test_other_arrays_keep_the_plain_refusal() -> None:
    with pytest.raises(TypeError, match=r"must hold real numbers, got dtype <U3$"):
        MeasurementLog.from_streams(yaw=(np.array(["1.0", "2.0"]), np.zeros(2)))


def test_a_naive_datetime_is_told_how_to_read_it_as_utc() -> None:
    # 2024-12-05 12:00:00.25 UTC, naive (as datetime.utcfromtimestamp gave it): its
    # timestamp() is the machine's local time, hours off wherever that is not UTC.
    naive = datetime.datetime(2024, 12, 5, 12, 0, 0, 250_000)
    message = _refusal(naive)
    assert "value.timestamp() for a local time" in message
    marker = "a naive datetime in UTC: "
    code = message.split(marker, 1)[1]
    seconds = eval(code, {"value": naive, "datetime": datetime})
    assert seconds == 1733400000.25
    # An aware datetime keeps the plain hint, which is right for it.
    aware = naive.replace(tzinfo=datetime.UTC)
    message = _refusal(aware)
    assert message.endswith("pass seconds since the epoch: value.timestamp()")
    assert aware.timestamp() == 1733400000.25
