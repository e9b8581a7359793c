"""Review 50 (MUTANT30): a point exactly on the map's far edge is off the map.

The correlative search reads the cell ``(int(row), int(col))`` of each point
with ``0 <= row < rows`` and ``0 <= col < cols``; beyond, a point counts as an
unknown cell (1/4, review 50, FOUND2). A mutant that took ``row == rows`` (or
``col == cols``) as on the map survived the suite: it read the cell past the
array's end (the next row's first cell for a column). So did one taking the
interpolation's inner patch up to ``row == rows - 1`` (the last row's centre),
whose row gradient then read the row past the array. Here the grid is a view
of a larger array whose cells past the view are occupied (or free), and the
points lie exactly on its far edges (or the last centres): each counts as
unknown, and the search keeps the guess; the interpolation does not depend
on what lies past the view.
"""

from __future__ import annotations

import numpy as np
import pytest

from navkit.mapping._scan_matcher_kernels import correlative_search, interpolate_batch


@pytest.mark.parametrize(
    ("point", "hidden"),
    [((0.55, 1.0), (10, slice(None))), ((1.0, 0.55), (6, 0))],
    ids=["last-row-edge", "last-column-edge"],
)
def test_a_point_on_the_far_edge_counts_as_unknown(
    point: tuple[float, float], hidden: tuple[object, object]
) -> None:
    big = np.zeros((11, 10), dtype=np.float32)
    big[hidden] = 20.0  # where a read past the view's last row or column lands
    grid = big[:10]
    pose = np.zeros(3)
    points = np.array([point])
    assert point[0] / 0.1 == 10.0 or point[1] / 0.1 == 10.0  # exactly on the edge
    cost = correlative_search(grid, 0.0, 0.0, 0.0, 0.1, points, pose, 3, 0.1, 2, 0.1, 0.0, 0.0)
    assert cost == 0.25
    assert pose.tolist() == [0.0, 0.0, 0.0]


def test_the_last_row_centre_does_not_read_past_the_map() -> None:
    # M, dM/drow, dM/dcol at the last row's centre (row 9 of 10), between columns.
    coords = np.array([[9.0, 4.25], [9.0, 0.0], [4.5, 9.0]])
    out = []
    for past in (20.0, -20.0):
        big = np.zeros((11, 10), dtype=np.float32)
        big[:10, :5] = 3.0  # occupied cells on the left
        big[10] = past
        values = np.zeros((3, 3))
        interpolate_batch(big[:10], coords, values)
        out.append(values)
    np.testing.assert_array_equal(out[0], out[1])
    # Beyond the last centre the neighbours are unknown (1/2): the row gradient at
    # the centre is 1/2 - p of the last row's cells.
    p = 1.0 / (1.0 + np.exp(-np.float64(np.float32(3.0))))
    assert out[0][1, 1] == pytest.approx(0.5 - p, rel=1e-6)
