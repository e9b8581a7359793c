"""One occupied cell in the centre of a square grid, and the exact discs around it.

Shared by the review 52 float32-resolution tests (PRECISION, MUTANT32): what a
radius of ``k`` cells must reach, by integer arithmetic.
"""

from __future__ import annotations

import numpy as np

from navkit.mapping import OccupancyGrid


def disc(n: int, k: int) -> np.ndarray:
    """Cells of an ``n`` x ``n`` grid within ``k`` cells of its centre cell (n // 2, n // 2)."""
    c = n // 2
    r, q = np.mgrid[0:n, 0:n]
    out: np.ndarray = (r - c) ** 2 + (q - c) ** 2 <= k * k
    return out


def centred_grid(n: int, resolution: float) -> OccupancyGrid:
    """An ``n`` x ``n`` grid of ``resolution`` (m) free but for its centre cell."""
    occ = np.zeros((n, n), dtype=bool)
    occ[n // 2, n // 2] = True
    return OccupancyGrid.from_occupancy(occ, resolution=resolution)
