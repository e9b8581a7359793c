"""Array type aliases used across navkit (private)."""

from __future__ import annotations

from collections.abc import Sequence
from typing import SupportsIndex

import numpy as np
from numpy.typing import NDArray

FloatArray = NDArray[np.float64]
"""A float64 array."""

IntArray = NDArray[np.int64]
"""An int64 array."""

BoolArray = NDArray[np.bool_]
"""A boolean array."""

CellLike = Sequence[SupportsIndex]
"""A grid cell ``(row, col)`` as the planners take it: two Python or NumPy integers."""
