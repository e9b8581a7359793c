"""Grid-search paths the default suite never ran (coverage review, session 30).

* ``AStarPlanner`` given NumPy scalars for its options (``np.int64(8)`` read
  from a config array, ``np.float64(1.0)``, ``np.bool_``) misses the one-pass
  fast path that builds jump point search's tables with the cost check, and
  builds them in ``_setup`` instead: the same tables, the same plans.
* ``distance_field`` on costs too wide for the bucket queue runs Dijkstra on a
  heap; a wavefront longer than the thread's queue (4096 entries at first) grows
  it and searches again.
* ``FieldDStar.update_costs`` refuses cells of the wrong shape, naming ``cells``.
"""

from __future__ import annotations

import threading
from typing import Any

import numpy as np
import pytest

import navkit.planning.grid._workspace as workspace
from navkit.planning import AStarPlanner, FieldDStar, distance_field


def _walled() -> np.ndarray:
    costs = np.ones((40, 60))
    costs[5:35, 30] = np.inf
    return costs


@pytest.mark.parametrize("method", ["jps", "auto"])
@pytest.mark.parametrize(
    "options",
    [
        {"connectivity": np.int64(8)},
        {"heuristic_weight": np.float64(1.0)},
        {"corner_cutting": np.bool_(False)},
    ],
)
def test_numpy_scalar_options_plan_by_jump_points_as_python_ones(
    method: str, options: dict[str, Any]
) -> None:
    costs = _walled()
    reference = AStarPlanner(costs, method="jps").plan((20, 5), (20, 55))
    path = AStarPlanner(costs, method=method, **options).plan((20, 5), (20, 55))
    np.testing.assert_array_equal(path.points, reference.points)
    assert (path.cost, path.length, path.expanded) == (
        reference.cost,
        reference.length,
        reference.expanded,
    )
    # JPS expands a handful of jump points here, A* hundreds of cells.
    assert path.expanded < 20
    assert AStarPlanner(costs, method="astar").plan((20, 5), (20, 55)).expanded > 100


def test_numpy_scalar_options_still_refuse_jps_on_varying_costs() -> None:
    costs = _walled()
    costs[0, 0] = 2.0
    with pytest.raises(ValueError, match="method='jps' needs every traversable cell"):
        AStarPlanner(costs, connectivity=np.int64(8), method="jps")
    auto = AStarPlanner(costs, connectivity=np.int64(8), method="auto")
    assert auto.plan((20, 5), (20, 55)).expanded > 100  # A*, not JPS


def test_a_wavefront_longer_than_the_queue_grows_it_and_stays_exact() -> None:
    # A cheap row beside an expensive one, searched from its end: every cell of the
    # expensive row waits in the queue while the cheap row is walked (9000 entries).
    m = 9000
    costs = np.full((2, m), 1e5)
    costs[0] = 1.0
    before = costs.copy()
    j = np.arange(m, dtype=np.float64)
    expected = np.vstack([j, j + (1.0 + 1e5) / 2.0])  # along row 0, then one step up
    got: dict[str, Any] = {}

    def fresh_thread() -> None:  # a new thread starts with the smallest queue
        start = workspace._local.heap.size
        got["field"] = distance_field(costs, (0, 0))
        got["sizes"] = (start, workspace._local.heap.size)

    thread = threading.Thread(target=fresh_thread)
    thread.start()
    thread.join()
    start, end = got["sizes"]
    assert end > start  # the case did fill the first queue
    np.testing.assert_array_equal(got["field"], expected)
    np.testing.assert_array_equal(AStarPlanner(costs).distance_field((0, 0)), expected)
    np.testing.assert_array_equal(costs, before)


@pytest.mark.parametrize(
    "cells",
    [[1, 2, 3], [[1, 2, 3]], np.zeros((2, 2, 2), dtype=np.int64)],
    ids=["three", "row-of-three", "3-d"],
)
def test_update_costs_refuses_cells_of_the_wrong_shape(cells: Any) -> None:
    planner = FieldDStar(_walled())
    before = np.array(cells, copy=True)
    with pytest.raises(ValueError, match=r"^cells must have shape \(M, 2\) or \(2,\), got \("):
        planner.update_costs(cells, 5.0)
    np.testing.assert_array_equal(np.asarray(cells), before)
    # Nothing was changed: the planner still plans around the wall at cost 1.
    path = planner.plan((20, 5), (20, 55))
    assert np.isfinite(path.cost)
    np.testing.assert_array_equal(planner.costs, _walled())
