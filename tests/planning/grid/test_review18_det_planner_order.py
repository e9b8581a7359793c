"""Determinism of the grid planners: no state carried from query to query, no order effects.

The searches keep their scratch per thread and reuse it (``astar``'s notes); a result
must be a function of its own query alone: the same bits after other queries on
larger or smaller grids, in another order, or in a fresh thread (fresh scratch).
Field D*'s ``update_costs`` lists changed cells in the order given: the same final
costs reached through other orders or groupings of the updates repair to the same
path, the path a fresh plan finds (``replan``'s documented promise).
"""

from __future__ import annotations

import threading
from typing import Any

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from hypothesis_twins import slow_twin
from navkit import NavkitError
from navkit.planning import AStarPlanner, FieldDStar, distance_field


def _grid(seed: int, rows: int, cols: int, ties: bool) -> tuple[Any, Any, Any]:
    """Costs (some impassable; all 1.0 when ``ties``) and two passable cells."""
    rng = np.random.default_rng(seed)
    costs = np.where(
        rng.random((rows, cols)) < 0.25, np.inf, rng.choice([1.0, 2.0, 7.5], (rows, cols))
    )
    if ties:
        costs[np.isfinite(costs)] = 1.0
    costs[0, 0] = costs[-1, -1] = 1.0
    free = np.argwhere(np.isfinite(costs))
    a, b = (tuple(int(v) for v in free[k]) for k in rng.integers(0, len(free), 2))
    return costs, a, b


def _answers(query: tuple[Any, Any, Any]) -> list[Any]:
    """Bytes of every planner's answer to one query (the error's type when it raises)."""
    costs, a, b = query
    jps = bool(np.all(costs[np.isfinite(costs)] == 1.0))
    runs = [
        lambda: AStarPlanner(costs, connectivity=4).plan(a, b),
        lambda: AStarPlanner(costs).plan(a, b),
        lambda: AStarPlanner(costs, method="jps" if jps else "astar").plan(a, b),
        lambda: FieldDStar(costs).plan_cells(a, b),
    ]
    out: list[Any] = []
    for run in runs:
        try:
            path = run()
        except NavkitError as exc:
            out.append(type(exc).__name__)
        else:
            out.append((path.points.tobytes(), path.cost))
    out.append(distance_field(costs, b).tobytes())
    return out


_QUERIES = st.lists(
    st.tuples(st.integers(0, 2**32 - 1), st.integers(2, 40), st.integers(2, 40), st.booleans()),
    min_size=2,
    max_size=6,
)


@settings(max_examples=12, deadline=None)
@given(_QUERIES)
def test_answers_do_not_depend_on_earlier_queries_or_the_thread(specs: list[Any]) -> None:
    queries = [_grid(*spec) for spec in specs]
    forward = [_answers(q) for q in queries]
    backward = [_answers(q) for q in reversed(queries)][::-1]
    fresh: list[Any] = [None] * len(queries)

    def alone(k: int) -> None:
        fresh[k] = _answers(queries[k])

    for k in range(len(queries)):  # one new thread per query: fresh scratch each time
        worker = threading.Thread(target=alone, args=(k,))
        worker.start()
        worker.join()
    assert backward == forward
    assert fresh == forward


test_answers_do_not_depend_on_earlier_queries_or_the_thread_thoroughly = slow_twin(
    test_answers_do_not_depend_on_earlier_queries_or_the_thread, max_examples=60
)


def test_a_big_search_then_a_small_one_gives_the_small_ones_fresh_answer() -> None:
    small = _grid(5, 12, 9, True)
    alone: list[Any] = []
    worker = threading.Thread(target=lambda: alone.append(_answers(small)))
    worker.start()
    worker.join()
    _answers(_grid(6, 150, 170, False))  # leaves large, used scratch in this thread
    assert _answers(small) == alone[0]


@settings(max_examples=15, deadline=None)
@given(
    st.integers(0, 2**32 - 1),
    st.integers(3, 12),
    st.integers(3, 12),
    st.integers(1, 8),
    st.randoms(use_true_random=False),
)
def test_field_dstar_repairs_alike_whatever_the_order_of_updates(
    seed: int, rows: int, cols: int, count: int, shuffler: Any
) -> None:
    rng = np.random.default_rng(seed)
    costs = np.where(rng.random((rows, cols)) < 0.2, np.inf, rng.choice([1.0, 3.0], (rows, cols)))
    costs[0, 0] = costs[-1, -1] = 1.0
    flat = rng.choice(rows * cols - 2, size=min(count, rows * cols - 2), replace=False) + 1
    cells = [(int(f // cols), int(f % cols)) for f in flat]  # distinct, never a corner's end
    values = [float(v) for v in rng.choice([1.0, 2.0, 5.0, np.inf], len(cells))]
    start, goal = (0, 0), (rows, cols)
    try:
        FieldDStar(costs).plan(start, goal)
    except NavkitError:
        return  # no first plan to repair
    orders = [list(range(len(cells))), list(range(len(cells)))[::-1]]
    shuffled = list(range(len(cells)))
    shuffler.shuffle(shuffled)
    orders.append(shuffled)
    answers = set()
    for order in orders:
        for grouping in ("one call", "one cell a call"):
            planner = FieldDStar(costs)
            planner.plan(start, goal)
            if grouping == "one call":
                planner.update_costs([cells[k] for k in order], [values[k] for k in order])
            else:
                for k in order:
                    planner.update_costs(cells[k], values[k])
            try:
                path = planner.replan()
            except (NavkitError, ValueError) as exc:  # a blocked end or no path: alike too
                answers.add(type(exc).__name__)
            else:
                answers.add((path.points.tobytes(), path.cost))
    assert len(answers) == 1
    final = costs.copy()
    final[tuple(np.array(cells).T)] = values
    (answer,) = answers
    if isinstance(answer, tuple):
        fresh = FieldDStar(final).plan(start, goal)
        assert answer == (fresh.points.tobytes(), fresh.cost)


test_field_dstar_repairs_alike_whatever_the_order_of_updates_thoroughly = slow_twin(
    test_field_dstar_repairs_alike_whatever_the_order_of_updates, max_examples=80
)
