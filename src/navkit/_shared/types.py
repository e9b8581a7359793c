"""Array type aliases used across navkit (private)."""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

FloatArray = NDArray[np.float64]
"""A float64 array."""

IntArray = NDArray[np.int64]
"""An int64 array."""

BoolArray = NDArray[np.bool_]
"""A boolean array."""
