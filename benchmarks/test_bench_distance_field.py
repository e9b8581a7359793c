"""Whole-grid distance fields: :func:`navkit.planning.distance_field` against SciPy's Dijkstra.

Run with ``python -m pytest benchmarks/test_bench_distance_field.py --benchmark-only
--benchmark-timer=time.thread_time`` (CPU time: the ratios stay meaningful on a
loaded machine; each group holds both contestants of one map, timed in the same
run).

Issue 17's row: ``distance_field`` at least 2× faster than
``scipy.sparse.csgraph.dijkstra`` on every map. Contestants, from the same goal
on the same graph (8-connected, move cost ``step * (c_u + c_v) / 2``):

* ``navkit``: :func:`distance_field` one-shot, validation and output included;
* ``navkit-heap``: the same field by the heap Dijkstra of the A* kernel
  (:meth:`AStarPlanner.distance_field` on a planner built per call, grid copy
  included), which the one-shot function ran before issue 17;
* ``csgraph``: ``scipy.sparse.csgraph.dijkstra(graph, indices=goal)``, its CSR
  matrix built once outside the timer (``test_bench_prepared._csr_graph``
  without corner cutting, ``test_bench_movingai.grid_graph`` with it).

Maps: the 1024² maps of ``test_bench_astar.py`` (random 20 %, random 35 %,
rooms) and the random-cost map of ``test_bench_prepared.py`` (costs 1-10, 10 %
blocked), goal at the centre; the MovingAI maps of ``test_bench_movingai.py``
(``../shared/data``, skipped when absent), goal that of the map's longest
scenario. Each map without corner cutting (navkit's default, the MovingAI
rules) and with it (the peers' graph). Before timing, the fields are checked
equal: same reachable cells, costs to 1e-12 relative.

Each timed round gets a new read-only copy of the costs, made outside the
timer (``test_bench_astar.fresh_copy``), so a field remembered from an earlier
round (a cache keyed on the array) cannot stand in for the search, and every
round's field is checked against the reference, also outside the timer
(``test_bench_astar.timed_fresh``). ``test_ratio_to_csgraph`` gives the
issue's row: navkit and csgraph alternately in one loop (the order reversed
every other round, this thread's CPU time), every round's two fields checked
equal to the reference outside the timers, the median per-round ratio
``csgraph_over_navkit`` in ``extra_info``.
"""

from __future__ import annotations

import time
from collections.abc import Callable
from functools import cache
from typing import Any

import numpy as np
import pytest
import scipy.sparse
from scipy.sparse.csgraph import dijkstra

from navkit.planning import AStarPlanner, distance_field
from test_bench_astar import fresh_copy, timed_fresh
from test_bench_movingai import MAPS, grid_graph, movingai
from test_bench_prepared import _csr_graph, _field_map

GRIDS = ["random20", "random35", "rooms", "weighted", *MAPS]
ROUNDS = 7


@cache
def field_case(name: str) -> tuple[np.ndarray, tuple[int, int]]:
    """Costs (read-only) and goal cell of a map."""
    if name in MAPS:
        costs, scenarios = movingai(name)
        return costs, scenarios[-1].goal
    return _field_map(name), (512, 512)


@cache
def scipy_graph(name: str, corner_cutting: bool) -> scipy.sparse.csr_matrix:
    costs = field_case(name)[0]
    return grid_graph(costs) if corner_cutting else _csr_graph(costs)


def contestant_run(name: str, contestant: str, corner_cutting: bool) -> Callable[[np.ndarray], Any]:
    """One contestant's field of map ``name``, from the costs it is given (csgraph: the
    CSR matrix of the map's costs, built once: it ignores them)."""
    goal = field_case(name)[1]
    if contestant == "navkit":
        return lambda costs: distance_field(costs, goal, corner_cutting=corner_cutting)
    if contestant == "navkit-heap":
        return lambda costs: AStarPlanner(costs, corner_cutting=corner_cutting).distance_field(goal)
    costs = field_case(name)[0]
    graph = scipy_graph(name, corner_cutting)
    source = goal[0] * costs.shape[1] + goal[1]
    return lambda _costs: dijkstra(graph, directed=True, indices=source)


