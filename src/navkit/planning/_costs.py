"""Validation of per-cell traversal-cost arrays shared by every grid planner (private)."""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray


def validate_costs(costs: ArrayLike, name: str = "costs") -> NDArray[np.float64]:
    """Check a traversal-cost grid and return it as a C-contiguous float64 array.

    The planners' convention: a 2-D array indexed ``[row, col]`` whose finite
    values are >= 1 (cost per unit length of crossing the cell) and whose
    ``+inf`` entries are impassable. The input is never modified; it is copied
    only when a dtype or layout conversion is needed.

    Raises
    ------
    ValueError
        Wrong dimension, empty grid, non-numeric or boolean dtype, NaN, ``-inf``
        or finite values below 1.
    """
    arr = np.asarray(costs)
    if arr.dtype == np.bool_ or arr.dtype.kind not in "fiu":
        raise ValueError(f"{name} must be a real-valued numeric array, got dtype {arr.dtype}")
    if arr.ndim != 2:
        raise ValueError(f"{name} must be 2-D (rows, cols), got shape {arr.shape}")
    if arr.shape[0] == 0 or arr.shape[1] == 0:
        raise ValueError(f"{name} must not be empty, got shape {arr.shape}")
    out = np.ascontiguousarray(arr, dtype=np.float64)
    if np.isnan(out).any():
        raise ValueError(f"{name} must not contain NaN")
    # -inf is < 1 as well, so this also rejects it.
    if (out < 1.0).any():
        raise ValueError(f"{name} must be >= 1 where traversable (np.inf marks impassable cells)")
    return out
