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
And the unclipped mutant of the same window's lower coordinate: overflow to inf.
Checked: fails on each mutant, passes on HEAD.
"""

from __future__ import annotations

import numpy as np
import pytest
from shapely.geometry import Point, box

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


def test_geometries_whose_grid_coordinates_overflow_are_rasterised() -> None:
    # Mutant: the window's lower coordinate unclipped (review 43). At 1e-6 m cells a
    # coordinate of 1e303 m is 1e309 cells: inf, and math.ceil(inf) raised OverflowError.
    bounds = (0.0, 0.0, 1e-5, 2e-5)
    far = rasterize_polygons(Point(1e303, 1e-5), bounds=bounds, resolution=1e-6)
    assert far.shape == (20, 10)
    assert not far.occupied().any()
    everywhere = rasterize_polygons(
        box(-1e303, -1e303, 1e303, 1e303), bounds=bounds, resolution=1e-6
    )
    assert everywhere.occupied().all()
