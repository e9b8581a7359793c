"""Distance from every cell to the nearest occupied cell, the basis of inflation (private).

Examples
--------
>>> import numpy as np
>>> obstacle_distance(np.array([[True, False, False]]))
array([[0., 1., 2.]])
"""

from __future__ import annotations

import numpy as np

from navkit._shared.types import BoolArray, FloatArray

__all__ = ["CELL_EPS", "obstacle_distance"]

#: Distances compared against radii get this slack (in cells) so that radii that
#: are exact multiples of the resolution include the cells at that distance.
CELL_EPS = 1e-9


def obstacle_distance(occupied: BoolArray) -> FloatArray:
    """Distance in cells from each cell centre to the nearest occupied cell centre.

    Exact Euclidean distance transform; ``inf`` everywhere when nothing is occupied.

    Examples
    --------
    >>> obstacle_distance(np.zeros((1, 2), dtype=bool))
    array([[inf, inf]])
    """
    if not occupied.any():
        return np.full(occupied.shape, np.inf)
    from scipy import ndimage

    return np.asarray(ndimage.distance_transform_edt(~occupied), dtype=np.float64)