@cache
def reference_field(name: str, corner_cutting: bool) -> np.ndarray:
    """SciPy's field of a map, checked against navkit's one-shot field (read-only)."""
    costs = field_case(name)[0]
    field = np.asarray(contestant_run(name, "csgraph", corner_cutting)(costs)).reshape(costs.shape)
    assert_same_field(contestant_run(name, "navkit", corner_cutting)(costs), field)
    field.flags.writeable = False
    return field


def assert_same_field(result: np.ndarray, want: np.ndarray) -> None:
    """Same reachable cells, costs to 1e-12 relative."""
    result = np.asarray(result).reshape(want.shape)
    reach = np.isfinite(want)
    np.testing.assert_array_equal(np.isfinite(result), reach)
    np.testing.assert_allclose(result[reach], want[reach], rtol=1e-12)


@pytest.mark.parametrize("corner_cutting", [False, True], ids=["no-cut", "cut"])
@pytest.mark.parametrize("name", GRIDS)
@pytest.mark.parametrize("contestant", ["navkit", "navkit-heap", "csgraph"])
def test_distance_field(benchmark: Any, name: str, contestant: str, corner_cutting: bool) -> None:
    run = contestant_run(name, contestant, corner_cutting)
    want = reference_field(name, corner_cutting)
    # Before timing: every contestant's field is SciPy's, itself checked equal to navkit's.
    assert_same_field(run(fresh_copy(field_case(name)[0])), want)
    benchmark.group = f"distance field {name} {'cut' if corner_cutting else 'no-cut'}"
    result = timed_fresh(
        benchmark,
        run,
        lambda: (fresh_copy(field_case(name)[0]),),
        lambda _args, field: assert_same_field(field, want),
        ROUNDS,
    )
    benchmark.extra_info["reachable"] = int(np.isfinite(result).sum())


@pytest.mark.parametrize("corner_cutting", [False, True], ids=["no-cut", "cut"])
@pytest.mark.parametrize("name", GRIDS)
def test_ratio_to_csgraph(benchmark: Any, name: str, corner_cutting: bool) -> None:
    """csgraph's field ÷ navkit's, alternately in one loop (issue 17's row: ≥ 2 on every map).

    ``csgraph_over_navkit`` in ``extra_info``: the median per-round ratio of this
    thread's CPU time (the order reversed every other round). Every round's two
    fields are checked against the reference outside the timers, and navkit gets
    a new copy of the costs each round. Under ``--benchmark-disable`` one round
    (the checks).
    """
    want = reference_field(name, corner_cutting)
    sides = {
        "navkit": contestant_run(name, "navkit", corner_cutting),
        "csgraph": contestant_run(name, "csgraph", corner_cutting),
    }
    n_rounds = 1 if benchmark.disabled else ROUNDS

    def rounds() -> dict[str, float]:
        ratios = []
        for i in range(n_rounds):
            spent, fields = {}, {}
            for side in sides if i % 2 == 0 else list(sides)[::-1]:
                costs = fresh_copy(field_case(name)[0])
                c0 = time.thread_time()
                fields[side] = sides[side](costs)
                spent[side] = time.thread_time() - c0
            for side, field in fields.items():
                try:
                    assert_same_field(field, want)
                except AssertionError as error:
                    raise AssertionError(f"{side}'s field differs in round {i}") from error
            ratios.append(spent["csgraph"] / spent["navkit"])
        return {"csgraph_over_navkit": float(np.median(ratios))}

    benchmark.group = "distance field ratio"
    benchmark.extra_info.update(benchmark.pedantic(rounds, rounds=1, iterations=1))
