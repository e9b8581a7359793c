"""Private checks of times, s: what float64 would round is refused, not read.

Shared by every reader and filter that takes time stamps (``PlanarFusion``,
``MeasurementLog``, ``FusionResult``, the bag and CARMEN records), so that an
integer nanosecond stamp or a float32 epoch stamp gets the same message wherever
it is passed.
"""

from __future__ import annotations

import datetime
import math
import numbers
from typing import Any

import numpy as np

from navkit._shared.types import FloatArray
from navkit._shared.validation import as_float_array, finite_float

# Times float64 cannot take as given are refused rather than silently rounded:
# integers beyond 2**53 (float64 rounds them: epoch nanoseconds, 1.7e18, are such
# integers, and would be read as seconds) and float16 / float32 times coarser than
# 1 ms, the period of a 1 kHz IMU (float32 from 2**14 s on; an epoch stamp in
# float32 is 128 s coarse, and every dt between such stamps 0 or 128 s).
EXACT_INTEGERS = 2**53
TIME_RESOLUTION = 1e-3

# What to pass for a numpy.datetime64 (or an array of them, as pandas gives a bag's
# stamps): its nanoseconds split into seconds and the rest, the correctly rounded
# stamp, as the bag readers compute one. Not ``(value - np.datetime64(0, 's')) /
# np.timedelta64(1, 's')``, the hint before: NumPy divides the count of nanoseconds
# as a float, rounded to a multiple of 256 ns first at epoch stamps (1.7e18 ns), and
# the seconds were a float off (2.4e-7 s) for 27 % of nanosecond stamps (1733400000.25
# s and 3 ns read 1733400000.2500002; review 54, FARWORLD).
DATETIME64_HINT = (
    "pass seconds since the epoch: ns = value.astype('datetime64[ns]').astype(np.int64); "
    "ns // 10**9 + ns % 10**9 * 1e-9"
)


#: Types of list items that float64 holds as given, and integer types to compare.
_PLAIN = frozenset({float, np.float64})
_INTEGERS = frozenset({int, np.int8, np.int16, np.int32, np.int64, np.uint8, np.uint16,
                       np.uint32, np.uint64})  # fmt: skip


def time_error(value: Any, name: str) -> Exception | None:
    """The error for a time ``value`` (a number) that float64 would not hold as given."""
    if issubclass(type(value), np.ndarray) and value.ndim == 0:
        value = value[()]
    if isinstance(value, (bool, np.bool_)):
        return None  # refused as a non-number by the caller's checks
    if isinstance(value, np.timedelta64):
        # NumPy registers it as an integer: its count of units is not seconds.
        return TypeError(
            f"{name} must be a time in seconds (a real number), got numpy.timedelta64 "
            f"{value!s}: pass it as seconds, e.g. value / np.timedelta64(1, 's')"
        )
    if isinstance(value, numbers.Integral):
        integer = int(value)
        if abs(integer) > EXACT_INTEGERS:
            digits = len(str(abs(integer))) if abs(integer) < 10**100 else None
            shown = str(integer) if digits is not None else f"of about 10**{_log10(integer)}"
            return ValueError(
                f"{name} must be a time in seconds, got the integer {shown}, beyond 2**53 "
                "where float64 rounds integers (a nanosecond stamp? pass seconds: "
                "sec + nanosec * 1e-9)"
            )
    elif isinstance(value, (np.float16, np.float32)) and np.isfinite(value):
        step = float(np.spacing(np.abs(value)))
        if step > TIME_RESOLUTION:
            return ValueError(
                f"{name} must resolve time to 1 ms, got the {value.dtype} time {value} s, "
                f"{step:g} s coarse: keep time stamps in float64 (float32 rounds an epoch "
                "stamp, 1.7e9 s, to 128 s)"
            )
    elif not isinstance(value, numbers.Real):
        hint = _stamp_hint(value)
        if hint is not None:
            return TypeError(
                f"{name} must be a time in seconds (a real number), got "
                f"{type(value).__name__}: {hint}"
            )
    return None


