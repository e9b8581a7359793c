"""Wheel encoder helpers: tick counts to distances, counter wrap-around."""

from __future__ import annotations

import math
import operator
from collections.abc import Sequence
from typing import overload

import numpy as np
from numpy.typing import ArrayLike

from navkit._shared.types import FloatArray, IntArray, IntScalar, RealScalar
from navkit._shared.validation import as_float_array, integer_readings, refuse_masked, shown
from navkit.kinematics._ranges import (
    MAX_LENGTH,
    MAX_TICKS_PER_REV,
    MIN_LENGTH,
    MIN_TICKS_PER_REV,
    in_range,
)

__all__ = ["tick_delta", "ticks_to_distance"]


@overload
def ticks_to_distance(
    delta_ticks: RealScalar, *, ticks_per_rev: float, wheel_radius: float
) -> float: ...
@overload
def ticks_to_distance(
    delta_ticks: Sequence[float] | Sequence[Sequence[float]],
    *,
    ticks_per_rev: float,
    wheel_radius: float,
) -> FloatArray: ...
@overload
def ticks_to_distance(
    delta_ticks: ArrayLike, *, ticks_per_rev: float, wheel_radius: float
) -> float | FloatArray: ...


def ticks_to_distance(
    delta_ticks: ArrayLike, *, ticks_per_rev: float, wheel_radius: float
) -> float | FloatArray:
    """Distance rolled by a wheel: ``d = 2πR · Δticks / ticks_per_rev``.

    Parameters
    ----------
    delta_ticks : float or array_like
        Change of the encoder count (see :func:`tick_delta` for wrap-around);
        finite.
    ticks_per_rev : float
        Encoder counts per wheel revolution (after any gearing), in [1, 1e12]
        (keyword-only).
    wheel_radius : float
        Wheel radius, m, in [1e-6, 1e6] (keyword-only).

    Returns
    -------
    float or ndarray
        Distance in metres, with the sign of ``delta_ticks``.

    Raises
    ------
    TypeError
        Arguments that are not real numbers (complex numbers, strings and
        booleans are refused), naming them.
    ValueError
        Non-finite values, parameters outside their ranges, or tick counts so
        large that the distance would overflow float64.

    Examples
    --------
    >>> round(ticks_to_distance(1024, ticks_per_rev=2048, wheel_radius=0.1), 12)
    0.314159265359
    """
    res = in_range(
        ticks_per_rev, "ticks_per_rev", MIN_TICKS_PER_REV, MAX_TICKS_PER_REV, "counts per rev"
    )
    radius = in_range(wheel_radius, "wheel_radius", MIN_LENGTH, MAX_LENGTH, "m")
    ticks = as_float_array(delta_ticks, "delta_ticks")
    with np.errstate(over="ignore"):
        dist = (2.0 * math.pi * radius / res) * ticks
    if not np.isfinite(dist).all():
        raise ValueError("delta_ticks: the distance would overflow float64 (values far too large)")
    if dist.ndim == 0:
        return float(dist)
    return dist


@overload
def tick_delta(previous: IntScalar, current: IntScalar, *, bits: int) -> int: ...
@overload
def tick_delta(
    previous: Sequence[int] | Sequence[Sequence[int]], current: ArrayLike, *, bits: int
) -> IntArray: ...
@overload
def tick_delta(
    previous: ArrayLike, current: Sequence[int] | Sequence[Sequence[int]], *, bits: int
) -> IntArray: ...
@overload
def tick_delta(previous: ArrayLike, current: ArrayLike, *, bits: int) -> int | IntArray: ...


def tick_delta(previous: ArrayLike, current: ArrayLike, *, bits: int) -> int | IntArray:
    """Signed change between two readings of a wrapping ``bits``-bit encoder counter.

    The difference is taken modulo ``2**bits`` and mapped to
    ``[-2**(bits-1), 2**(bits-1))``, so a counter that wraps (65535 → 2 on a
    16-bit encoder) gives the small true step (+3). Readings may be unsigned
    (``0 .. 2**bits - 1``) or signed (``-2**(bits-1) .. 2**(bits-1) - 1``). A
    real change of half the counter range or more between two readings cannot be
    told apart from one in the other direction: read the counter often enough.

    Parameters
    ----------
    previous, current : int or array_like of int
        Consecutive counter readings (broadcast together), each within the
        range of a ``bits``-bit counter, signed or unsigned.
    bits : int
        Counter width, 2 to 64 (typically 16 or 32); keyword-only.

    Returns
    -------
    int or ndarray of int64
        ``current - previous`` corrected for wrap-around.

    Raises
    ------
    TypeError
        Readings that are not integers (floats and booleans are refused), or
        ``bits`` not an integer.
    ValueError
        Readings outside the counter's range, ``bits`` outside 2..64, or shapes
        that do not broadcast.

    Examples
    --------
    >>> tick_delta(65535, 2, bits=16)
    3
    >>> tick_delta(5, 65534, bits=16)
    -7
    """
    if isinstance(bits, (bool, np.bool_)):
        raise TypeError(f"bits must be an integer, got {shown(bits)}")
    refuse_masked(bits, "bits")  # operator.index reads a masked 0-d array's data
    try:
        nbits = operator.index(bits)
    except TypeError:
        raise TypeError(f"bits must be an integer, got {shown(bits)}") from None
    if not 2 <= nbits <= 64:
        raise ValueError(f"bits must be an integer from 2 to 64, got {shown(bits)}")
    prev = _as_counter(previous, "previous", nbits)
    cur = _as_counter(current, "current", nbits)
    try:
        np.broadcast_shapes(prev.shape, cur.shape)
    except ValueError:
        raise ValueError(
            f"previous and current must broadcast together, got shapes {prev.shape} and {cur.shape}"
        ) from None
    shift = np.uint64(64 - nbits)
    # uint64 subtraction wraps modulo 2**64; shifting the low `bits` bits to the top and
    # back with an arithmetic shift sign-extends them: the modular difference, signed.
    with np.errstate(over="ignore"):
        diff = (cur.astype(np.uint64) - prev.astype(np.uint64)) << shift
    out: IntArray = diff.view(np.int64) >> np.int64(shift)
    if out.ndim == 0:
        return int(out)
    return out


def _as_counter(value: ArrayLike, name: str, bits: int) -> IntArray:
    arr = integer_readings(value, name)
    low, high = -(2 ** (bits - 1)), 2**bits - 1
    if arr.size and (int(arr.min()) < low or int(arr.max()) > high):
        raise ValueError(f"{name} holds readings outside the range of a {bits}-bit counter")
    if arr.dtype == np.uint64:
        return arr.view(np.int64)
    if arr.dtype == object:
        # Python ints that share no NumPy integer dtype ([2**64 - 1, -1]): the same
        # readings modulo 2**64, all that the modular difference of tick_delta needs.
        wrapped = [int(item) % (1 << 64) for item in arr.flat]
        return np.array(wrapped, dtype=np.uint64).reshape(arr.shape).view(np.int64)
    return arr.astype(np.int64)
