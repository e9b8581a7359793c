"""Grid planners shared by threads whose searches now really run at once.

The grid searches release the GIL (``navkit._shared.jit.RELEASES_GIL``), so
two threads' kernels run together, on two cores. What the mapping guide calls
shareable (``AStarPlanner``, ``MapPlanner`` with ``"astar"``, the one-shot
functions on one cost array) must give each thread the answer a lone call
gives, bit for bit: the searches' scratch is per thread, never per planner.
Objects with state (``FieldDStar``, ``MapPlanner`` with ``"field_dstar"``)
serve one thread each; several of them planning at once on one shared cost
array must not disturb each other either. Threads are lined up at a barrier
and released together, a few rounds (``thread_runs.concurrent_results``).
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy as np
import pytest

from navkit.errors import NoPathError
from navkit.mapping import OccupancyGrid
from navkit.planning import AStarPlanner, FieldDStar, MapPlanner, astar, distance_field
from navkit.planning.grid import Path2D
from thread_runs import concurrent_results

THREADS = 4


def _costs(n: int, seed: int, *, uniform: bool = False) -> np.ndarray:
    rng = np.random.default_rng(seed)
    costs = np.ones((n, n)) if uniform else rng.uniform(1.0, 4.0, (n, n))
    costs[rng.random((n, n)) < 0.25] = np.inf
    costs[0, 0] = costs[-1, -1] = 1.0
    return costs


def _queries(n: int, seed: int, k: int) -> list[tuple[tuple[int, int], tuple[int, int]]]:
    rng = np.random.default_rng(seed + 1000)
    cells = rng.integers(0, n, (k, 2, 2))
    return [((int(a[0]), int(a[1])), (int(b[0]), int(b[1]))) for a, b in cells]


def _outcome(plan: Callable[[], Path2D]) -> tuple[Any, ...]:
    """Everything a path holds, or the refusal, as bytes and numbers."""
    try:
        path = plan()
    except (ValueError, NoPathError) as exc:  # an obstacle cell, or no path
        return (type(exc).__name__, str(exc))
    return (path.points.tobytes(), path.cost, path.length, path.expanded)


def _found(value: object) -> int:
    """How many paths (or fields, as bytes) ``value`` holds."""
    if isinstance(value, bytes):
        return 1
    if isinstance(value, (list, tuple)):
        return sum(_found(v) for v in value)
    return 0


def _check(calls: list[Callable[[], Any]]) -> None:
    """Concurrent rounds give each call's serial answer."""
    serial = [call() for call in calls]
    assert _found(serial) > 0  # not refusals only
    for results in concurrent_results(calls, rounds=3):
        for got, want in zip(results, serial, strict=True):
            assert got == want


@pytest.mark.parametrize("seed", [0, 1])
@pytest.mark.parametrize("method", ["astar", "jps"])
@pytest.mark.parametrize("corner_cutting", [False, True])
def test_one_astar_planner_shared_by_threads(seed: int, method: str, corner_cutting: bool) -> None:
    n = 160
    planner = AStarPlanner(
        _costs(n, seed, uniform=method == "jps"), method=method, corner_cutting=corner_cutting
    )
    queries = _queries(n, seed, THREADS * 3)

    def run(part: int) -> list[tuple[Any, ...]]:
        return [_outcome(lambda q=q: planner.plan(*q)) for q in queries[part::THREADS]]

    _check([lambda part=part: run(part) for part in range(THREADS)])


@pytest.mark.parametrize("seed", [2, 3])
def test_distance_fields_of_one_planner_and_one_array(seed: int) -> None:
    n = 200
    costs = _costs(n, seed)
    costs.flags.writeable = False  # shared, as a map a node publishes
    planner = AStarPlanner(costs)
    goals = [q[1] for q in _queries(n, seed, THREADS)]

    def field(i: int) -> bytes | str:
        try:
            if i % 2:
                return planner.distance_field(goals[i]).tobytes()
            return distance_field(costs, goals[i]).tobytes()
        except ValueError as exc:
            return str(exc)

    _check([lambda i=i: field(i) for i in range(THREADS)])


def test_one_shot_astar_on_one_array() -> None:
    n = 200
    costs = _costs(n, 4)
    queries = _queries(n, 4, THREADS)
    _check([lambda q=q: _outcome(lambda: astar(costs, *q)) for q in queries])


def test_one_map_planner_with_astar_shared_by_threads() -> None:
    occupied = np.random.default_rng(5).random((150, 150)) < 0.03
    occupied[:120, 75] = True
    grid = OccupancyGrid.from_occupancy(occupied, resolution=0.05)
    planner = MapPlanner(grid, robot_radius=0.1)
    rng = np.random.default_rng(6)
    points = rng.uniform(0.2, 7.3, (THREADS * 2, 2, 2))

    def run(part: int) -> list[tuple[Any, ...]]:
        return [
            _outcome(lambda p=p: planner.plan(tuple(p[0]), tuple(p[1]), start_tolerance=0.3))
            for p in points[part::THREADS]
        ]

    _check([lambda part=part: run(part) for part in range(THREADS)])


def test_field_dstar_planners_of_each_thread_on_one_cost_array() -> None:
    """One planner per thread (they have state), one read-only cost array."""
    n = 120
    costs = _costs(n, 7)
    costs.flags.writeable = False
    queries = [q for q in _queries(n, 7, 40) if np.isfinite(costs[q[0]] + costs[q[1]])]
    assert len(queries) >= THREADS

    def run(i: int) -> list[tuple[Any, ...]]:
        planner = FieldDStar(costs)
        start, goal = queries[i]
        first = _outcome(lambda: planner.plan(start, goal))
        blocked = [(r, c) for r in range(40, 80) for c in (60,)]
        planner.update_costs(blocked, np.inf)
        return [first, _outcome(lambda: planner.replan(start))]

    _check([lambda i=i: run(i) for i in range(THREADS)])


def test_map_planners_with_field_dstar_of_each_thread_on_one_grid() -> None:
    occupied = np.zeros((100, 100), dtype=bool)
    occupied[20:80, 50] = True
    grid = OccupancyGrid.from_occupancy(occupied, resolution=0.05)
    goals = [(4.5, 0.5), (4.5, 4.5), (4.0, 2.5), (3.0, 4.8)]

    def run(i: int) -> tuple[Any, ...]:
        planner = MapPlanner(grid, robot_radius=0.1, planner="field_dstar")
        return _outcome(lambda: planner.plan((0.5, 2.5), goals[i]))

    _check([lambda i=i: run(i) for i in range(THREADS)])
