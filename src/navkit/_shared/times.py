"""Private checks of times, s: what float64 would round is refused, not read.

Shared by every reader and filter that takes time stamps (``PlanarFusion``,
``MeasurementLog``, ``FusionResult``, the bag and CARMEN records), so that an
integer nanosecond stamp or a float32 epoch stamp gets the same message wherever
it is passed.
"""

from __future__ import annotations

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


def time_error(value: Any, name: str) -> ValueError | None:
    """The error for a time ``value`` (a number) that float64 would not hold as given."""
    if isinstance(value, np.ndarray) and value.ndim == 0:
        value = value[()]
    if isinstance(value, (bool, np.bool_)):
        return None  # refused as a non-number by the caller's checks
    if isinstance(value, numbers.Integral):
        if abs(int(value)) > EXACT_INTEGERS:
            return ValueError(
                f"{name} must be a time in seconds, got the integer {value}, beyond 2**53 "
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
    return None


def as_time(value: Any, name: str) -> float:
    """A time, s, as a finite float (:func:`finite_float`), refusing what float64 would round."""
    error = time_error(value, name)
    if error is not None:
        raise error
    return finite_float(value, name)


def as_times(value: Any, name: str) -> FloatArray:
    """Times, s, shape (T,), as a float64 array, refusing what float64 would round (``as_time``)."""
    times = as_float_array(value, name, ndim=1)
    if isinstance(value, (list, tuple)):
        # Python floats (the common case) need no look; NumPy would round an integer
        # beyond 2**53 in a list with floats into a float64 array unseen.
        items: Any = () if all(type(v) is float for v in value) else value
    else:
        raw = np.asarray(value)
        kind = raw.dtype.kind
        if kind in "iu":
            items = raw if np.any(raw > EXACT_INTEGERS) or np.any(raw < -EXACT_INTEGERS) else ()
        elif raw.dtype in (np.float16, np.float32):
            items = raw if np.any(np.spacing(np.abs(raw)) > TIME_RESOLUTION) else ()
        else:
            items = raw if kind == "O" else ()
    for i, item in enumerate(items):
        error = time_error(item, f"{name}, element {i},")
        if error is not None:
            raise error
    return times
