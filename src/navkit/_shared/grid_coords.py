"""Grid-coordinate helpers shared by every grid type (private).

navkit's continuous grid coordinates are float ``(row, col)`` with integers at
cell centres; the cell of a coordinate is its value rounded half up. Every grid
(:class:`navkit.mapping.OccupancyGrid`, :class:`navkit.mapping.LocalGrid`,
:class:`navkit.planning.SampledField`, Field D*'s node grid) converts with these
helpers, so the rounding rule and the one-or-many shape rule exist once: a
single pair of shape ``(2,)`` gives a result of shape ``(2,)`` (or a 0-d
boolean), ``(N, 2)`` input gives ``(N, 2)`` (or ``(N,)``).
"""

from __future__ import annotations

from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from navkit._shared.types import BoolArray, FloatArray, IntArray
from navkit._shared.validation import as_points


def as_pairs(value: ArrayLike, name: str) -> tuple[FloatArray, bool]:
    """``value`` as ``(N, 2)`` float64 pairs, and whether it was one pair of shape ``(2,)``.

    Examples
    --------
    >>> as_pairs([1.0, 2.0], "p")
    (array([[1., 2.]]), True)
    >>> as_pairs([[1.0, 2.0]], "p")[1]
    False
    """
    pts = as_points(value, name)
    # Only a one-row result can come from a (2,) input; np.ndim converts no big input.
    return pts, pts.shape[0] == 1 and np.ndim(value) == 1


#: Cells of coordinates beyond ±2**62 are clamped there: far outside any grid, and
#: an int64 (casting a larger float to int64 is undefined and gives INT64_MIN).
CELL_LIMIT = float(2**62)


def round_half_up(values: FloatArray) -> IntArray:
    """Cells of continuous coordinates: each value rounded half up (``⌊v + ½⌋``) as int64.

    ``np.rint`` rounds half to even; cell boundaries must not depend on parity.
    Values beyond ±2**62 (:data:`CELL_LIMIT`) give ±2**62, a cell outside every
    grid, instead of an undefined cast.

    Examples
    --------
    >>> round_half_up(np.array([0.5, 1.5, -0.5, 2.49]))
    array([1, 2, 0, 2])
    >>> round_half_up(np.array([0.49999999999999994, 2.0**52 + 1])).tolist()
    [0, 4503599627370497]
    >>> round_half_up(np.array([1e300, -1e300])).tolist() == [2**62, -(2**62)]
    True
    """
    # Not np.floor(values + 0.5): that sum is rounded before the floor, so a value
    # just below a cell edge (0.5 - 2**-54) or an odd integer beyond 2**52 lands
    # one cell up. The fraction v - floor(v) is exact, and so is this comparison.
    low = np.floor(values)
    cells = low + (values - low >= 0.5)
    out: IntArray = np.clip(cells, -CELL_LIMIT, CELL_LIMIT).astype(np.int64)
    return out


def inside(cells: IntArray, shape: tuple[int, int]) -> BoolArray:
    """Whether each ``(row, col)`` of ``cells`` (N, 2) lies in a grid of ``shape``; (N,).

    Examples
    --------
    >>> inside(np.array([[0, 0], [2, 1], [-1, 0]]), (2, 3))
    array([ True, False, False])
    """
    rows, cols = shape
    out: BoolArray = (
        (cells[:, 0] >= 0) & (cells[:, 0] < rows) & (cells[:, 1] >= 0) & (cells[:, 1] < cols)
    )
    return out


def one_or_many(values: FloatArray | IntArray | BoolArray, single: bool) -> NDArray[Any]:
    """``values`` for one input pair (row 0, or a 0-d array for (N,) results) or all of them.

    Examples
    --------
    >>> one_or_many(np.array([[1, 2]]), True)
    array([1, 2])
    >>> one_or_many(np.array([True]), True).shape
    ()
    """
    if not single:
        return values
    return values[0] if values.ndim == 2 else values.reshape(())
