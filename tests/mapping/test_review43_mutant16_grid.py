"""``OccupancyGrid`` behaviour past its block sizes and at conversion edges (review 43, mutants).

Mutants of ``navkit.mapping._grid`` that the suite let pass, each named at its test.
Checked: each test fails on its mutant, passes on HEAD.
"""

from __future__ import annotations

import numpy as np
import pytest

from navkit.mapping import OccupancyGrid
from navkit.mapping._logodds import P_MAX, P_MIN


@pytest.mark.parametrize("shape", [(300, 300), (3, 70_000)])
def test_from_probabilities_past_one_block_is_the_whole_grids_logodds(
    shape: tuple[int, int],
) -> None:
    # _probability_logodds works in blocks of 2**16 cells; the mutant that stepped one
    # row too far between blocks left rows as np.empty made them. Oracle: the
    # docstring's whole-grid expression, rounded to float32 once.
    rng = np.random.default_rng(43)
    p = rng.random(shape)
    p[0, :3] = [0.0, 1.0, 0.5]
    grid = OccupancyGrid.from_probabilities(p, resolution=0.1)
    clipped = np.clip(p, P_MIN, P_MAX)
    expected = np.log(clipped / (1.0 - clipped)).astype(np.float32)
    assert np.array_equal(grid.logodds, expected)
