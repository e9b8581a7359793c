"""Validation of per-cell traversal-cost arrays shared by every grid planner (private)."""

from __future__ import annotations

import numbers
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from navkit._shared.validation import aligned, holds_bool, refuse_masked

#: The most cells a cost grid may have: the grid searches' limit (``MAX_NODES`` of
#: navkit.planning.grid._search_heap, which this layer cannot import; a test
#: checks that the two agree). Beyond it the float64 copy alone takes 16 GiB.
MAX_COST_CELLS = 2**31 - 1


def validate_costs(costs: ArrayLike, name: str = "costs") -> NDArray[np.float64]:
    """Check a traversal-cost grid and return it as a C-contiguous float64 array.

    The planners' convention: a 2-D array indexed ``[row, col]`` whose finite
    values are >= 1 (cost per unit length of crossing the cell) and whose
    ``+inf`` entries are impassable. The input is never modified; it is copied
    only when a dtype or layout conversion is needed, or when its buffer is
    not aligned for float64 (:func:`~navkit._shared.validation.aligned`).

    Raises
    ------
    ValueError
        Wrong dimension, empty grid, more than :data:`MAX_COST_CELLS` cells
        (checked before anything is converted or copied), non-numeric or
        boolean dtype, NaN, ``-inf`` or finite values below 1.
    """
    return validate_costs_lowest(costs, name)[0]


def validate_costs_lowest(
    costs: ArrayLike, name: str = "costs"
) -> tuple[NDArray[np.float64], float]:
    """As :func:`validate_costs`, also returning the smallest cost (inf if none is finite).

    One pass over the grid gives both: the minimum is NaN when any cell is NaN
    and below 1 when any cell is, so the check costs nothing extra for callers
    that need the minimum anyway (the A* heuristic).
    """
    if isinstance(costs, (list, tuple)) and holds_bool(costs):
        # NumPy turns [[True, 2.0]] into [[1.0, 2.0]] (only all-bool lists stay bool).
        raise ValueError(f"{name} must be a real-valued numeric array, got an element of type bool")
    refuse_masked(costs, name)
    try:
        arr = np.asarray(costs)
    except (TypeError, ValueError, OverflowError) as exc:  # ragged lists, unconvertible objects
        raise ValueError(f"{name} must be a 2-D numeric array: {exc}") from None
    if arr.ndim == 2 and arr.size > MAX_COST_CELLS:
        # Before any conversion: a broadcast 50000 x 50000 view takes no memory, but
        # its float64 copy would take 18.6 GiB (NumPy's MemoryError, or swapping).
        raise ValueError(
            f"{name} has {arr.size:.3g} cells (shape {arr.shape}, "
            f"{arr.size * 8 / 2**30:.3g} GiB as float64); cost grids, like the grid "
            f"planners, take at most 2**31 - 1 = {MAX_COST_CELLS} cells"
        )
    if arr.dtype.kind == "O" and arr.ndim == 2 and _real_numbers(arr):
        # Python numbers in an object array (pandas' .values of mixed columns,
        # np.array(..., dtype=object)) are their values, as for every array argument.
        try:
            arr = arr.astype(np.float64)
        except OverflowError:
            raise ValueError(
                f"{name} must hold finite numbers, got an integer too large for a float"
            ) from None
    if arr.dtype == np.bool_ or arr.dtype.kind not in "fiu":
        raise ValueError(
            f"{name} must be a real-valued numeric array, got "
            + _not_costs_hint(costs, arr.dtype)
        )
    if arr.ndim != 2:
        raise ValueError(f"{name} must be 2-D (rows, cols), got shape {arr.shape}")
    if arr.shape[0] == 0 or arr.shape[1] == 0:
        raise ValueError(f"{name} must not be empty, got shape {arr.shape}")
    out = aligned(np.ascontiguousarray(arr, dtype=np.float64))
    lowest = float(out.min())
    if np.isnan(lowest):
        raise ValueError(f"{name} must not contain NaN (found at {_first(np.isnan(out))})")
    # -inf is < 1 as well, so this also rejects it.
    if lowest < 1.0:
        raise ValueError(
            f"{name} must be >= 1 where traversable (np.inf marks impassable cells); "
            f"found {lowest} at {_first(out == lowest)}" + (_FREE_IS_ZERO if lowest >= 0 else "")
        )
    return out, lowest


# Occupancy arrays and Nav2 costmaps use 0 for free space, which a cost grid cannot.
_FREE_IS_ZERO = (
    " (an occupancy array or a Nav2 costmap, where 0 means free, is not a cost grid: "
    "make one with navkit.mapping.traversal_costs(grid) or np.where(occupied, np.inf, 1.0))"
)


def _not_costs_hint(costs: object, dtype: np.dtype[np.generic]) -> str:
    """The rest of the message refusing a non-numeric ``costs``: what it got and the fix."""
    if dtype == np.bool_:
        return (
            "dtype bool (an occupancy mask is not a cost grid: use "
            "np.where(occupied, np.inf, 1.0))"
        )
    # Duck-typed by name: this module sits below mapping and cannot import it.
    kind = type(costs).__name__
    if kind == "OccupancyGrid":
        return (
            "an OccupancyGrid (make a cost grid with navkit.mapping.traversal_costs(grid), "
            "or plan on the map in metres with MapPlanner)"
        )
    if kind == "LocalGrid":
        # traversal_costs and MapPlanner take an OccupancyGrid only.
        return (
            "a LocalGrid (make a cost grid from its mask: "
            "np.where(grid.occupied, np.inf, 1.0))"
        )
    return f"dtype {dtype}"


def _real_numbers(arr: NDArray[Any]) -> bool:
    """Whether an object array holds only real numbers (no bools, strings, None)."""
    items: list[object] = arr.ravel().tolist()
    return all(
        isinstance(item, numbers.Real) and not isinstance(item, (bool, np.bool_))
        for item in items
    )


def _first(mask: NDArray[np.bool_]) -> tuple[int, ...]:
    """``(row, col)`` of the first True cell of ``mask``."""
    return tuple(int(i) for i in np.unravel_index(int(np.argmax(mask)), mask.shape))
