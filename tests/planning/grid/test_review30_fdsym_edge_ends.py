"""Field D* on mirrored and turned grids (review 30): a crossing point whose
optimum is an edge's end is that end on every drawing; tied walk candidates
leave the node values alone.

The 8 drawings are those of the eighth review's metamorphic tests (the node
grid is one larger than the cell grid, so nodes map as its cells).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterator

import numpy as np
import pytest
from test_review8_grid_metamorphic import _node_symmetry

from navkit.planning import FieldDStar

FloatArray = np.ndarray
Node = tuple[int, int]
inf = math.inf


def _drawings(
    shape: tuple[int, int],
) -> Iterator[tuple[Callable[[FloatArray], FloatArray], Callable[[Node], Node]]]:
    """(cost grid transform, node transform) for the 8 symmetries of the square."""
    yield from _node_symmetry(shape)


# From node (0, 2) the optimal crossing point of the far edge of cell (0, 1) is
# its end, node (1, 1), in exact arithmetic (the stationary point is u = 1: the
# value difference 2*sqrt(2) along the edge over sqrt(4**2 - 8)). On the
# column-flipped grid it came out at u = 1 - 1e-16: the walk stepped to
# (1, 0.9999999999999999), and the segment from there down the column line
# paid the cell beside it (3) instead of the cheaper one (1): 16.657 instead
# of 14.657 on 4 of the 8 drawings.
EDGE_END = np.array(
    [[4.0, 4.0], [1.0, 3.0], [4.0, inf], [5.0, 4.0], [1.0, 5.0], [3.0, inf], [4.0, 2.0]]
)


@pytest.mark.parametrize("lookahead", [False, True])
def test_review30_fdsym_an_edge_end_optimum_is_the_node_on_every_drawing(
    lookahead: bool,
) -> None:
    want = 4.0 * math.sqrt(2.0) + 1.0 + 4.0 + 4.0
    for grid, node in _drawings(EDGE_END.shape):
        path = FieldDStar(grid(EDGE_END), lookahead=lookahead, smooth=False).plan(
            node((0, 2)), node((4, 1))
        )
        assert path.cost == pytest.approx(want, rel=1e-12), path.points.tolist()
        # Every point of this path is a node (grid frame: nodes at half integers).
        nodes = path.points + 0.5
        assert np.array_equal(nodes, np.round(nodes)), nodes.tolist()


# From node (7, 1) the crossing points of the top and the right edge of cell
# (6, 1) tie exactly (its corners (6, 1) and (7, 2) both have value 11): the
# walk takes the one it scans first, and the two continuations cost 16.709 and
# 16.287 (the start's value) on 4 drawings each (the class Notes).
TIED = np.array(
    [[3.0, 4.0, 3.0, 5.0], [2.0, 2.0, 1.0, 4.0], [3.0, 5.0, 1.0, 3.0], [1.0, 1.0, 1.0, 5.0],
     [2.0, 5.0, inf, inf], [inf, 5.0, 1.0, 3.0], [inf, 4.0, 1.0, 3.0], [1.0, 5.0, 2.0, 3.0]]
)


def test_review30_fdsym_tied_walk_candidates_leave_the_node_values_alone() -> None:
    start, goal = (8, 0), (2, 1)
    rows, cols = TIED.shape
    base = FieldDStar(TIED, lookahead=False, smooth=False)
    raw = base.plan(start, goal).cost
    values = base._g.reshape(rows + 1, cols + 1).copy()
    assert values[start] == pytest.approx(16.287196908580512, rel=1e-12)
    assert raw >= values[start] * (1 - 1e-12)
    for grid, node in _drawings(TIED.shape):
        drawn = FieldDStar(grid(TIED), lookahead=False, smooth=False)
        other = drawn.plan(node(start), node(goal)).cost
        # Whichever of the tied candidates the walk took (16.287 or 16.709 here).
        assert values[start] * (1 - 1e-12) <= other <= 16.71
        g = drawn._g.reshape(grid(TIED).shape[0] + 1, grid(TIED).shape[1] + 1)
        for i in range(rows + 1):
            for j in range(cols + 1):
                a, b = values[i, j], g[node((i, j))]
                assert a == b or abs(a - b) <= 1e-12 * max(a, b), ((i, j), a, b)
        # The one-step lookahead (the default) sees past this tie.
        ahead = FieldDStar(grid(TIED), smooth=False).plan(node(start), node(goal)).cost
        assert ahead == pytest.approx(values[start], rel=1e-12)
