"""Angle wrapping."""

from __future__ import annotations

import math
from typing import overload

import numpy as np
from numpy.typing import ArrayLike, NDArray

from navkit._shared.validation import as_float_array

__all__ = ["angle_diff", "wrap_angle"]


@overload
def wrap_angle(angle: float) -> float: ...
@overload
def wrap_angle(angle: ArrayLike) -> float | NDArray[np.float64]: ...


def wrap_angle(angle: ArrayLike) -> float | NDArray[np.float64]:
    """Wrap angles to the half-open interval (-π, π].

    Parameters
    ----------
    angle : float or array_like
        Angle(s) in radians; must be finite.

    Returns
    -------
    float or ndarray
        A float for scalar input, otherwise a new float64 array of the same shape.
        Angles already inside (-π, π] are returned unchanged, so the function is
        idempotent bit for bit.

    Raises
    ------
    ValueError
        If any angle is NaN or infinite.

    Examples
    --------
    >>> import math
    >>> wrap_angle(3 * math.pi / 2)
    -1.5707963267948966
    >>> wrap_angle(-math.pi) == math.pi
    True
    """
    arr = as_float_array(angle, "angle")
    inside = (arr > -math.pi) & (arr <= math.pi)
    wrapped = math.pi - np.mod(math.pi - arr, 2.0 * math.pi)
    # np.mod can round up to exactly 2π for tiny negative arguments.
    wrapped = np.where(wrapped <= -math.pi, wrapped + 2.0 * math.pi, wrapped)
    out = np.where(inside, arr, wrapped)
    if out.ndim == 0:
        return float(out)
    return out


@overload
def angle_diff(a: float, b: float) -> float: ...
@overload
def angle_diff(a: ArrayLike, b: ArrayLike) -> float | NDArray[np.float64]: ...


def angle_diff(a: ArrayLike, b: ArrayLike) -> float | NDArray[np.float64]:
    """Signed smallest difference ``a - b`` wrapped to (-π, π].

    Parameters
    ----------
    a, b : float or array_like
        Angles in radians (broadcast together).

    Returns
    -------
    float or ndarray
        ``wrap_angle(a - b)``: positive when ``a`` lies counter-clockwise of ``b``.

    Examples
    --------
    >>> import math
    >>> round(angle_diff(math.radians(10), math.radians(350)), 12) == round(math.radians(20), 12)
    True
    """
    return wrap_angle(np.subtract(as_float_array(a, "a"), as_float_array(b, "b")))
