"""Validate once, query many: a prepared A* planner on a 4096 x 4096 grid.

Run with ``python -m pytest benchmarks/test_bench_prepared.py --benchmark-only``.

The grid is 4096 x 4096 (16.8 M cells), 20 % random obstacles (seeded); the
query runs 10 cells along a row from the centre (start and goal forced free),
so the search itself expands a handful of cells. Timed per query:

* ``navkit-prepared``: :meth:`AStarPlanner.plan` on a planner built once (the
  grid validated, converted and its minimum found in the constructor);
* ``navkit-one-shot``: :func:`astar`, which validates the 16.8 M-cell grid on
  every call (the query the issue measured at 6.5 ms);
* ``navkit-one-shot-float32``: :func:`astar` on a float32 copy of the grid,
  which the one-shot form also converts to float64 on every call;
* ``tcod-pathfinder``: tcod's prepared ``Pathfinder`` on a ``SimpleGraph``
  (cardinal 2, diagonal 3: its integer octile) built once; each query resets
  the distances (``clear()``, O(cells)), adds the root and resolves to the goal
  with its A* heuristic;
* ``tcod-astar``: a ``tcod.path.AStar`` built once, ``get_path`` per query.

The constructor time of each prepared form is in ``extra_info``
(``prepare_s``), as are the expansions of navkit's search.

``test_distance_field_vs_scipy`` (issue 17) times :func:`distance_field` (one-shot,
validation included) against ``scipy.sparse.csgraph.dijkstra`` from the same goal on
the same graph (8-connected, no corner cutting, move cost
``step * (c_u + c_v) / 2``), its CSR matrix built outside the timer, on the
1024 x 1024 maps of ``test_bench_astar.py`` (random 20 %, random 35 %, rooms) and
a random-cost map (costs 1-10, 10 % blocked); the fields are checked equal.
"""

from __future__ import annotations

import math
import time
from functools import cache
from typing import Any

import numpy as np
import pytest
import scipy.sparse
from scipy.sparse.csgraph import dijkstra

from navkit.planning import AStarPlanner, astar, distance_field
from test_bench_astar import fresh_copy, peer, timed_fresh

try:
    import tcod.path
except ImportError:  # a peer from the bench extra: its tests skip (peer())
    tcod = None

