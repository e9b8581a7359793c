"""Jump point search on plateaus of one f rounded differently (review 40, PLANREV).

A* has queued f with its lowest ``F_TIE_BITS`` bits cleared since session 43
(``test_review39_astarplat_plateau.py``): sums of 1 and sqrt(2) added in
different orders round differently, and f compared exactly expanded a plateau
of one value in the order of its ulps instead of towards the goal. JPS's queue
still compared f exactly. On an open grid that costs nothing (two or three
jump points), but where obstacles make many jump points, as on random maps,
it did: on MovingAI's ``random512-10-0`` its 1,780 problems expanded
9,031,338 jump points without corner cutting and 1,807,384 with it, up to 17
and 38 times as many as needed on one problem (now 8,004,276 and 1,114,374).
JPS now queues f as A* does.

The reference is the cell-by-cell JPS of
``test_review26_jpsoracle_word_edges`` (its queue bands f too); ``Exact`` is
the same search with f compared exactly, the queue before the fix.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from grid_oracle import scipy_costs_from
from test_review26_jpsoracle_word_edges import Reference, check_against_reference

from navkit.planning import AStarPlanner

Cell = tuple[int, int]


class Exact(Reference):
    """The reference search with f compared exactly (JPS's queue before review 40)."""

    @staticmethod
    def queued_f(f: float) -> float:
        return f


def random_map(seed: int) -> tuple[np.ndarray, list[tuple[Cell, Cell]]]:
    """A square grid of 24-48 cells a side, 10 % blocked, and six queries between free cells."""
    rng = np.random.default_rng(seed)
    side = int(rng.integers(24, 49))
    costs = np.where(rng.random((side, side)) < 0.1, np.inf, 1.0)
    free = np.argwhere(np.isfinite(costs))
    queries = []
    for _ in range(6):
        a, b = (tuple(int(x) for x in free[rng.integers(free.shape[0])]) for _ in range(2))
        queries.append((a, b))
    return costs, queries  # type: ignore[return-value]


@pytest.mark.parametrize("cutting", [False, True])
def test_jps_queues_f_within_its_band_as_the_reference_does(cutting: bool) -> None:
    # Every search's whole state (expansions, nodes reached and closed, their
    # costs, parents and directions, the path) is the banded reference's; with
    # f compared exactly, about 2 in 5 of these searches expanded other jump
    # points.
    differ = 0
    for seed in range(40):
        costs, queries = random_map(seed)
        free = np.isfinite(costs)
        for start, goal in queries:
            check_against_reference(costs, start, goal, cutting)
            exact = Exact(free, cutting).search(start, goal)
            banded = Reference(free, cutting).search(start, goal)
            differ += exact.expanded != banded.expanded
            # The band merges only roundings of one value here: the same cost.
            assert exact.found == banded.found
            if banded.found:
                v = goal[0] * costs.shape[1] + goal[1]
                assert math.isclose(exact.records[v][0], banded.records[v][0], rel_tol=1e-14)
    assert differ > 0  # the maps have plateaus split by ulps


@pytest.mark.parametrize("cutting", [False, True])
def test_a_plateau_split_by_ulps_is_not_expanded_in_ulp_order(cutting: bool) -> None:
    # The query of these maps where f compared exactly expanded most jump
    # points more than the band (37 against 13 without corner cutting).
    worst: tuple[int, int, np.ndarray, Cell, Cell] | None = None
    for seed in range(40):
        costs, queries = random_map(seed)
        free = np.isfinite(costs)
        for start, goal in queries:
            extra = (
                Exact(free, cutting).search(start, goal).expanded
                - Reference(free, cutting).search(start, goal).expanded
            )
            if worst is None or extra > worst[0]:
                worst = (extra, seed, costs, start, goal)
    assert worst is not None
    _, _, costs, start, goal = worst
    free = np.isfinite(costs)
    exact = Exact(free, cutting).search(start, goal)
    path = AStarPlanner(costs, method="jps", corner_cutting=cutting).plan(start, goal)
    assert path.expanded == Reference(free, cutting).search(start, goal).expanded
    assert 2 * path.expanded <= exact.expanded
    # Still an optimal path (scipy's Dijkstra on the same graph).
    optimum = scipy_costs_from(costs, start, 8, cutting)[goal]
    assert math.isclose(path.cost, optimum, rel_tol=1e-13)
