"""Documented ranges of navkit.planning.grid and the checks that enforce them (private).

* costs: finite values in ``[1, MAX_COST]`` (``1e12``) or ``inf``, on at most
  :data:`MAX_NODES` (``2**31 - 1``) cells (Field D*: nodes, ``(rows + 1) ×
  (cols + 1)``);
* ``heuristic_weight``: ``[0, MAX_HEURISTIC_WEIGHT]`` (``1e6``);
* Field D*: the least cost from the start to the goal below
  :data:`PATH_COST_LIMIT` (``2**52``, about 4.5e15 cost units × cells);
  ``resolution`` in ``[1e-6, 1e6]`` m, origin and world points within
  ``±1e9`` m;
* :class:`~navkit.planning.MapPlanner`: ``robot_radius`` in ``[0, 1e6]`` m.

Why these bounds. A* and Dijkstra add move costs ``step * (c_u + c_v) / 2``:
with costs up to 1e12 no sum over a grid of ``2**31`` cells comes near
overflow (3e21), and ``heuristic_weight × min(costs) × distance`` stays below
1e28. Field D* has a tighter limit, float64 resolution: its path extraction
walks downhill on the cost-to-goal and needs every node to be strictly
dearer than the neighbour its value comes from. In exact arithmetic the
difference is at least ``1/sqrt(2)`` (costs are >= 1); in float64 it survives
rounding while the values are below 2**52 (one unit in the last place is then
at most 0.5), while far above it a step vanishes (1e20 + 1.41 == 1e20), no
neighbour is strictly lower and the walk cannot proceed (issue 12's
RuntimeError). The limit is on the start's cost-to-goal, i.e. on the path
cost, not on any single cell; with cells up to 1e12 it leaves paths of 4,500
cells at the maximum cost. Checking it costs O(1) after each search.
"""

from __future__ import annotations

import math
from typing import Any, TypeVar

import numpy as np
from numpy.typing import ArrayLike, NDArray

from navkit._shared.costs import validate_costs_lowest
from navkit._shared.jit import njit_released
from navkit._shared.types import FloatArray
from navkit._shared.validation import aligned, finite_float, holds_bool, refuse_masked
from navkit.planning.grid._search_heap import MAX_NODES

__all__ = [
    "COORDINATE_LIMIT",
    "MAX_COST",
    "MAX_HEURISTIC_WEIGHT",
    "MAX_NODES",
    "PATH_COST_LIMIT",
    "RADIUS_LIMIT",
    "RESOLUTION_MAX",
    "RESOLUTION_MIN",
    "bounded_float",
    "check_node_count",
    "check_range",
    "checked_cost_range",
    "checked_costs",
    "compiled_cost_range",
    "converted_costs",
    "cost_range",
    "highest_finite",
    "read_only",
    "scanned_cost_range",
]

_T = TypeVar("_T", bound=np.generic)

MAX_COST = 1e12
"""Largest finite traversal cost the grid planners accept."""
MAX_HEURISTIC_WEIGHT = 1e6
PATH_COST_LIMIT = float(2**52)
"""Field D*: the start's cost-to-goal must be below this (float64 resolution)."""
RESOLUTION_MIN = 1e-6
RESOLUTION_MAX = 1e6
COORDINATE_LIMIT = 1e9
"""Largest |x|, |y| of a world point or grid origin, m."""
RADIUS_LIMIT = 1e6
"""Largest robot_radius, m."""

# Search state: A* scratch per cell (g, parent, mark, heap entry, slot); Field D*
# per node (padded cost, g, rhs, heap node, two keys, slot).
_SEARCH_BYTES_PER_CELL = 33
_FIELD_BYTES_PER_NODE = 56

# Bit patterns of non-negative float64 values order like the values themselves
# (and every negative value, -0.0 included, is a negative int64), so integer
# comparisons of the bit patterns order the costs; NaN is above inf.
ONE_BITS = int(np.array(1.0).view(np.int64))
MAX_BITS = int(np.array(MAX_COST).view(np.int64))
INF_BITS = int(np.array(np.inf).view(np.int64))
# Cells per block of the value scans (:func:`cost_range`): 512 KiB of scratch.
_SCAN_BLOCK = 65536


