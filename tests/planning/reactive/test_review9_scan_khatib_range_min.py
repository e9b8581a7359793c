"""Review 9: a Khatib scan beam exactly at ``range_min`` counts (mutation-testing gap).

``LaserScan.valid_mask`` keeps ``range_min <= r < range_max``; the piecewise
kernel's thresholds were tested, the Khatib kernel's lower one was not.
"""

from __future__ import annotations

import numpy as np

from navkit.mapping import LaserScan
from navkit.planning.reactive import repulsive_force_from_scan


def test_khatib_beam_at_range_min_counts_and_at_range_max_does_not() -> None:
    k_rep, d0, r = 1.0, 1.0, 0.5
    # Khatib: k_rep·(1/r - 1/d0)/r², pushing away from the beam (angle 0: along -x).
    push = k_rep * (1.0 / r - 1.0 / d0) / (r * r)

    def force(range_min: float, range_max: float) -> np.ndarray:
        scan = LaserScan(np.array([r]), angle_min=0.0, angle_increment=0.1,
                         range_min=range_min, range_max=range_max)
        return repulsive_force_from_scan(scan, k_rep=k_rep, influence_radius=d0)

    assert bool(LaserScan(np.array([r]), angle_min=0.0, angle_increment=0.1,
                          range_min=r, range_max=9.0).valid_mask()[0])
    np.testing.assert_allclose(force(r, 9.0), [-push, 0.0], rtol=1e-12, atol=1e-15)
    np.testing.assert_allclose(force(0.0, 9.0), [-push, 0.0], rtol=1e-12, atol=1e-15)
    np.testing.assert_array_equal(force(0.0, r), [0.0, 0.0])
