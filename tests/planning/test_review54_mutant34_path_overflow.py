"""Review 54 (MUTANT34): a grid path whose world cost overflows is refused by name.

``Path2D.to_world`` (and ``MapPlanner``, through the same conversion) scale a
grid path's cost by the resolution; review 53's tests met only ``to_grid``'s
overflow (a division), so dropping the check on the multiplication passed
them, and a path of cost 1e308 cells on a 10 m map was refused by Path2D's
own check ("cost must be ..."), which does not say why.
"""

from __future__ import annotations

import numpy as np
import pytest

from navkit.mapping import LocalGrid, OccupancyGrid
from navkit.planning import Path2D


@pytest.mark.parametrize("resolution", [10.0, 2.0])
def test_a_cost_overflowing_once_scaled_is_refused_by_name(resolution: float) -> None:
    grid = OccupancyGrid.empty(width=3 * resolution, height=2 * resolution, resolution=resolution)
    path = Path2D([[0.0, 0.0], [1.0, 1.0]], "grid", cost=1e308, length=2**0.5, expanded=3)
    with pytest.raises(ValueError, match=r"cost 1e\+308 overflows float64 multiplied by"):
        path.to_world(grid)
    # A cost that scales to a finite one converts.
    fits = Path2D([[0.0, 0.0], [1.0, 1.0]], "grid", cost=1e307, length=2**0.5, expanded=3)
    assert fits.to_world(grid).cost == 1e307 * resolution


def test_a_local_grid_path_overflowing_is_refused_too() -> None:
    local = LocalGrid.from_points(np.empty((0, 2)), half_width=20.0, resolution=10.0)
    path = Path2D([[0.0, 0.0], [1.0, 1.0]], "grid", cost=1e308, length=2**0.5, expanded=0)
    with pytest.raises(ValueError, match="overflows float64"):
        path.to_world(local)
