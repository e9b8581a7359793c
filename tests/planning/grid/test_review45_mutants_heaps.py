"""The grid searches' queues where their mutants survived (review 45, MUTANT24).

A mutation review of :mod:`navkit.planning.grid._search_heap`,
:mod:`navkit.planning.grid._dstar_heap` and :mod:`navkit.planning.grid._prefetch`
found these behaviours unpinned:

* ``F_TIE_BITS``: the tests read the constant back (``F_BAND`` is the mask of
  ``F_TIE_BITS`` bits), so clearing 10 bits instead of 12 passed them all,
  though the module documents that 10 still split plateaus at a band's edge
  on open grids. A query that does: with 10 bits A* expanded 1949 cells for a
  path of 168 on an open 256 x 256 grid, with 12 the path alone.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from navkit.planning import AStarPlanner, astar

SQRT2 = math.sqrt(2.0)


@pytest.mark.parametrize("corner_cutting", [False, True])
def test_a_plateau_split_by_a_ten_bit_band_is_expanded_as_the_path_alone(
    corner_cutting: bool,
) -> None:
    """Mutant ``F_TIE_BITS = 10``: 1949 cells expanded (found among 400 random queries)."""
    costs = np.ones((256, 256))
    start, goal = (46, 194), (213, 40)
    path = astar(costs, start, goal, corner_cutting=corner_cutting)
    assert path.expanded == len(path.cells) == 168
    assert math.isclose(path.cost, 13 + 154 * SQRT2, rel_tol=1e-13)
    assert AStarPlanner(costs).plan(start, goal).expanded == 168
