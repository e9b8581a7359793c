"""Argument checks shared by the grid searches (private)."""

from __future__ import annotations

import math
from typing import Any

import numpy as np
from numpy.typing import NDArray

from navkit._shared.validation import as_cell, bounded_int
from navkit.planning.grid._search_heap import MAX_NODES


def check_connectivity(value: Any) -> bool:
    """Return True for 8-connectivity, False for 4; reject anything else."""
    count = bounded_int(value, "connectivity")
    if count not in (4, 8):
        raise ValueError(f"connectivity must be 4 or 8, got {value!r}")
    return count == 8


def traversable_cell(costs: NDArray[np.float64], value: Any, name: str) -> tuple[int, int]:
    """Convert ``value`` to a ``(row, col)`` inside ``costs`` whose cost is finite."""
    rows, cols = costs.shape
    # Fast path for the common (int, int) tuple: a prepared planner's query
    # costs microseconds, and the general conversion would dominate it.
    if (
        type(value) is tuple
        and len(value) == 2
        and type(value[0]) is int
        and type(value[1]) is int
        and 0 <= value[0] < rows
        and 0 <= value[1] < cols
    ):
        row, col = value
    else:
        row, col = as_cell(value, name, costs.shape)
    if not math.isfinite(costs[row, col]):
        raise ValueError(f"{name} {(row, col)} is on an impassable cell (cost inf)")
    return row, col


def check_search_size(costs: NDArray[np.float64], name: str = "costs") -> None:
    """Reject grids with more cells than the search heap can index (2**31 - 1)."""
    if costs.size > MAX_NODES:
        raise ValueError(
            f"{name} has {costs.size} cells; the grid searches support at most {MAX_NODES}"
        )
