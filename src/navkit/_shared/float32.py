"""Float32 numbers as ROS messages and drivers give them (private).

The cell size a float32 resolution stands for, and cells counted in it; the
precision of an input given in a float narrower than float64.

``nav_msgs/OccupancyGrid`` carries a map's resolution as a float32: a 0.01 m
map arrives at 0.009999999776482582 m. Counting cells of a length in that
float (10 m: 1000.0000224 cells) gained a cell over the same map read from its
YAML; every count of cells from a length and a resolution goes through
:func:`intended_resolution` so that the two maps agree (review 52 for radii,
review 53 for grid and window sizes).

Examples
--------
>>> import numpy as np
>>> 10.0 / float(np.float32(0.01)) > 1000.0
True
>>> 10.0 / intended_resolution(float(np.float32(0.01)))
1000.0
"""

from __future__ import annotations

import array
import math
from typing import Any

import numpy as np

__all__ = ["intended_resolution", "length_in_cells", "narrow_float_dtype"]

#: The positive normal float32 values' range: a resolution outside it is no float32.
_FLOAT32_TINY = float(np.finfo(np.float32).tiny)
_FLOAT32_MAX = float(np.finfo(np.float32).max)


def intended_resolution(resolution: float) -> float:
    """The decimal a float32 ``resolution`` stands for; any other resolution itself.

    A resolution that is a float32 value is taken to stand for the shortest
    decimal that float32 rounds to it (0.05 for 0.05000000074505806): the
    radius a user gives in cells of that decimal (0.15 m, 3 cells) must reach
    as many cells of the float32 (2.99999996 of them), and a 10 m grid at it
    has 1000 cells of 0.01 m, not 1001. A float64 resolution that is not a
    float32 value (0.05 written in Python) is returned unchanged, and so is a
    float32 value whose shortest decimal has more than 6 significant digits
    (more than float32 keeps of any decimal): no short decimal stands behind
    it. 0.00244140625 (5 / 2**11, written in Python) was taken for
    0.0024414062, and a grid of that width and height at it had 2 x 2 cells;
    float32 1/81 for 0.012345679, and 1 m at it had 82 cells (review 53).

    Parameters
    ----------
    resolution : float
        A cell size, m, finite and positive.

    Returns
    -------
    float
        The cell size counts and radii are taken in, m.

    Examples
    --------
    >>> intended_resolution(float(np.float32(0.05))), intended_resolution(0.05)
    (0.05, 0.05)
    >>> intended_resolution(0.5), intended_resolution(0.00244140625)
    (0.5, 0.00244140625)
    """
    if not _FLOAT32_TINY <= resolution <= _FLOAT32_MAX:
        return resolution  # no float32 value: and its cast would overflow (or underflow)
    single = np.float32(resolution)
    if float(single) != resolution:
        return resolution
    shortest = np.format_float_scientific(single, unique=True)
    if len(shortest.split("e")[0].replace(".", "").lstrip("-")) > _FLT_DIG:
        return resolution  # no decimal a float32 keeps stands behind it
    return float(shortest)


#: Relative rounding of ``length / resolution`` for a length computed as a multiple of
#: the resolution (two roundings of half an ulp, a factor 4 to spare).
_RATIO_ULPS = 4.0 * 2.0**-52


def length_in_cells(length: float, resolution: float, *, halves: bool = False) -> float:
    """``length`` (m) in cells of ``resolution``, as counts of cells take it.

    In cells of the decimal a float32 ``resolution`` stands for
    (:func:`intended_resolution`: 10 m at float32 0.01 m are 1000 cells, as at
    0.01), except a length that is a whole number of the resolution's own
    cells (with ``halves``, a whole number of half cells), within 1e-9 cells
    and the rounding of the division: that is that number. ``n * resolution``
    is ``n`` cells at any resolution; where float32 lies above its decimal
    (0.05 as 0.05000000075) it is a little more than ``n`` of the decimal's,
    and a grid of ``width = resolution`` had 2 x 2 cells (review 54).

    Parameters
    ----------
    length : float
        A length, m, finite and >= 0.
    resolution : float
        A cell size, m, finite and positive.
    halves : bool, default False
        Whether a length of a whole number of half cells (rounded half up by
        the caller) is taken in the resolution's own cells too.

    Returns
    -------
    float
        The length in cells (unrounded).

    Examples
    --------
    >>> res = float(np.float32(0.05))
    >>> length_in_cells(res, res), length_in_cells(0.05, res), length_in_cells(1.0, res)
    (1.0, 1.0, 20.0)
    >>> length_in_cells(10.0, float(np.float32(0.01)))
    1000.0
    """
    own = length / resolution
    cell = intended_resolution(resolution)
    if cell == resolution or not math.isfinite(own):
        return own
    unit = 0.5 if halves else 1.0
    units = own / unit
    if abs(units - round(units)) * unit <= 1e-9 + _RATIO_ULPS * own:
        return own
    return length / cell


#: Significant digits any decimal keeps through float32 (C's FLT_DIG): the float32 of a
#: decimal of at most 6 is the float32 whose shortest decimal is that one, so a float32
#: whose shortest decimal is longer stands for none (a written binary fraction, 1/81).
_FLT_DIG = 6


def narrow_float_dtype(value: object) -> np.dtype[np.floating[Any]] | None:
    """The dtype of ``value``'s floats when narrower than float64 (float16, float32), else None.

    ``value`` is an input already read as a float array (this only asks its
    dtype): an ndarray or NumPy scalar of float16 or float32, a list of
    them (NumPy gives it their dtype), an ``array.array`` or ``memoryview`` of
    C floats, or another library's array NumPy converts to one, was rounded to
    that precision by whatever made it (a driver, a message), and its values
    are compared in it.

    Parameters
    ----------
    value : object
        The argument as given.

    Returns
    -------
    numpy.dtype or None
        The float16 or float32 dtype; None for float64, long double,
        integers and anything else.

    Examples
    --------
    >>> narrow_float_dtype(np.zeros(2, dtype=np.float32))
    dtype('float32')
    >>> narrow_float_dtype([0.5, 1.0]) is None, narrow_float_dtype([np.float16(0.5)])
    (True, dtype('float16'))
    """
    dtype = getattr(value, "dtype", None)
    if not isinstance(dtype, np.dtype) and (
        isinstance(value, (list, tuple, array.array, memoryview)) or hasattr(value, "__array__")
    ):
        # A buffer (a memoryview of a float32 array.array) or an array of another
        # library NumPy converts (whose own dtype is no NumPy dtype) was read as float64
        # and compared so (review 54).
        try:
            dtype = np.asarray(value).dtype
        except (TypeError, ValueError):
            return None
    if not isinstance(dtype, np.dtype) or dtype.kind != "f" or dtype.itemsize >= 8:
        return None
    return dtype
