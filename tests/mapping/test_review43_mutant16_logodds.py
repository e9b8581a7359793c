"""The log-odds conventions' documented values and ends (review 43, mutants of ``_logodds``).

Mutants of ``navkit.mapping._logodds`` that the suite let pass: OctoMap's
clamping probabilities 0.12 / 0.97 changed to 0.10 or 0.98, map_server's
``free_thresh`` 0.196 changed to 0.2, and :func:`logit_bound`'s ends
(``p <= 0`` gives -inf, ``p >= 1`` gives +inf) turned into ``<`` / ``>`` or
a wrong sign: no test asked for a view at threshold 0 or 1, where the mutants
raise (``log(0)``, a division by zero) or mark the opposite cells.
Oracles: the probabilities the docstrings state (log-odds computed here
from them) and :meth:`OccupancyGrid.probability` compared with the threshold.
Checked: each test fails on its mutants, passes on HEAD.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from navkit.mapping import LaserScan, OccupancyGrid


def test_repeated_scans_saturate_at_octomaps_clamping_probabilities() -> None:
    # One beam along a 1 x 4 row: cells 0..2 are crossed (misses), cell 3 holds the hit.
    grid = OccupancyGrid.empty(width=2.0, height=0.5, resolution=0.5)
    scan = LaserScan([1.4], angle_min=0.0, angle_increment=0.1, range_min=0.1, range_max=3.0)
    for _ in range(60):  # far more than the 5 hits / 4 misses each bound needs
        grid.integrate_scan(scan, (0.25, 0.25, 0.0))
    low = np.float32(math.log(0.12 / 0.88))
    high = np.float32(math.log(0.97 / 0.03))
    assert grid.logodds[0, :3].tolist() == [low] * 3
    assert grid.logodds[0, 3] == high
    assert grid.probability()[0, 3] == pytest.approx(0.97, abs=1e-6)
    assert grid.probability()[0, 0] == pytest.approx(0.12, abs=1e-6)


def test_the_default_free_threshold_is_map_servers_0_196() -> None:
    grid = OccupancyGrid.from_probabilities([[0.195, 0.197, 0.649, 0.651]], resolution=1.0)
    assert grid.free().tolist() == [[True, False, False, False]]
    assert grid.occupied().tolist() == [[False, False, False, True]]
    assert grid.unknown().tolist() == [[False, True, True, False]]


@pytest.mark.parametrize("threshold", [0.0, 1.0])
def test_views_at_thresholds_0_and_1_follow_the_probabilities(threshold: float) -> None:
    # Certain cells (0 and 1) are stored clipped to 0.001 / 0.999: strictly inside (0, 1).
    grid = OccupancyGrid.from_probabilities([[0.0, 0.001, 0.5, 0.999, 1.0]], resolution=1.0)
    p = grid.probability()
    assert grid.occupied(threshold).tolist() == (p > threshold).tolist()
    assert grid.free(threshold).tolist() == (p < threshold).tolist()
    both = grid.unknown(occupied_thresh=1.0, free_thresh=0.0)
    assert both.tolist() == ((p >= 0.0) & (p <= 1.0)).tolist()
    assert bool(both.all())
