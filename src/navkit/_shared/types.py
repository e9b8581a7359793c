"""Array type aliases used across navkit (private)."""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any, SupportsIndex

import numpy as np
from numpy.typing import NDArray

FloatArray = NDArray[np.float64]
"""A float64 array."""

IntArray = NDArray[np.int64]
"""An int64 array."""

BoolArray = NDArray[np.bool_]
"""A boolean array."""

CellLike = Sequence[SupportsIndex] | NDArray[np.integer[Any]]
"""A grid cell ``(row, col)`` as the planners take it: two Python or NumPy integers,
or an integer array of shape (2,) (what ``world_to_cell`` returns for one point)."""