def _stamp_hint(value: object) -> str | None:
    """What to pass instead of a time stamp object (a ROS stamp, a datetime), if it is one.

    Told by attributes, not types: navkit imports neither rclpy nor rospy.
    """
    if isinstance(value, np.datetime64):
        return DATETIME64_HINT
    if isinstance(value, datetime.datetime):
        if value.utcoffset() is None:
            # timestamp() reads a naive datetime as the machine's local time: a UTC
            # one (utcfromtimestamp's, a naive pandas stamp's) came out hours off
            # where the machine's clock is not on UTC (review 54, FARWORLD).
            return (
                "pass seconds since the epoch: value.timestamp() for a local time; "
                "a naive datetime in UTC: value.replace(tzinfo=datetime.UTC).timestamp()"
            )
        return "pass seconds since the epoch: value.timestamp()"
    if isinstance(value, datetime.timedelta):
        return "pass seconds: value.total_seconds()"
    try:
        if hasattr(value, "sec") and hasattr(value, "nanosec"):
            # builtin_interfaces/msg/Time (ROS 2), as in a message's header.stamp.
            return "a ROS 2 stamp? pass seconds: stamp.sec + stamp.nanosec * 1e-9"
        if hasattr(value, "secs") and hasattr(value, "nsecs"):
            return "a ROS 1 stamp? pass seconds: stamp.to_sec()"
        if hasattr(value, "nanoseconds") and hasattr(value, "seconds_nanoseconds"):
            # Not time.nanoseconds * 1e-9: an epoch count of nanoseconds (1.78e18) is
            # rounded to a float (256 ns apart) before the product, which then lands
            # a float off (2.4e-7 s) about every other stamp; sec + nsec * 1e-9 is
            # the correctly rounded stamp, as the bag readers compute it.
            return (
                "an rclpy Time? pass seconds: "
                "sec, nsec = time.seconds_nanoseconds(); sec + nsec * 1e-9"
            )
    except Exception:  # an attribute that raises: no hint, the caller's error stands
        return None
    return None


def _log10(integer: int) -> int:
    """The decimal exponent of a huge ``integer`` (its digit count less one)."""
    return int(abs(integer).bit_length() * math.log10(2))


def as_time(value: Any, name: str) -> float:
    """A time, s, as a finite float (:func:`finite_float`), refusing what float64 would round."""
    # A plain float is float64 already, which time_error never refuses; its isinstance
    # tests (numbers.Integral is an ABC) cost a filter's online step about 0.35 us.
    if type(value) is float and math.isfinite(value):
        return value
    error = time_error(value, name)
    if error is not None:
        raise error
    return finite_float(value, name)


def as_times(value: Any, name: str) -> FloatArray:
    """Times, s, shape (T,), as a float64 array, refusing what float64 would round (``as_time``)."""
    if isinstance(value, (list, tuple)):
        if not set(map(type, value)) <= _PLAIN:
            # NumPy would round an integer beyond 2**53 among floats into a float64
            # array unseen, and read a timedelta64 as its count: such items are
            # looked at one by one (floats and exact integers at a type check's cost).
            _refuse_items(value, name)
        return as_float_array(value, name, ndim=1)
    try:
        times = as_float_array(value, name, ndim=1)
    except TypeError as error:
        hint = _array_hint(value)
        if hint is None:
            raise
        # An array of datetime64 / timedelta64 (pandas' stamps): the way to seconds too.
        raise TypeError(f"{error}: {hint}") from None
    raw = np.asarray(value)
    if raw.dtype.kind in "iu":
        rounded = bool(np.any(raw > EXACT_INTEGERS) or np.any(raw < -EXACT_INTEGERS))
    elif raw.dtype in (np.float16, np.float32):
        rounded = bool(np.any(np.spacing(np.abs(raw)) > TIME_RESOLUTION))
    else:
        rounded = raw.dtype.kind == "O"
    if rounded:
        _refuse_items(raw, name)
    return times


def _array_hint(value: Any) -> str | None:
    """What to pass instead of an array of datetime64 or timedelta64, if it is one."""
    dtype = getattr(value, "dtype", None)
    if not isinstance(dtype, np.dtype):
        return None
    if dtype.kind == "M":
        return DATETIME64_HINT
    if dtype.kind == "m":
        return "pass seconds: value / np.timedelta64(1, 's')"
    return None


def _refuse_items(items: Any, name: str) -> None:
    """Raise :func:`time_error`'s error for the first item of ``items`` that has one."""
    for i, item in enumerate(items):
        kind = type(item)
        if kind in _PLAIN or (kind in _INTEGERS and -EXACT_INTEGERS <= item <= EXACT_INTEGERS):
            continue
        error = time_error(item, f"{name}, element {i},")
        if error is not None:
            raise error