def check_range(values: FloatArray, limit: float, name: str, unit: str) -> None:
    """Refuse coordinates beyond ``±limit`` (``values`` are already finite).

    Examples
    --------
    >>> check_range(np.array([[1e9, -2.0]]), COORDINATE_LIMIT, "points_xy", "m")
    >>> check_range(np.array([[1e9 + 0.5, 0.0]]), COORDINATE_LIMIT, "points_xy", "m")
    Traceback (most recent call last):
        ...
    ValueError: points_xy must lie within ±1e+09 m, got 1000000000.5
    """
    if values.size and not float(np.abs(values).max()) <= limit:
        # The value itself, exactly: rounded (":g") 1e9 + 0.5 would print as the limit.
        worst = float(values.reshape(-1)[int(np.argmax(np.abs(values)))])
        raise ValueError(f"{name} must lie within ±{limit:g} {unit}, got {worst!r}")


def read_only(array: NDArray[_T]) -> NDArray[_T]:
    """A read-only view of ``array`` (O(1), no copy).

    The grid kernels receive their input grids only as read-only arrays:
    numba compiles a kernel once per argument type, and read-only and
    writable arrays are different types, so passing both would compile the
    kernels twice (callers' grids may be either).
    """
    view: NDArray[_T] = array.view()
    view.flags.writeable = False
    return view


def checked_costs(
    costs: ArrayLike, name: str = "costs", *, corner_nodes: bool = False
) -> tuple[FloatArray, float]:
    """A cost grid as C-contiguous float64 and its smallest value (inf if none is finite).

    See :func:`checked_cost_range`, which also returns the largest finite value.
    """
    grid, lowest, _ = checked_cost_range(costs, name, corner_nodes=corner_nodes)
    return grid, lowest


def checked_cost_range(
    costs: ArrayLike, name: str = "costs", *, corner_nodes: bool = False
) -> tuple[FloatArray, float, float]:
    """A cost grid as C-contiguous float64, its smallest value and its largest finite value.

    The smallest value is inf and the largest -inf when no value is finite.

    The checks of :func:`navkit.mapping.validate_costs` (2-D, not empty, real
    numbers, no NaN, finite values >= 1) plus the planners' limits: at most
    :data:`MAX_NODES` cells (``corner_nodes``: Field D*'s ``(rows + 1) ×
    (cols + 1)`` nodes), checked before anything is converted or allocated,
    and finite values <= :data:`MAX_COST`, these in one compiled pass over
    the grid (:func:`_scan_cost_bits`; :func:`cost_range` names the culprit
    when it finds one). The input is never modified; it is copied only when
    a dtype or layout conversion is needed, or when its buffer is not
    aligned for float64 (see :func:`converted_costs`).

    Raises
    ------
    ValueError
        Not real numbers (complex, strings, booleans, ragged input), wrong
        dimension, empty, NaN, values below 1 or finite values above 1e12
        (the same exception as :func:`navkit.mapping.validate_costs`).
    """
    out = converted_costs(costs, name, corner_nodes=corner_nodes)
    lowest, highest = compiled_cost_range(out, name)
    return out, lowest, highest


def compiled_cost_range(grid: FloatArray, name: str = "costs") -> tuple[float, float]:
    """:func:`cost_range` of a converted grid, its values scanned in one compiled pass.

    The values check of :func:`checked_cost_range`: :func:`_scan_cost_bits`,
    then :func:`scanned_cost_range` (jump point search's tables scan the
    values in their own pass, see
    :func:`~navkit.planning.grid._jps_kernels.jps_tables`).
    """
    lo_bits, hi_bits = _scan_cost_bits(read_only(grid.reshape(-1).view(np.int64)), INF_BITS)
    return scanned_cost_range(grid, name, lo_bits, hi_bits)


