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


@pytest.mark.parametrize(
    ("res", "k", "radius"),
    [
        (1.0, 2, 1.999999999),
        (0.5, 3, 1.4999999995),
        (0.1, 2, 0.1999999999),
        (0.25, 1, 0.24999999975),
    ],
)
def test_inflate_includes_a_cell_exactly_at_the_widened_radius(
    res: float, k: int, radius: float
) -> None:
    # inflate's rule is ``distance <= radius / res + 1e-9`` cells; the mutant ``<`` passed
    # the suite, whose radii never put the widened reach exactly on a cell centre. These
    # radii do (checked first). Oracle: the documented rule; cells_near agrees.
    assert radius / res + 1e-9 == k
    occupied = np.zeros((1, k + 3), dtype=bool)
    occupied[0, 0] = True
    grid = OccupancyGrid.from_occupancy(occupied, resolution=res)
    expected = [True] * (k + 1) + [False] * 2
    assert grid.inflate(radius)[0].tolist() == expected
    near = grid.cells_near(grid.cell_to_world([0, 0]), robot_radius=radius)
    assert near.tolist() == [[0, j] for j in range(k + 1)]
