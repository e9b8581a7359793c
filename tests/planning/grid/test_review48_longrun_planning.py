"""Long runs of Field D*: a thousand cost changes and replans (review 48, LONGRUN).

A planner kept for a whole mission takes ``update_costs`` and ``replan`` thousands of
times. What it keeps between them must neither grow nor go stale: after every
hundredth of 1,000 random changes (costs raised, lowered, cells blocked and freed,
with the start moving along the path) the replan is the fresh plan of a new planner
on the same costs, point for point and cost for cost, and its memory is what it was
after the first hundred cycles.
"""

from __future__ import annotations

import gc
import tracemalloc
from collections.abc import Callable
from functools import partial

import numpy as np
import pytest

from navkit.errors import NoPathError
from navkit.planning import FieldDStar, Path2D

_N = 40


def _outcome(call: Callable[[], Path2D]) -> Path2D | str:
    """The plan, or the kind of error that refused it (no path; a start walled in)."""
    try:
        return call()
    except (NoPathError, ValueError) as exc:
        return type(exc).__name__


def _same(a: Path2D | str, b: Path2D | str) -> bool:
    if isinstance(a, str) or isinstance(b, str):
        return a == b
    return bool(np.array_equal(a.points, b.points)) and a.cost == b.cost


def _cycles(seed: int, cycles: int, every: int) -> tuple[int, list[int]]:
    rng = np.random.default_rng(seed)
    costs = np.where(rng.random((_N, _N)) < 0.15, np.inf, 1.0 + rng.random((_N, _N)))
    costs[:2, :2] = 1.0
    costs[-2:, -2:] = 1.0
    planner = FieldDStar(costs)
    start, goal = np.array([0, 0]), np.array([_N, _N])
    path = _outcome(lambda: planner.plan(start, goal))
    compared, memory = 0, []
    for k in range(1, cycles + 1):
        if k == every:
            gc.collect()
            tracemalloc.start()
        # Any cell but the goal's corner (a goal walled in is refused, not planned).
        cells = rng.integers(0, _N - 2, (5, 2))
        new = np.where(rng.random(5) < 0.3, np.inf, 1.0 + rng.random(5))
        costs[cells[:, 0], cells[:, 1]] = new
        planner.update_costs(cells, new)
        if not isinstance(path, str) and k % 7 == 0:
            # The robot moves on: the start goes a few nodes along the last path.
            node = np.rint(path.points[min(3, len(path.points) - 1)]).astype(int)
            if not np.array_equal(node, goal):
                start = node
        path = _outcome(partial(planner.replan, start))
        if k % every == 0:
            fresh = _outcome(partial(FieldDStar(costs).plan, start, goal))
            assert _same(path, fresh), f"cycle {k}: the replan is not the fresh plan"
            compared += not isinstance(path, str)
            gc.collect()
            memory.append(tracemalloc.get_traced_memory()[0])
    tracemalloc.stop()
    return compared, memory


def test_thousand_replans_equal_fresh_plans_and_hold_no_more_memory() -> None:
    compared, memory = _cycles(3, 1000, 100)
    assert compared >= 8  # plans compared (the rest: both refused alike)
    # The fresh planners compared with are gone; the kept planner's buffers grow by
    # doubling up to bounds set by the grid (its list of changed cells keeps each
    # cell once past 2·rows·cols entries, 51 kB here), not by the cycles.
    assert max(memory[1:]) - memory[1] < 64_000


@pytest.mark.slow
@pytest.mark.parametrize("seed", [4, 5])
def test_ten_thousand_replans(seed: int) -> None:
    compared, memory = _cycles(seed, 10_000, 1000)
    assert compared >= 5
    assert max(memory[2:]) - memory[2] < 64_000
