"""Review 54 (MUTANT34): the walk past an edge point rounded to a corner value, on every drawing.

Field D*'s walk, stopped at a point inside an edge whose interpolated value
rounded to exactly a corner's, takes a straight step below the value of the
last node passed (the walk's mode 2, review 53). ``test_grid_limits`` checks
it on one drawing of the grid found by random search, whose point lies on a
vertical grid line; taking a point on a horizontal line for a node (testing
only its row) passed it, and the transposed grid's walk then failed to reach
the goal (RuntimeError). Node values are the same floats in every drawing
(review 41), so each of the eight must walk to the goal.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from navkit.planning import field_dstar

INF = math.inf

# test_grid_limits.ROUNDED_EDGE_GRID: costs of 1e9 next to ~5, found by random search.
GRID = np.array(
    [
        [INF, 2602830.6646243823, 77.90996070854636, 1e9, 294.0347524131588, INF,
         1493043.7007096678, 1349790.0740335411],
        [1e9, 1e9, 1e9, 1e9, 2.887345915739406, 1e9, 20898.515234943847, 510.2349828735274],
        [1e9, 23339.94418941429, 33801419.90732689, 304.170811580372, 1e9, 5.383097732341978,
         1e9, 9835.706126592318],
        [9847.333897046583, 3191.8276974052865, 234191.15533415225, 78598617.0806656,
         450039545.0371566, 311.681275027267, 126138.72152654406, INF],
        [1368.577284836821, 3.402068764853022, 1e9, 833120.1043443613, 1e9, INF, 1e9,
         258.05718899705874],
    ]
)  # fmt: skip


def _drawing(k: int, transpose: bool) -> tuple[np.ndarray, tuple[int, int], tuple[int, int]]:
    """The grid and its start (2, 5) and goal (5, 5) nodes, flipped by ``k`` and transposed."""
    costs = GRID
    rows, cols = GRID.shape
    ends = [(2, 5), (5, 5)]
    if k & 1:
        costs = costs[::-1]
        ends = [(rows - i, j) for i, j in ends]
    if k & 2:
        costs = costs[:, ::-1]
        ends = [(i, cols - j) for i, j in ends]
    if transpose:
        costs = costs.T
        ends = [(j, i) for i, j in ends]
    return np.ascontiguousarray(costs), ends[0], ends[1]


@pytest.mark.parametrize("transpose", [False, True])
@pytest.mark.parametrize("k", range(4))
def test_every_drawing_walks_to_the_goal(k: int, transpose: bool) -> None:
    costs, start, goal = _drawing(k, transpose)
    path = field_dstar(costs, start, goal)
    assert path.points[0].tolist() == [start[0] - 0.5, start[1] - 0.5]
    assert path.points[-1].tolist() == [goal[0] - 0.5, goal[1] - 0.5]
    exact = field_dstar(costs, start, goal, interpolate=False)
    assert path.cost <= exact.cost * (1 + 1e-9)
    # The same cost on every drawing, to rounding.
    first = field_dstar(GRID, (2, 5), (5, 5))
    assert path.cost == pytest.approx(first.cost, rel=1e-12)
