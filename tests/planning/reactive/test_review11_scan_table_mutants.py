"""repulsive_force_from_scan's beam-table shortcut keys on the scanner geometry (mutation testing).

The last table is reused when ``angle_min``, ``angle_increment`` and the beam
count agree. Storing the first two swapped went unnoticed: it only recomputed
the table on every call, until a scanner whose ``angle_min`` is the other's
increment (and vice versa) got the other's beam directions.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from navkit.mapping import LaserScan
from navkit.planning import repulsive_force_from_scan


def _khatib_sum(ranges: list[float], angle_min: float, inc: float, d0: float) -> np.ndarray:
    """The documented per-beam sum, k_rep = 1, every beam valid and within d0."""
    f = np.zeros(2)
    for k, r in enumerate(ranges):
        theta = angle_min + k * inc
        mag = (1.0 / r - 1.0 / d0) / (r * r)
        f -= mag * np.array([math.cos(theta), math.sin(theta)])
    return f


@pytest.mark.parametrize("order", [(0, 1), (1, 0)])
def test_scanners_with_swapped_angle_min_and_increment_keep_their_own_directions(
    order: tuple[int, int],
) -> None:
    ranges = [0.4, 0.6, 0.5]
    geometries = [(0.1, 0.5), (0.5, 0.1)]
    for which in order:
        angle_min, inc = geometries[which]
        scan = LaserScan(ranges, angle_min=angle_min, angle_increment=inc,
                         range_min=0.05, range_max=10.0)
        for _ in range(2):  # the second call takes the remembered table
            got = repulsive_force_from_scan(scan, k_rep=1.0, influence_radius=1.0)
            want = _khatib_sum(ranges, angle_min, inc, 1.0)
            np.testing.assert_allclose(got, want, rtol=1e-12, atol=0.0)
