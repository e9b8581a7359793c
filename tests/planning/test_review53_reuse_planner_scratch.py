"""Planners of many maps queried in one thread, against a fresh thread (review 53, REUSE).

A robot process keeps several planners (a global map, a local window, maps
swapped in as it goes) and queries them in any order. Every A* and jump point
search borrows its thread's scratch arrays, sized for the largest grid that
thread has searched and stamped per search (``_workspace``, ``_JpsScratch``),
so nothing is cleared between queries. A query must not depend on what the
scratch held: each answer here (path cells, cost, expansions; a distance field
bit for bit; the error) is compared with the same query run in a new thread,
whose scratch has never been used. Earlier reviews pinned one planner against
fresh planners (review 29); here the planners differ in size, method and
options and their queries interleave, big maps before small ones.
"""

from __future__ import annotations

import threading
from collections.abc import Callable
from functools import partial
from typing import Any

import numpy as np
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from navkit.errors import NoPathError
from navkit.planning import AStarPlanner

_OPTIONS: list[dict[str, Any]] = [
    {},
    {"method": "auto"},  # JPS on the uniform maps
    {"connectivity": 4},
    {"corner_cutting": True},
    {"corner_cutting": True, "method": "auto"},
    {"heuristic_weight": 2.0},
    {"heuristic_weight": 0.0},
]


def _outcome(query: Callable[[], Any]) -> Any:
    try:
        answer = query()
    except (NoPathError, ValueError) as exc:
        return type(exc).__name__
    if isinstance(answer, np.ndarray):
        return answer.tobytes()
    return answer.cells.tobytes(), answer.cost, answer.expanded


def _in_new_thread(query: Callable[[], Any]) -> Any:
    box: list[Any] = []
    worker = threading.Thread(target=lambda: box.append(_outcome(query)))
    worker.start()
    worker.join()
    return box[0]


@st.composite
def _planner_jobs(draw: st.DrawFn) -> tuple[AStarPlanner, list[tuple[str, Any, Any]]]:
    rows, cols = draw(st.integers(1, 40)), draw(st.integers(1, 40))
    rng = np.random.default_rng(draw(st.integers(0, 2**32 - 1)))
    free = rng.random((rows, cols)) >= draw(st.floats(0.0, 0.5))
    uniform = draw(st.booleans())
    costs = np.where(free, 1.0 if uniform else rng.uniform(1.0, 5.0, (rows, cols)), np.inf)
    planner = AStarPlanner(costs, **draw(st.sampled_from(_OPTIONS)))

    def cell() -> tuple[int, int]:
        return int(rng.integers(rows)), int(rng.integers(cols))

    kinds = draw(st.lists(st.sampled_from(["plan", "field"]), min_size=1, max_size=4))
    return planner, [(kind, cell(), cell()) for kind in kinds]


@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(jobs=st.lists(_planner_jobs(), min_size=2, max_size=6), order=st.randoms())
def test_interleaved_queries_of_many_planners_equal_a_fresh_threads(
    jobs: list[tuple[AStarPlanner, list[tuple[str, Any, Any]]]], order: Any
) -> None:
    queries: list[Callable[[], Any]] = []
    for planner, asks in jobs:
        for kind, start, goal in asks:
            if kind == "plan":
                queries.append(partial(planner.plan, start, goal))
            else:
                queries.append(partial(planner.distance_field, goal))
    order.shuffle(queries)
    for query in queries:
        assert _outcome(query) == _in_new_thread(query)


def test_a_small_map_after_a_big_one_equals_a_fresh_thread() -> None:
    # The big map's search leaves marks and parents all over the scratch beyond the
    # small map's cells, and JPS's block bits: the small map must not read them.
    rng = np.random.default_rng(53)
    big = np.where(rng.random((120, 150)) < 0.2, np.inf, 1.0)
    small = np.where(rng.random((9, 7)) < 0.2, np.inf, 1.0)
    small[0, 0] = small[-1, -1] = big[0, 0] = big[-1, -1] = 1.0
    for method in ("astar", "jps"):
        for first in (AStarPlanner(big, method=method), AStarPlanner(big)):
            for _ in range(2):
                _outcome(partial(first.plan, (0, 0), (119, 149)))
                _outcome(partial(first.distance_field, (60, 70)))
            planner = AStarPlanner(small, method=method)
            for query in (
                partial(planner.plan, (0, 0), (8, 6)),
                partial(planner.plan, (8, 6), (0, 0)),
                partial(planner.distance_field, (0, 0)),
            ):
                assert _outcome(query) == _in_new_thread(query)
