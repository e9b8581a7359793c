"""Review 9: LocalGrid.from_points on the outer edges of the grid (found by mutation testing).

Cells are ``round((y + half_width) / resolution)`` (rows) and
``round((x + half_width) / resolution)`` (columns), rounding half up: a point
exactly on the lower outer edge (half a cell below the first centre) is in the
first cell; one exactly on the upper outer edge is outside (it rounds up to
``n``), and "points outside the grid are ignored".
"""

from __future__ import annotations

import numpy as np
import pytest

from navkit.mapping import LocalGrid


@pytest.mark.parametrize(("half_width", "resolution"), [(1.0, 0.5), (1.0, 0.25), (2.0, 1.0)])
def test_points_exactly_on_the_outer_edges(half_width: float, resolution: float) -> None:
    edge = half_width + resolution / 2  # exact in binary for these values
    n = 2 * round(half_width / resolution) + 1
    lower = LocalGrid.from_points(
        [[-edge, 0.0], [0.0, -edge]], half_width=half_width, resolution=resolution
    )
    expected = np.zeros((n, n), dtype=bool)
    expected[n // 2, 0] = expected[0, n // 2] = True
    np.testing.assert_array_equal(lower.occupied, expected)
    upper = LocalGrid.from_points(
        [[edge, 0.0], [0.0, edge]], half_width=half_width, resolution=resolution
    )
    assert not upper.occupied.any()


def test_from_points_marks_exactly_the_cells_world_to_cell_gives_inside_the_grid() -> None:
    # Points on and around every cell edge of a 0.25 m grid, including the outer ones.
    half_width, res = 1.0, 0.25
    ticks = np.arange(-1.5, 1.5001, 0.125)  # edges and centres, exact in binary
    xs, ys = np.meshgrid(ticks, ticks)
    points = np.column_stack([xs.ravel(), ys.ravel()])
    grid = LocalGrid.from_points(points, half_width=half_width, resolution=res)
    expected = np.zeros_like(grid.occupied)
    for x, y in points:
        # The documented rule, by hand: row from y, column from x, half up.
        i = int(np.floor((y + half_width) / res + 0.5))
        j = int(np.floor((x + half_width) / res + 0.5))
        if 0 <= i < expected.shape[0] and 0 <= j < expected.shape[1]:
            expected[i, j] = True
    np.testing.assert_array_equal(grid.occupied, expected)
    assert expected[0].any() and expected[:, 0].any()  # the lower outer edges are hit
