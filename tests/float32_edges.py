"""Float32 log-odds at the edges of the grid's range, for checks of step tables.

The values where a float32 log-odds changes kind (zero, subnormal, the grid's
clipping, where ``exp`` overflows, the grid's range) and those beyond what a
grid holds, with :func:`ulps` to take their float32 neighbours.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

F32 = np.float32
SPECIAL = [
    0.0,
    -0.0,
    1e-45,  # smallest subnormal
    -1e-45,
    1.1754942e-38,  # largest subnormal
    -1.1754942e-38,
    1.1754944e-38,  # smallest normal
    -1.1754944e-38,
    1e-30,
    -1e-30,
    1e-8,
    -1e-8,
    6.906755,  # logit(0.999), the grid's clipping
    -6.906755,
    88.7,  # exp overflows float32 (not float64) around here
    -88.7,
    710.0,  # exp overflows float64
    -710.0,
    1e6,  # the grid's range
    -1e6,
]
BEYOND_GRID = [np.inf, -np.inf, 3.4028235e38, -3.4028235e38, 1.0000001e6, -1.0000001e6]


def ulps(values: NDArray[np.float32], n: int) -> NDArray[np.float32]:
    """``values`` and their neighbours up to ``n`` float32 steps away on each side."""
    out = [values]
    down, up = values, values
    for _ in range(n):
        down = np.nextafter(down, F32(-np.inf))
        up = np.nextafter(up, F32(np.inf))
        out += [down, up]
    return np.concatenate(out).astype(F32)