@njit_released
def _scan_cost_bits(bits: NDArray[np.int64], inf_bits: int) -> tuple[int, int]:
    """(smallest of ``bits``, largest one other than ``inf_bits`` or -1), one pass.

    The values check of :func:`checked_cost_range`, for
    :func:`scanned_cost_range`. Integer comparisons vectorise, so the pass
    costs what ``ndarray.min`` costs: it streams the grid once, where the
    NumPy reductions of :func:`cost_range` take a minimum, a subtraction into
    scratch and a maximum (1024 x 1024 grid: about 0.4 ms against 1.0 ms in
    cache, 0.9 ms against 1.8 ms from memory; issue 17). A small kernel of
    its own (about 0.2 s of first-use compilation, then loaded from the
    cache in a few ms), rather than the JPS table kernel, which scans the
    values while it packs the bit rows (one pass over the grid, review 48)
    but whose bit transposition would add about 1 s to every other
    validating entry point's first use.
    """
    lo = bits[0]
    hi = -1
    for i in range(bits.shape[0]):
        v = bits[i]
        # Selects, not the min/max builtins: numba compiles those as overloads
        # of their own on first use (about 0.15 s; issue 17).
        lo = v if v < lo else lo
        w = v if v != inf_bits else -1
        hi = w if w > hi else hi
    return lo, hi


def converted_costs(
    costs: ArrayLike, name: str = "costs", *, corner_nodes: bool = False
) -> FloatArray:
    """The conversion half of :func:`checked_cost_range`: its values are not checked yet.

    Type, dimension, emptiness and size are (before anything is converted or
    allocated); the caller must check the values, with :func:`cost_range` or
    from a scan of its own (:func:`scanned_cost_range`). The result is
    C-contiguous, float64 and aligned: a misaligned buffer (a view of bytes
    at an odd offset) is copied, since numba's dispatcher types such an
    array as an aligned one and the kernels would read it with loads that
    LLVM assumes aligned (review 46; the project-wide rule since review 47,
    :func:`~navkit._shared.validation.aligned`).
    """
    if isinstance(costs, (list, tuple)) and holds_bool(costs):
        # NumPy turns [[True, 2.0]] into [[1.0, 2.0]] (only all-bool lists stay bool).
        raise ValueError(f"{name} must be a real-valued numeric array, got an element of type bool")
    refuse_masked(costs, name)
    try:
        arr = np.asarray(costs)
    except (TypeError, ValueError) as exc:
        raise ValueError(f"{name} must be a 2-D array of real numbers: {exc}") from None
    if arr.dtype.kind not in "fiu" or arr.ndim != 2 or arr.size == 0:
        validate_costs_lowest(costs, name)  # raises, with the shared message
    rows, cols = arr.shape
    if corner_nodes:
        check_node_count(
            (rows + 1) * (cols + 1),
            f"Field D* on {name} of shape {arr.shape}",
            _FIELD_BYTES_PER_NODE,
        )
    else:
        check_node_count(
            rows * cols, f"A search on {name} of shape {arr.shape}", _SEARCH_BYTES_PER_CELL, "cells"
        )
    # ascontiguousarray keeps a misaligned buffer (bytes at an odd offset) as it is,
    # which numba would type as an aligned array (review 46): the shared rule copies it.
    return aligned(np.ascontiguousarray(arr, dtype=np.float64))


def cost_range(grid: FloatArray, name: str = "costs") -> tuple[float, float]:
    """The smallest value and the largest finite value of a converted grid, checked.

    NumPy reductions, no compiled kernel, block by block
    (:func:`_highest_finite`): the minimum (NaN propagates, so it also finds
    NaN) and the largest finite value. Raises as :func:`checked_cost_range`;
    it reports the culprit when a kernel's scan found an invalid value
    (:func:`scanned_cost_range`).
    """
    flat = grid.reshape(-1)
    scratch = np.empty(min(_SCAN_BLOCK, flat.size), dtype=np.int64)
    lowest = np.inf
    highest = -np.inf
    for begin in range(0, flat.size, _SCAN_BLOCK):
        block = flat[begin : begin + _SCAN_BLOCK]
        block_lowest = float(block.min())
        if not block_lowest >= 1.0:
            validate_costs_lowest(grid, name)  # NaN or below 1: raises, the shared message
        lowest = min(lowest, block_lowest)
        highest = max(highest, _highest_finite(block, scratch))
    if highest > MAX_COST:
        _raise_above_max(grid, name)
    return lowest, highest


