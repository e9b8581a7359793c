"""JPS on a grid with no traversable cell (review 44, MUTANT19's mutant #24).

Every traversable cell costs the same when there is none: JPS is accepted, as
for any uniform grid, and a plan names the impassable start. Dropping the
all-impassable case from the uniformity check refused the planner instead, and
no test noticed.
"""

from __future__ import annotations

import numpy as np
import pytest

from navkit.planning import AStarPlanner


@pytest.mark.parametrize("shape", [(1, 1), (3, 3), (2, 5)])
def test_jps_is_accepted_on_a_grid_with_no_traversable_cell(shape: tuple[int, int]) -> None:
    planner = AStarPlanner(np.full(shape, np.inf), method="jps")
    assert planner.method == "jps"
    with pytest.raises(ValueError, match=r"start_cell \(0, 0\) is on an impassable cell"):
        planner.plan((0, 0), (shape[0] - 1, shape[1] - 1))
