"""What the planners' error hints claim is true (review 11).

* A ``LocalGrid`` given as ``costs`` was told to use ``traversal_costs(grid)``
  or ``MapPlanner``, both of which refuse a LocalGrid; the hint now gives a fix
  that works, which this test runs.
* MapPlanner's "the map covers x in [...]" printed 6 significant digits: a map
  at UTM-size coordinates read ``[4.51235e+06, 4.51235e+06]``, an extent the
  refused point seemed to lie in.
"""

from __future__ import annotations

import re

import numpy as np
import pytest

from navkit.geometry import Pose2D
from navkit.mapping import LocalGrid, OccupancyGrid
from navkit.planning import MapPlanner, astar


def test_the_local_grid_costs_hint_names_a_fix_that_works() -> None:
    grid = LocalGrid(np.zeros((5, 5), dtype=bool), resolution=0.1, half_width=0.2)
    with pytest.raises(ValueError, match="costs") as err:
        astar(grid, (0, 0), (4, 4))  # type: ignore[arg-type]
    text = str(err.value)
    assert "LocalGrid" in text
    assert "traversal_costs" not in text and "MapPlanner" not in text
    fix = re.search(r"(np\.where\(grid\.occupied, np\.inf, 1\.0\))", text)
    assert fix is not None
    costs = eval(fix.group(1), {"np": np, "grid": grid})  # the hint's own code
    assert astar(costs, (0, 0), (4, 4)).points.shape[1] == 2


def test_the_map_extent_of_a_far_away_map_is_printed_exactly() -> None:
    origin = Pose2D(4512345.2, 512345.6, 0.0)
    grid = OccupancyGrid.from_probabilities(np.zeros((20, 20)), resolution=0.05, origin=origin)
    goal = [4512346.5, 512345.9]  # 0.3 m east of the map
    with pytest.raises(ValueError, match="goal") as err:
        MapPlanner(grid).plan([4512345.5, 512345.9], goal)
    found = re.search(r"x in \[(\S+), (\S+)\] m and y in \[(\S+), (\S+)\] m", str(err.value))
    assert found is not None
    x_lo, x_hi, y_lo, y_hi = (float(v) for v in found.groups())
    assert x_lo == pytest.approx(origin.x, abs=1e-6)
    assert x_hi == pytest.approx(origin.x + 1.0, abs=1e-6)
    assert y_lo == pytest.approx(origin.y, abs=1e-6)
    assert y_hi == pytest.approx(origin.y + 1.0, abs=1e-6)
    assert not x_lo <= goal[0] <= x_hi  # the printed extent excludes the refused goal