def highest_finite(grid: FloatArray) -> float:
    """The largest finite value of a float64 grid of non-negative values or inf (-inf if none)."""
    flat = grid.reshape(-1)
    scratch = np.empty(min(_SCAN_BLOCK, flat.size), dtype=np.int64)
    highest = -np.inf
    for begin in range(0, flat.size, _SCAN_BLOCK):
        highest = max(highest, _highest_finite(flat[begin : begin + _SCAN_BLOCK], scratch))
    return highest


def _highest_finite(block: FloatArray, scratch: NDArray[np.int64]) -> float:
    """:func:`highest_finite` of a 1-D block, with ``scratch`` at least its size.

    On the bit patterns: ``bits - INF_BITS`` read as unsigned is 0 for inf and
    grows with the value below it, so one subtraction and one maximum find it.
    Scanned in blocks with a small scratch array because a grid-sized
    temporary costs fresh pages, zero-filled by the OS at every call, and
    evicts a search's records from the cache (about 1 ms of a 10 ms A*
    search on a 1024 x 1024 grid).
    """
    diff = scratch[: block.size]
    np.subtract(block.view(np.int64), INF_BITS, out=diff)
    top = int(diff.view(np.uint64).max())
    if top == 0:
        return -np.inf
    return float(np.array((top + INF_BITS) % 2**64, dtype=np.uint64).view(np.float64))


def scanned_cost_range(
    grid: FloatArray, name: str, lo_bits: int, hi_bits: int
) -> tuple[float, float]:
    """:func:`cost_range` from a kernel's scan of the grid's bit patterns, checked.

    ``lo_bits`` is the smallest bit pattern of ``grid`` (viewed as int64) and
    ``hi_bits`` the largest one other than inf's (-1 if none). Every value is
    valid when ``lo_bits`` is at least 1.0's pattern (no negative value, no
    NaN with its sign bit set) and ``hi_bits`` at most :data:`MAX_BITS` (no
    value above 1e12 but inf, no other NaN); otherwise :func:`cost_range`
    finds and reports the culprit.
    """
    if lo_bits < ONE_BITS or hi_bits > MAX_BITS:
        cost_range(grid, name)  # raises
    lowest = float(np.array(lo_bits, dtype=np.int64).view(np.float64))
    highest = float(np.array(hi_bits, dtype=np.int64).view(np.float64)) if hi_bits >= 0 else -np.inf
    return lowest, highest


def _raise_above_max(grid: FloatArray, name: str) -> None:
    validate_costs_lowest(grid, name)  # NaN is reported as NaN
    bad = np.isfinite(grid) & (grid > MAX_COST)
    where = tuple(int(i) for i in np.unravel_index(int(np.argmax(bad)), grid.shape))
    raise ValueError(
        f"{name} must be <= {MAX_COST:g} where finite (np.inf marks impassable cells); "
        f"found {float(grid[where])} at {where}"
    )


def bounded_float(value: Any, name: str, low: float, high: float, unit: str = "") -> float:
    """``value`` as a finite float in ``[low, high]``; ValueError naming the range."""
    if type(value) is float and low <= value <= high:
        return value
    out = finite_float(value, name)
    if not low <= out <= high:
        suffix = f" {unit}" if unit else ""
        raise ValueError(f"{name} must lie in [{low:g}, {high:g}]{suffix}, got {out}")
    return out


def check_node_count(count: int, what: str, bytes_per_node: int, unit: str = "nodes") -> None:
    """Refuse searches over more than :data:`MAX_NODES` nodes before allocating them."""
    if count > MAX_NODES:
        size = count * bytes_per_node
        raise ValueError(
            f"{what} would need {count:.3g} {unit} ({_bytes_text(size)} of search state); "
            f"the maximum is 2**31 - 1 = {MAX_NODES} {unit}"
        )


def _bytes_text(n: float) -> str:
    units = ("B", "KiB", "MiB", "GiB", "TiB", "PiB", "EiB")
    k = min(len(units) - 1, max(0, int(math.log(max(n, 1.0), 1024))))
    return f"{n / 1024.0**k:.3g} {units[k]}"
