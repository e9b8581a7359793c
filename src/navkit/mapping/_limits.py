"""Documented ranges of navkit.mapping's parameters and the checks that enforce them (private).

Every mapping object checks its numbers where it is built, with these helpers,
so that finite input inside the ranges never produces NaN, an overflow or an
allocation the machine cannot make:

* grid size: at most :data:`MAX_CELLS` cells (``2**28``, e.g. 16384 × 16384:
  1 GiB of float32 log-odds; 819 m × 819 m at 5 cm). Sizes are checked as
  floats *before* anything is allocated or converted to an integer;
* ``resolution``: [1e-6, 1e6] m;
* world coordinates of a grid origin: ``|x|, |y| <= 1e9`` m;
* radii (``robot_radius``, ``inflation_radius``): [0, 1e6] m;
* log-odds (stored values, ``hit``, ``miss``, ``clamp``): within ±1e6;
* laser ``range_max``: at most 1e9 m; beam angles within ±2π;
* costs: ``cost_weight`` in [0, 1e9], ``unknown_cost`` in [1, 1e9] or ``inf``,
  ``cost_scaling_factor`` in (0, 1e12] 1/m.

Examples
--------
>>> grid_shape(width=2.0, height=1.0, resolution=0.5, what="the grid")
(2, 4)
>>> grid_shape(width=1e6, height=1e6, resolution=1e-3, what="the grid")
Traceback (most recent call last):
...
ValueError: the grid would need 1e+18 cells (3.47 EiB of float32); the maximum is ...
>>> bounded_float(2.0, "gain", 0.0, 1.0, "1/m")
Traceback (most recent call last):
...
ValueError: gain must be >= 0 and <= 1 1/m, got 2.0
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from navkit._shared.counts import bytes_text
from navkit._shared.float32 import length_in_cells
from navkit._shared.types import FloatArray
from navkit._shared.validation import finite_float, refuse_masked

__all__ = [
    "CELL_INDEX_LIMIT",
    "COORDINATE_LIMIT",
    "COST_LIMIT",
    "LOGODDS_LIMIT",
    "MAX_CELLS",
    "RADIUS_LIMIT",
    "RANGE_LIMIT",
    "RESOLUTION_MAX",
    "RESOLUTION_MIN",
    "SCALING_LIMIT",
    "bounded_float",
    "cells_text",
    "check_cell_count",
    "check_cell_range",
    "cost_or_inf",
    "grid_shape",
    "number_text",
    "resolution_float",
]

#: Largest number of cells of any grid navkit.mapping builds or reads.
MAX_CELLS = 2**28
RESOLUTION_MIN = 1e-6
RESOLUTION_MAX = 1e6
#: Largest |x| and |y| of a grid origin, m.
COORDINATE_LIMIT = 1e9
RADIUS_LIMIT = 1e6
LOGODDS_LIMIT = 1e6
#: Largest laser range_max, m.
RANGE_LIMIT = 1e9
#: Largest finite cost_weight and unknown_cost.
COST_LIMIT = 1e9
SCALING_LIMIT = 1e12
#: Cell indices are clamped to ±CELL_INDEX_LIMIT (far outside any grid) so that
#: points far away never overflow an int64.
CELL_INDEX_LIMIT = float(2**62)


def cells_text(cells: float, bytes_per_cell: int = 4, dtype: str = "float32") -> str:
    """``"1e+18 cells (3.47 EiB of float32)"``: a size for error messages."""
    if not math.isfinite(cells):
        return "more than 1e308 cells (more bytes than exist)"
    return f"{cells:.3g} cells ({bytes_text(cells * bytes_per_cell)} of {dtype})"


def check_cell_count(
    cells: float, what: str, *, bytes_per_cell: int = 4, dtype: str = "float32"
) -> None:
    """Raise ``ValueError`` when ``cells`` (a float, possibly inf) exceeds :data:`MAX_CELLS`."""
    if not cells <= MAX_CELLS:  # also catches inf and NaN
        raise ValueError(
            f"{what} would need {cells_text(cells, bytes_per_cell, dtype)}; "
            f"the maximum is 2**28 = {MAX_CELLS} cells"
        )


def number_text(x: float) -> str:
    """Short form of a bound for messages: ``0``, ``0.5``, ``1e6``, ``inf``."""
    if math.isfinite(x) and x == int(x) and abs(x) < 1e4:
        return str(int(x))
    return f"{x:g}".replace("e+0", "e").replace("e-0", "e-").replace("e+", "e")


def bounded_float(
    value: Any, name: str, low: float, high: float, unit: str = "", *, low_open: bool = False
) -> float:
    """``value`` as a finite float in ``[low, high]`` (``(low, high]`` with ``low_open``)."""
    out = finite_float(value, name)
    if not ((out > low if low_open else out >= low) and out <= high):
        suffix = f" {unit}" if unit else ""
        bound = f"{'>' if low_open else '>='} {number_text(low)}"
        if math.isfinite(high):
            bound += f" and <= {number_text(high)}"
        raise ValueError(f"{name} must be {bound}{suffix}, got {out}")
    return out


def resolution_float(value: Any, name: str = "resolution") -> float:
    """A cell size in [1e-6, 1e6] m."""
    return bounded_float(value, name, RESOLUTION_MIN, RESOLUTION_MAX, "m")


def cost_or_inf(value: Any, name: str) -> float:
    """A cost in [1, 1e9] or ``inf``; booleans, strings and NaN are refused."""
    if issubclass(type(value), np.ndarray) and value.ndim == 0 and value.dtype.kind == "f":
        refuse_masked(value, name)  # .item() would read a masked value's data
        value = value.item()
    if isinstance(value, (float, np.floating)) and value == math.inf:
        return math.inf
    out = finite_float(value, name)  # TypeError for non-numbers, ValueError for NaN, -inf
    if not 1.0 <= out <= COST_LIMIT:
        raise ValueError(f"{name} must be >= 1 and <= 1e9, or inf, got {out}")
    return out


#: Relative rounding of a cell count ``extent / resolution`` when ``extent`` was
#: itself computed as ``cells * resolution``: two roundings of half an ulp each,
#: with a factor 4 to spare.
_COUNT_ULPS = 4.0 * 2.0**-52


def _cell_count(extent: float, resolution: float) -> float:
    """Cells covering ``extent`` m, rounded up (a float: inf when absurdly many).

    A ratio within 1e-9 cells of an integer, or within the rounding of the
    division (a few ulps of the ratio: 3e-8 cells for 2**28), is not rounded
    up, so that ``extent = n * resolution`` gives ``n`` cells however long the
    grid is. Cells of a float32 resolution are counted as cells of the decimal
    it stands for (:func:`~navkit._shared.float32.intended_resolution`):
    10 m at a ROS message's 0.01 m (0.009999999776482582) are 1000 cells, as
    at the YAML's 0.01, where the float32 itself gave 1001; an extent of a
    whole number of the float32's own cells is that many
    (:func:`~navkit._shared.float32.length_in_cells`: ``n`` times float32
    0.05, a little more than ``n`` times 0.05, gave ``n + 1``; review 54).
    """
    n = length_in_cells(extent, resolution)
    if not n < 1e18:
        return math.inf if not math.isfinite(n) else n
    return float(max(1, math.ceil(n - (1e-9 + _COUNT_ULPS * n))))


def grid_shape(*, width: float, height: float, resolution: float, what: str) -> tuple[int, int]:
    """``(rows, cols)`` covering ``width × height`` m (rounded up), checked before any allocation.

    Arguments are already validated floats; the cell counts are computed as
    floats so that no size overflows before it is compared with :data:`MAX_CELLS`.
    """
    cols = _cell_count(width, resolution)
    rows = _cell_count(height, resolution)
    check_cell_count(rows * cols, what)
    return int(rows), int(cols)


def check_cell_range(cells: FloatArray, name: str = "cells") -> None:
    """Refuse grid coordinates beyond ±2**62 (their world points could overflow)."""
    if cells.size and not float(np.abs(cells).max()) <= CELL_INDEX_LIMIT:
        raise ValueError(
            f"{name} must lie within ±2**62 of cell (0, 0), got {float(np.abs(cells).max())}"
        )
