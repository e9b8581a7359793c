"""Field D*'s list of changed cells stays bounded by the grid between searches.

``update_costs`` listed every changed cell, repeats included, until the next
search: a costmap updated far more often than the plan is repaired grew the
list (and the next repair's requeue) with the number of updates.
"""

from __future__ import annotations

import numpy as np

from navkit.planning import FieldDStar


def test_many_updates_between_searches_keep_the_list_bounded_and_the_repair_exact() -> None:
    rows, cols = 12, 15
    costs = np.ones((rows, cols))
    planner = FieldDStar(costs)
    planner.plan((0, 0), (rows, cols))
    rng = np.random.default_rng(7)
    cells = np.column_stack((rng.integers(2, rows - 2, 40), rng.integers(2, cols - 2, 40)))
    final = costs.copy()
    for k in range(400):
        value = 1.0 + (k % 3)
        planner.update_costs(cells, value)
        final[cells[:, 0], cells[:, 1]] = value
        # Each update lists at most the grid's cells once more beyond the bound.
        assert int(planner._changed[0]) <= 2 * rows * cols + cells.shape[0]
    repaired = planner.replan()
    fresh = FieldDStar(final).plan((0, 0), (rows, cols))
    assert repaired.cost == fresh.cost
    np.testing.assert_array_equal(repaired.points, fresh.points)
