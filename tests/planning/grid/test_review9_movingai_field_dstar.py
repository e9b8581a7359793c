"""Field D* on the MovingAI benchmark maps, against the published optimal lengths.

Map cell ``(r, c)`` to Field D* node ``(r + 1, c + 1)`` (its lower-right corner).
Each MovingAI move (8-connected, no corner cutting) then becomes a node move of
the same cost along an edge or across a passable cell, so the 8-connected node
optimum (``interpolate=False``) is at most the published length; it is checked
exactly against an independent Dijkstra on the node graph. ``interpolate=True``
paths must cost no more than that 8-connected optimum. After cost updates,
:meth:`FieldDStar.replan` must return the path a fresh plan returns.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
import scipy.sparse
from numpy.typing import NDArray
from scipy.sparse.csgraph import dijkstra
from test_movingai import load

from navkit.planning import FieldDStar

MAPS = ["dao/arena2", "street/Berlin_0_256", "street/Boston_0_256", "maze/maze512-1-0"]
PER_MAP = 6


def node_graph(costs: NDArray[np.float64]) -> scipy.sparse.csr_matrix:
    """The 8-connected node graph the Field D* docs describe, built with numpy."""
    rows, cols = costs.shape
    pad = np.full((rows + 2, cols + 2), np.inf)
    pad[1:-1, 1:-1] = costs
    n_rows, n_cols = rows + 1, cols + 1
    index = np.arange(n_rows * n_cols).reshape(n_rows, n_cols)
    # An axis move runs along an edge and pays the cheaper cell beside it.
    along_row = np.minimum(pad[:n_rows, 1:n_cols], pad[1:, 1:n_cols])
    along_col = np.minimum(pad[1:n_rows, :n_cols], pad[1:n_rows, 1:])
    # A diagonal move crosses one cell and pays sqrt(2) times its cost.
    diagonal = math.sqrt(2.0) * costs
    parts = [
        (index[:, :-1], index[:, 1:], along_row),
        (index[:-1, :], index[1:, :], along_col),
        (index[:-1, :-1], index[1:, 1:], diagonal),
        (index[:-1, 1:], index[1:, :-1], diagonal),
    ]
    src = np.concatenate([a[np.isfinite(w)] for a, _, w in parts])
    dst = np.concatenate([b[np.isfinite(w)] for _, b, w in parts])
    weight = np.concatenate([w[np.isfinite(w)] for _, _, w in parts])
    both_ways = (np.concatenate([src, dst]), np.concatenate([dst, src]))
    return scipy.sparse.csr_matrix(
        (np.concatenate([weight, weight]), both_ways), shape=(n_rows * n_cols, n_rows * n_cols)
    )


@pytest.mark.parametrize("name", MAPS)
def test_field_dstar_bounded_by_published_optimum(shared_data: Path, name: str) -> None:
    costs, scenarios = load(shared_data, name)
    graph = node_graph(costs)
    n_cols = costs.shape[1] + 1
    octile = FieldDStar(costs, interpolate=False)
    field = FieldDStar(costs)
    rng = np.random.default_rng(2012)
    for i in rng.choice(len(scenarios), size=PER_MAP, replace=False):
        sc = scenarios[i]
        start = (sc.start[0] + 1, sc.start[1] + 1)
        goal = (sc.goal[0] + 1, sc.goal[1] + 1)
        eight = octile.plan(start, goal).cost
        distances = dijkstra(graph, indices=start[0] * n_cols + start[1])
        reference = distances[goal[0] * n_cols + goal[1]]
        assert eight == pytest.approx(reference, rel=1e-9)
        assert eight <= sc.optimal + 1e-6
        assert field.plan(start, goal).cost <= eight * (1 + 1e-9)


@pytest.mark.parametrize("interpolate", [False, True])
def test_replan_after_updates_equals_fresh_plan(shared_data: Path, interpolate: bool) -> None:
    costs, scenarios = load(shared_data, "street/Berlin_0_256")
    sc = scenarios[len(scenarios) // 2]
    start = (sc.start[0] + 1, sc.start[1] + 1)
    goal = (sc.goal[0] + 1, sc.goal[1] + 1)
    planner = FieldDStar(costs, interpolate=interpolate)
    path = planner.plan(start, goal)
    current = costs.copy()
    rng = np.random.default_rng(7)
    for step in range(4):
        if step % 2 == 0:
            # Raise the cost of cells on the middle of the current path.
            third = len(path.points) // 3
            cells = np.rint(path.points[third : 2 * third]).astype(int)
            cells = np.unique(np.clip(cells, 0, np.array(costs.shape) - 1), axis=0)[:8]
            values = rng.uniform(2.0, 20.0, len(cells))
        else:
            cells = np.column_stack(
                [rng.integers(0, costs.shape[0], 30), rng.integers(0, costs.shape[1], 30)]
            )
            values = np.where(rng.random(30) < 0.5, 1.0, rng.uniform(1.0, 5.0, 30))
            values[np.isinf(current[cells[:, 0], cells[:, 1]])] = np.inf
        planner.update_costs(cells, values)
        current[cells[:, 0], cells[:, 1]] = values
        path = planner.replan()
        fresh = FieldDStar(current, interpolate=interpolate).plan(start, goal)
        np.testing.assert_array_equal(path.points, fresh.points)
        assert path.cost == fresh.cost
