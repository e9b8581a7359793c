"""SciPy's exact distance transform, the oracle of navkit's, and floats as bits (review 47).

navkit's transform (``distance_transform``, ``OccupancyGrid.obstacle_distance``,
the banded kernels) is SciPy's ``distance_transform_edt`` bit for bit, and ``inf``
everywhere when nothing is occupied. Review 45's and 46's tests each wrote the
oracle and the bit view again.
"""

from __future__ import annotations

import numpy as np
from scipy import ndimage


def scipy_distances(occupied: np.ndarray, resolution: float = 1.0) -> np.ndarray:
    """Distance from each cell centre to the nearest occupied one, in cells times ``resolution``.

    ``inf`` everywhere when nothing is occupied (SciPy has no answer there).
    """
    if not occupied.any():
        return np.full(occupied.shape, np.inf)
    return np.asarray(ndimage.distance_transform_edt(~occupied), dtype=np.float64) * resolution


def float_bits(a: np.ndarray) -> np.ndarray:
    """The float64 values of ``a`` as int64 bit patterns: equal exactly when the floats are."""
    return np.ascontiguousarray(a, dtype=np.float64).view(np.int64)
