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
"""

from __future__ import annotations

import math
import time
from functools import cache
from typing import Any

import numpy as np
import pytest
import tcod.path

from navkit.planning import AStarPlanner, astar, distance_field

SIZE = 4096
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


def test_navkit_prepared(benchmark: Any) -> None:
    planner, prepare_s = prepared()
    planner.plan(START, GOAL)  # the thread's scratch arrays are allocated once
    benchmark.group = "4096^2 10-cell query"
    path = benchmark(planner.plan, START, GOAL)
    benchmark.extra_info.update(
        prepare_s=prepare_s, expanded=path.expanded, cost=path.cost, cells=len(path.points)
    )
    assert path.cost == astar(big_map(), START, GOAL).cost


def test_navkit_one_shot(benchmark: Any) -> None:
    costs = big_map()
    astar(costs, START, GOAL)
    benchmark.group = "4096^2 10-cell query"
    path = benchmark(astar, costs, START, GOAL)
    benchmark.extra_info.update(expanded=path.expanded, cost=path.cost)


def test_navkit_one_shot_float32(benchmark: Any) -> None:
    costs = big_map().astype(np.float32)
    benchmark.group = "4096^2 10-cell query"
    path = benchmark(astar, costs, START, GOAL)
    benchmark.extra_info.update(expanded=path.expanded, cost=path.cost)


def test_tcod_pathfinder(benchmark: Any) -> None:
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

    benchmark.group = "4096^2 10-cell query"
    path = benchmark(query)
    benchmark.extra_info.update(prepare_s=prepare_s, cells=len(path))
    assert tuple(path[-1]) == GOAL


def test_tcod_astar(benchmark: Any) -> None:
    passable = np.isfinite(big_map()).astype(np.int8)
    t0 = time.perf_counter()
    finder = tcod.path.AStar(passable, diagonal=SQRT2)
    prepare_s = time.perf_counter() - t0
    benchmark.group = "4096^2 10-cell query"
    steps = benchmark(finder.get_path, *START, *GOAL)
    benchmark.extra_info.update(prepare_s=prepare_s, cells=len(steps) + 1)
    assert tuple(steps[-1]) == GOAL


@pytest.mark.parametrize("what", ["prepared", "one-shot"])
def test_navkit_distance_field_1024(benchmark: Any, what: str) -> None:
    """Whole-grid Dijkstra (1024 x 1024 view of the map): the O(cells) answer itself
    dominates, so preparing saves only the validation pass."""
    costs = np.array(big_map()[:1024, :1024])
    goal = (512, 512)
    costs[goal] = 1.0
    benchmark.group = "1024^2 distance field"
    if what == "prepared":
        planner = AStarPlanner(costs)
        field = benchmark(planner.distance_field, goal)
    else:
        field = benchmark(distance_field, costs, goal)
    benchmark.extra_info["reachable"] = int(np.isfinite(field).sum())
