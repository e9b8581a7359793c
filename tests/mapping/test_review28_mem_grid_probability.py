"""OccupancyGrid.probability() allocates its result and nothing of its size more (review 28)."""

from __future__ import annotations

import numpy as np

from memory_peak import peak_bytes
from navkit.mapping import OccupancyGrid


def test_probability_peak_is_its_result_and_values_unchanged() -> None:
    rng = np.random.default_rng(28)
    logodds = rng.normal(0.0, 30.0, (1024, 1024))
    logodds[0, :4] = (0.0, 1e6, -1e6, 88.7)  # p = 0.5, exactly 1 and 0, exp near overflow
    grid = OccupancyGrid(logodds, resolution=0.05)
    stored = grid.logodds.copy()
    peak, p = peak_bytes(grid.probability)
    # 1 / (1 + exp(-l)) as one expression held two float64 grids at once.
    assert peak < 1.3 * p.nbytes, f"peak {peak / 1e6:.1f} MB for a {p.nbytes / 1e6:.1f} MB result"
    with np.errstate(over="ignore"):
        expected = 1.0 / (1.0 + np.exp(-stored.astype(np.float64)))
    assert p.dtype == np.float64
    assert np.array_equal(p, expected)  # bit for bit
    assert p[0, :3].tolist() == [0.5, 1.0, 0.0]
    assert np.array_equal(grid.logodds, stored)
