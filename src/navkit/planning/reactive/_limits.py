"""Documented ranges of navkit.planning.reactive and the checks that enforce them (private).

* world points (``points_xy``, ``goal_xy``, ``obstacles_xy``, a sampling
  window, a greedy goal): finite, ``|x|, |y| <= 1e9`` m;
* gains (``k_att``, ``c``, ``m``, ``u_trans``, ``alpha``, ``k_rep``,
  ``delta``, ``beta``): ``[1e-12, 1e12]``;
* lengths (``a``, ``b``, ``width``, ``spread``, ``influence_radius``):
  ``[1e-6, 1e6]`` m; offsets that may be 0 (``threshold_radius``,
  ``goal_radius``, ``obstacle_radius``): ``[0, 1e6]`` m;
* Khatib repulsion: an obstacle nearer than :data:`MIN_DISTANCE` (1e-9 m) but
  not on the point acts from 1e-9 m (the force saturates instead of
  overflowing, so opposite pushes still cancel);
* :func:`~navkit.planning.sample_field`: at most :data:`MAX_SAMPLES`
  (``2**26``) cells; a :class:`~navkit.planning.SampledField`'s resolution in
  ``[1e-6, 1e6]`` m.

Inside these ranges every product the fields form stays finite: squared
offsets are at most 1.6e19 m², divided by a squared semi-axis at least 1e-12
and multiplied by gains up to 1e24, and a Khatib push is at most
``1e12 / (1e-9)³ = 1e39`` per obstacle.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from navkit._shared.types import FloatArray
from navkit._shared.validation import as_float_array, finite_float, transposed_hint

__all__ = [
    "COORDINATE_LIMIT",
    "GAIN_MAX",
    "GAIN_MIN",
    "LENGTH_MAX",
    "LENGTH_MIN",
    "MAX_SAMPLES",
    "MIN_DISTANCE",
    "RESOLUTION_MAX",
    "RESOLUTION_MIN",
    "check_coordinates",
    "gain",
    "length",
    "point",
    "points",
]

COORDINATE_LIMIT = 1e9
"""Largest |x|, |y| of a world point, m."""
GAIN_MIN = 1e-12
GAIN_MAX = 1e12
LENGTH_MIN = 1e-6
LENGTH_MAX = 1e6
MIN_DISTANCE = 1e-9
"""Distance (m) below which a Khatib obstacle acts as if it were this far."""
MAX_SAMPLES = 2**26
"""Largest number of cells :func:`sample_field` evaluates (8192 × 8192)."""
RESOLUTION_MIN = 1e-6
RESOLUTION_MAX = 1e6


def _in_range(value: Any, name: str, low: float, high: float, unit: str) -> float:
    # Fast path for a plain float in range (fields are rebuilt every control step).
    if type(value) is float and low <= value <= high:
        return value
    out = finite_float(value, name)
    if not low <= out <= high:
        raise ValueError(f"{name} must lie in [{low:g}, {high:g}]{unit}, got {out}")
    return out


def gain(value: Any, name: str) -> float:
    """A gain in ``[1e-12, 1e12]``."""
    return _in_range(value, name, GAIN_MIN, GAIN_MAX, "")


def length(value: Any, name: str, *, allow_zero: bool = False) -> float:
    """A length in ``[1e-6, 1e6]`` m, or in ``[0, 1e6]`` m with ``allow_zero``."""
    return _in_range(value, name, 0.0 if allow_zero else LENGTH_MIN, LENGTH_MAX, " m")


def check_coordinates(values: FloatArray, name: str, limit: float = COORDINATE_LIMIT) -> None:
    """Refuse NaN, infinities and coordinates beyond ``±limit`` in ``values``."""
    if values.size == 0:
        return
    worst = float(np.abs(values).max())  # NaN when any value is NaN
    if not worst <= limit:
        if not math.isfinite(worst):
            raise ValueError(f"{name} must contain only finite values")
        # repr, not :g: six digits showed 1e9 + 1 as "1e+09", the limit itself.
        raise ValueError(f"{name} must lie within ±{limit:g} m in x and y, got {worst!r}")


def points(value: ArrayLike, name: str) -> FloatArray:
    """World points as ``(N, 2)`` float64: ``(2,)`` gives ``(1, 2)``, empty ``(0, 2)``."""
    arr = as_float_array(value, name, finite=False)
    if arr.size == 0:
        return np.empty((0, 2), dtype=np.float64)
    if arr.ndim == 1 and arr.shape[0] == 2:
        arr = arr.reshape(1, 2)
    elif arr.ndim != 2 or arr.shape[1] != 2:
        raise ValueError(
            f"{name} must have shape (N, 2) or (2,), got {arr.shape}"
            + transposed_hint(arr.shape, (None, 2))
        )
    check_coordinates(arr, name)
    return arr


def point(value: ArrayLike, name: str) -> FloatArray:
    """One world point ``(x, y)`` as a float64 array of shape (2,)."""
    arr = as_float_array(value, name, shape=(2,), finite=False)
    check_coordinates(arr, name)
    return arr
