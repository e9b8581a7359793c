"""A point on a cell edge as rounded occupies both cells it touches (review 43, mutants).

``rasterize_polygons`` documents that cell ``k``'s closed square holds
``origin + k * res`` and ``origin + (k + 1) * res`` as rounded. Its candidate
window (``_window``) is one cell wider than exact arithmetic needs because a
rounded edge can lie past the exact one: 0.1 * 3 is 0.30000000000000004, whose
grid coordinate 3.0000000000000004 has ceiling 4. The mutant ``ceil(lo) - 1``
(for ``- 2``) of ``navkit.mapping._rasterize._window`` cut the window at cell 3
and left cell 2 free under a point at 0.1 * 3; the suite's edge tests place
geometry at 0.3 (coordinate exactly 3), so it passed. Oracle: the documented
closed squares (the cells ``k - 1`` and ``k`` on each axis, no other).
Checked: fails on that mutant, passes on HEAD.
"""

from __future__ import annotations

import numpy as np
import pytest
from shapely.geometry import Point

from navkit.mapping import rasterize_polygons


@pytest.mark.parametrize("res", [0.1, 0.05, 0.3, 0.7])
@pytest.mark.parametrize("origin", [0.0, -1.3, 2.1])
def test_a_point_on_rounded_edges_occupies_the_four_cells_around_it(
    res: float, origin: float
) -> None:
    n = 10
    for k in range(1, n):
        edge = origin + k * res  # rounded as the documentation says
        grid = rasterize_polygons(
            Point(edge, edge),
            bounds=(origin, origin, origin + n * res, origin + n * res),
            resolution=res,
        )
        expected = np.zeros(grid.shape, dtype=bool)
        expected[k - 1 : k + 1, k - 1 : k + 1] = True
        assert np.array_equal(grid.occupied(), expected), (k, repr(edge))