SIZE = 4096
# Rounds of the one-shot queries (timed_fresh: a new 64-128 MB copy of the map each).
ONE_SHOT_ROUNDS = 10
START = (SIZE // 2, SIZE // 2)
GOAL = (SIZE // 2, SIZE // 2 + 10)
SQRT2 = math.sqrt(2.0)


@cache
def big_map() -> np.ndarray:
    rng = np.random.default_rng(4096)
    costs = np.where(rng.random((SIZE, SIZE)) < 0.20, np.inf, 1.0)
    costs[START] = costs[GOAL] = 1.0
    costs.flags.writeable = False
    return costs


@cache
def prepared() -> tuple[AStarPlanner, float]:
    t0 = time.perf_counter()
    planner = AStarPlanner(big_map())
    return planner, time.perf_counter() - t0


def check_cells(cells: np.ndarray, corner_cutting: bool) -> float:
    """Check a START → GOAL cell path move by move; its recomputed cost."""
    from test_bench_movingai import assert_valid_path

    cost, _ = assert_valid_path(
        big_map(), np.asarray(cells), START, GOAL, corner_cutting=corner_cutting
    )
    return float(cost)


@cache
def least_cost(corner_cutting: bool) -> float:
    """The query's least cost: navkit's one-shot path, checked move by move (no cut: the
    default of every navkit contestant)."""
    path = astar(big_map(), START, GOAL, corner_cutting=corner_cutting)
    assert path.cost == pytest.approx(check_cells(path.cells, corner_cutting), rel=1e-12)
    return float(path.cost)


def test_navkit_prepared(benchmark: Any) -> None:
    planner, prepare_s = prepared()
    # Also allocates the thread's scratch arrays once, outside the timer.
    assert planner.plan(START, GOAL).cost == least_cost(False)
    benchmark.group = "4096^2 10-cell query"
    path = benchmark(planner.plan, START, GOAL)
    benchmark.extra_info.update(
        prepare_s=prepare_s, expanded=path.expanded, cost=path.cost, cells=len(path.points)
    )


def one_shot(benchmark: Any, costs: np.ndarray) -> Any:
    """Time one-shot ``astar`` on ``costs``, each round on a new read-only copy (made
    outside the timer), every round's cost checked (:func:`timed_fresh`): a one-shot
    call that kept its tables for the array would time as the prepared planner."""
    want = least_cost(False)
    assert astar(costs, START, GOAL).cost == want
    benchmark.group = "4096^2 10-cell query"

    def check(_args: tuple[Any, ...], path: Any) -> None:
        assert path.cost == want

    return timed_fresh(
        benchmark,
        lambda c: astar(c, START, GOAL),
        lambda: (fresh_copy(costs),),
        check,
        rounds=ONE_SHOT_ROUNDS,
    )


def test_navkit_one_shot(benchmark: Any) -> None:
    path = one_shot(benchmark, big_map())
    benchmark.extra_info.update(expanded=path.expanded, cost=path.cost)


def test_navkit_one_shot_float32(benchmark: Any) -> None:
    path = one_shot(benchmark, big_map().astype(np.float32))
    benchmark.extra_info.update(expanded=path.expanded, cost=path.cost)


def test_tcod_pathfinder(benchmark: Any) -> None:
    peer("tcod")
    passable = np.isfinite(big_map()).astype(np.int8)
    t0 = time.perf_counter()
    graph = tcod.path.SimpleGraph(cost=passable, cardinal=2, diagonal=3)
    finder = tcod.path.Pathfinder(graph)
    prepare_s = time.perf_counter() - t0

    def query() -> np.ndarray:
        finder.clear()
        finder.add_root(START)
        path: np.ndarray = finder.path_to(GOAL)
        return path

    # Its own integer octile costs: a valid path (tcod cuts corners) is what it owes.
    check_cells(query(), True)
    benchmark.group = "4096^2 10-cell query"
    path = benchmark(query)
    benchmark.extra_info.update(prepare_s=prepare_s, cells=len(path))


def test_tcod_astar(benchmark: Any) -> None:
    peer("tcod")
    passable = np.isfinite(big_map()).astype(np.int8)
    t0 = time.perf_counter()
    finder = tcod.path.AStar(passable, diagonal=SQRT2)
    prepare_s = time.perf_counter() - t0
    # Octile costs with corners cut: the least cost of that graph.
    cells = np.array([START, *finder.get_path(*START, *GOAL)])
    assert check_cells(cells, True) == pytest.approx(least_cost(True), rel=1e-9)
    benchmark.group = "4096^2 10-cell query"
    steps = benchmark(finder.get_path, *START, *GOAL)
    benchmark.extra_info.update(prepare_s=prepare_s, cells=len(steps) + 1)


@pytest.mark.parametrize("what", ["prepared", "one-shot"])
def test_navkit_distance_field_1024(benchmark: Any, what: str) -> None:
    """Whole-grid Dijkstra (1024 x 1024 view of the map): the O(cells) answer itself
    dominates, so preparing saves only the validation pass."""
    costs = np.array(big_map()[:1024, :1024])
    goal = (512, 512)
    costs[goal] = 1.0
    benchmark.group = "1024^2 distance field"
    want = distance_field(costs, goal)
    if what == "prepared":
        planner = AStarPlanner(costs)
        np.testing.assert_allclose(planner.distance_field(goal), want, rtol=1e-12)
        field = benchmark(planner.distance_field, goal)
    else:
        field = benchmark(distance_field, costs, goal)
    benchmark.extra_info["reachable"] = int(np.isfinite(field).sum())


def _csr_graph(costs: np.ndarray) -> scipy.sparse.csr_matrix:
    """navkit's 8-connected graph without corner cutting as a symmetric CSR matrix."""
    rows, cols = costs.shape
    free = np.isfinite(costs)
    index = np.arange(rows * cols).reshape(rows, cols)
    src, dst, weight = [], [], []
    for dr, dc in ((0, 1), (1, 0), (1, 1), (1, -1)):
        r0, r1 = 0, rows - dr
        c0, c1 = max(0, -dc), cols - max(0, dc)
        a = (slice(r0, r1), slice(c0, c1))
        b = (slice(r0 + dr, r1 + dr), slice(c0 + dc, c1 + dc))
        ok = free[a] & free[b]
        if dr and dc:
            ok &= free[r0 + dr : r1 + dr, c0:c1] & free[r0:r1, c0 + dc : c1 + dc]
        step_half = SQRT2 * 0.5 if dr and dc else 0.5
        w = step_half * (costs[a] + costs[b])
        src.append(index[a][ok])
        dst.append(index[b][ok])
        weight.append(w[ok])
    s, d, w = np.concatenate(src), np.concatenate(dst), np.concatenate(weight)
    n = rows * cols
    return scipy.sparse.csr_matrix(
        (np.concatenate((w, w)), (np.concatenate((s, d)), np.concatenate((d, s)))), shape=(n, n)
    )


@cache
def _field_map(name: str) -> np.ndarray:
    if name == "weighted":
        rng = np.random.default_rng(17)
        costs = rng.integers(1, 11, size=(1024, 1024)).astype(np.float64)
        costs[rng.random((1024, 1024)) < 0.10] = np.inf
    else:
        from test_bench_astar import benchmark_map

        costs = np.array(benchmark_map(name))
    costs[512, 512] = 1.0
    costs.flags.writeable = False
    return costs


@pytest.mark.parametrize("name", ["random20", "random35", "rooms", "weighted"])
@pytest.mark.parametrize("contestant", ["navkit", "scipy"])
def test_distance_field_vs_scipy(benchmark: Any, name: str, contestant: str) -> None:
    costs = _field_map(name)
    goal = (512, 512)
    benchmark.group = f"1024^2 distance field, {name}"
    graph = _csr_graph(costs)
    kwargs = {"directed": True, "indices": goal[0] * 1024 + goal[1]}
    # Before timing: both fields equal (same reachable cells, costs to 1e-12).
    np.testing.assert_allclose(
        dijkstra(graph, **kwargs), distance_field(costs, goal).ravel(), rtol=1e-12
    )
    if contestant == "navkit":
        field = benchmark.pedantic(distance_field, (costs, goal), rounds=5, warmup_rounds=1)
        benchmark.extra_info["reachable"] = int(np.isfinite(field).sum())
    else:
        benchmark.pedantic(dijkstra, (graph,), kwargs, rounds=5)
