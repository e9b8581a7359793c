"""Field D* path walk and expansion count against outside oracles (review 35, mutation testing).

Survivors of the earlier mutation runs of the path kernels, closed here:

* the walk's option D from a node (leave along the cheap edge, then cross the
  expensive cell: Ferguson & Stentz's interpolated step written out in
  ``_candidates``) switched off, and the straight corner step taken even when
  an interpolated step was found: both gave 4.0 where the continuous optimum
  is 1 + 2√2 = 3.83 on the two-cell grid below;
* ``settle`` counting its expansions from twice the work already spent in
  the search, so a fresh plan reported several times more expansions than the
  grid has nodes.

The oracles are independent of the planner: the cheapest way from a corner
of two stacked cells to the far corner of the expensive one minimised over
where the path leaves the shared edge (a one-dimensional convex problem,
solved here by a fine scan refined with golden-section search), and the
documented property that a fresh search expands each node at most once.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from test_review8_grid_metamorphic import _node_symmetry

from navkit.planning import FieldDStar


def _edge_then_cross(b: float, c: float) -> float:
    """min over x in [0, 1] of ``b x + c hypot(1 - x, 1)``, found numerically.

    From a node on the edge shared by a cheap cell (cost ``b``) and an expensive
    one (``c``), the path runs ``x`` along the shared edge (paying the cheaper
    cell) and then straight across the expensive cell to its far corner.
    """

    def f(x: float) -> float:
        return b * x + c * math.hypot(1.0 - x, 1.0)

    xs = np.linspace(0.0, 1.0, 20001)
    vals = b * xs + c * np.hypot(1.0 - xs, 1.0)
    k = int(np.argmin(vals))
    lo = xs[max(k - 1, 0)]
    hi = xs[min(k + 1, len(xs) - 1)]
    g = (math.sqrt(5.0) - 1.0) / 2.0
    for _ in range(80):
        m1 = hi - g * (hi - lo)
        m2 = lo + g * (hi - lo)
        if f(m1) <= f(m2):
            hi = m2
        else:
            lo = m1
    return min(f(lo), f(hi), f(0.0), f(1.0))


@pytest.mark.parametrize(("b", "c"), [(1.0, 3.0), (1.0, 1.5), (2.0, 7.0), (1.0, 1.2), (3.0, 4.5)])
def test_cheap_edge_then_crossing_is_the_continuous_optimum(b: float, c: float) -> None:
    # Two stacked cells: the expensive one on top, the cheap one below. From the
    # node between them on the left (1, 0) to the top right node (0, 1) the
    # cheapest path runs along the shared edge, then across the top cell; there
    # is no other way (the cheap cell lies away from the goal), so Field D*'s
    # interpolation finds the exact optimum on every drawing of the grid.
    costs = np.array([[c], [b]])
    expected = _edge_then_cross(b, c)
    assert expected <= min(b + c, c * math.sqrt(2.0)) + 1e-12
    transforms = list(_node_symmetry((costs.shape[0], costs.shape[1])))
    assert len(transforms) == 8
    for grid_t, node_t in transforms:
        path = FieldDStar(grid_t(costs)).plan(node_t((1, 0)), node_t((0, 1)))
        assert path.cost == pytest.approx(expected, rel=1e-12, abs=1e-12)
        if c > math.sqrt(2.0) * b:
            # The optimum leaves the edge inside it: the path bends there.
            assert len(path.points) == 3


def test_option_d_beats_the_corner_paths_on_a_larger_grid() -> None:
    # The same two cells inside a field of impassable ones: nothing else changes.
    inf = math.inf
    costs = np.full((4, 5), inf)
    costs[1, 2] = 3.0
    costs[2, 2] = 1.0
    path = FieldDStar(costs).plan((2, 2), (1, 3))
    assert path.cost == pytest.approx(_edge_then_cross(1.0, 3.0), rel=1e-12)
    assert path.cost < 4.0 - 0.1


@pytest.mark.parametrize("interpolate", [True, False])
@pytest.mark.parametrize("seed", range(6))
def test_a_fresh_plan_expands_each_node_at_most_once(interpolate: bool, seed: int) -> None:
    # The class documents that each node is expanded once in a fresh search (its
    # heuristic never lets an interpolated node go before the neighbours its cost
    # depends on), so a fresh plan's expansion count cannot exceed the number of
    # nodes, whichever way its ends are given.
    rng = np.random.default_rng(seed)
    rows, cols = (int(v) for v in rng.integers(4, 14, size=2))
    costs = rng.uniform(1.0, 5.0, size=(rows, cols))
    nodes = (rows + 1) * (cols + 1)
    planner = FieldDStar(costs, interpolate=interpolate)
    far = planner.plan((0, 0), (rows, cols))
    assert 1 <= far.expanded <= nodes
    cells = planner.plan_cells((0, 0), (rows - 1, cols - 1))
    assert 1 <= cells.expanded <= nodes
    a = (int(rng.integers(0, rows + 1)), int(rng.integers(0, cols + 1)))
    z = (int(rng.integers(0, rows + 1)), int(rng.integers(0, cols + 1)))
    if a != z:
        some = planner.plan(a, z)
        assert 1 <= some.expanded <= nodes
        # The same search on a new planner counts the same.
        assert FieldDStar(costs, interpolate=interpolate).plan(a, z).expanded == some.expanded
