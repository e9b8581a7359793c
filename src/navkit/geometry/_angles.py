"""Angle wrapping."""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any, overload

import numpy as np
from numpy.typing import ArrayLike, NDArray

from navkit._shared.angles import wrap_float
from navkit._shared.types import RealScalar
from navkit._shared.validation import as_float_array

__all__ = ["angle_diff", "wrap_angle"]

_TWO_PI = 2.0 * math.pi


@overload
def wrap_angle(angle: RealScalar) -> float: ...
@overload
def wrap_angle(
    angle: Sequence[float] | Sequence[Sequence[float]],
) -> NDArray[np.float64]: ...
@overload
def wrap_angle(angle: ArrayLike) -> float | NDArray[np.float64]: ...


def wrap_angle(angle: ArrayLike) -> float | NDArray[np.float64]:
    """Wrap angles to the half-open interval (-π, π].

    Parameters
    ----------
    angle : float or array_like
        Angle(s) in radians: any finite real numbers.

    Returns
    -------
    float or ndarray
        A float for scalar input, otherwise a new float64 array of the same shape.
        Angles already inside (-π, π] are returned unchanged, so the function is
        idempotent bit for bit. Others are reduced exactly, with no rounding, by
        a multiple of the float ``2 * math.pi`` (``wrap_angle(2 * math.pi)`` is
        0.0): that is 2.4e-16 less than 2π, so the result is within
        ``k * 2.4e-16`` rad of the exact reduction by 2π, where ``k`` is the
        number of multiples of ``2 * math.pi`` removed (under 1e-14 rad for
        angles within ±100 rad). That is a circular distance (as
        :func:`angle_diff` measures it): within ``k * 2.4e-16`` of ±π the
        result and the exact reduction may lie on opposite sides of the seam,
        2π apart as numbers. ``wrap_angle(-3 * math.pi)`` is +π (the float
        ``math.pi``, removing ``k = 2`` multiples), the exact reduction
        -π + 3.7e-16: 4.9e-16 apart around the circle.

        That difference never exceeds about 1.1 times half the spacing of
        floats at ``angle`` (the rounding the angle already carries when it is
        given as a float): 4e-11 rad at 1e6 rad, where floats lie 1.2e-10 rad
        apart. Beyond about 1e17 rad, where consecutive floats lie more than a
        turn apart, a float determines no angle at all: the result is some
        value in (-π, π] (``wrap_angle(1e16)`` is 2.637, the exact reduction
        2.247, and the floats next to 1e16 are 2 rad away).

    Raises
    ------
    TypeError
        If ``angle`` is not real numbers (complex, strings and booleans are
        refused).
    ValueError
        If any angle is NaN or infinite.

    Examples
    --------
    >>> import math
    >>> wrap_angle(3 * math.pi / 2)
    -1.5707963267948966
    >>> wrap_angle(-math.pi) == math.pi
    True
    >>> wrap_angle(-3 * math.pi) == math.pi  # the seam: -π + 3.7e-16 exactly
    True
    """
    value: Any = angle
    if type(value) is float and value - value == 0.0:  # a finite float: the fast path
        return wrap_float(value)
    arr = as_float_array(angle, "angle")
    # As wrap_float: fmod and the fold are exact; fmod returns angles inside
    # (-π, π] unchanged, and only -π itself is folded (to π).
    rem = np.fmod(arr, _TWO_PI)
    if rem.ndim == 0:
        r = float(rem)
        return r - _TWO_PI if r > math.pi else r + _TWO_PI if r <= -math.pi else r
    # Folded in place (np.where's branches took four more arrays of the input's
    # size). rem - 2π is exact for rem in (π, 2π) and above -π: never folded twice.
    np.subtract(rem, _TWO_PI, out=rem, where=rem > math.pi)
    np.add(rem, _TWO_PI, out=rem, where=rem <= -math.pi)
    return rem


@overload
def angle_diff(a: RealScalar, b: RealScalar) -> float: ...
@overload
def angle_diff(
    a: Sequence[float] | Sequence[Sequence[float]], b: ArrayLike
) -> NDArray[np.float64]: ...
@overload
def angle_diff(
    a: ArrayLike, b: Sequence[float] | Sequence[Sequence[float]]
) -> NDArray[np.float64]: ...
@overload
def angle_diff(a: ArrayLike, b: ArrayLike) -> float | NDArray[np.float64]: ...


def angle_diff(a: ArrayLike, b: ArrayLike) -> float | NDArray[np.float64]:
    """Signed smallest difference ``a - b`` wrapped to (-π, π].

    Parameters
    ----------
    a, b : float or array_like
        Angles in radians (broadcast together): any finite real numbers.

    Returns
    -------
    float or ndarray
        ``wrap_angle(a - b)``: positive when ``a`` lies counter-clockwise of ``b``.
        When ``a - b`` would overflow (angles near ±1.8e308) both angles are
        wrapped first, which gives the same angle.

    Raises
    ------
    TypeError, ValueError
        As :func:`wrap_angle`, naming ``a`` or ``b``; ``ValueError`` also if
        their shapes do not broadcast together.

    Examples
    --------
    >>> import math
    >>> round(angle_diff(math.radians(10), math.radians(350)), 12) == round(math.radians(20), 12)
    True
    """
    first_value: Any = a
    second_value: Any = b
    if type(first_value) is float and type(second_value) is float:
        d = first_value - second_value
        if d - d == 0.0:
            return wrap_float(d)
    first = as_float_array(a, "a")
    second = as_float_array(b, "b")
    try:
        np.broadcast_shapes(first.shape, second.shape)
    except ValueError:
        # NumPy's own message names neither argument.
        raise ValueError(
            f"a and b must broadcast together, got shapes {first.shape} and {second.shape}"
        ) from None
    # a - b overflows only when |a| or |b| exceeds half the float range.
    if max(_peak(first), _peak(second)) < 8e307:
        return wrap_angle(np.subtract(first, second))
    with np.errstate(over="ignore", invalid="ignore"):
        diff = np.subtract(first, second)
    # Where a - b overflowed, wrap both angles first: the same angle, always finite.
    rescue = np.subtract(wrap_angle(first), wrap_angle(second))
    return wrap_angle(np.where(np.isfinite(diff), diff, rescue))


def _peak(arr: NDArray[np.float64]) -> float:
    """Largest magnitude in ``arr`` (0 when empty)."""
    return float(np.max(np.abs(arr))) if arr.size else 0.0
