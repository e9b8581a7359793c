"""A* on plateaus of equal f whose f was rounded differently (session 43, ASTARPLAT).

On open grids of one cost, sums of 1 and sqrt(2) added in different orders
round differently, so the cells of a plateau of equal f differed by an ulp or
a few, and A* compared f exactly: it expanded the plateau in the order of
those ulps instead of towards the goal (an empty 512 x 512 grid from (0, 0)
to (511, 250): 63,760 cells for a path of 512). The queue now ignores f's
lowest ``F_TIE_BITS`` bits (f within 2**-40 of itself ties, then the
documented tie key, towards the goal): the path alone is expanded. The band
can also merge costs that really differ by less than 2**-40; the cost then
stays within the bound of ``F_TIE_BITS`` (checked against scipy's Dijkstra).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from grid_oracle import assert_valid_path, scipy_costs_from
from hypothesis import given, settings
from hypothesis import strategies as st

from navkit.planning import AStarPlanner, astar
from navkit.planning.grid._search_heap import F_BAND, F_TIE_BITS

SQRT2 = math.sqrt(2.0)
BAND = 2.0 ** (F_TIE_BITS - 52)  # relative width of a band of f: 2**-40


def octile(start: tuple[int, int], goal: tuple[int, int]) -> float:
    """Exact-as-possible octile distance: one rounding of a + b sqrt(2)."""
    dr, dc = abs(start[0] - goal[0]), abs(start[1] - goal[1])
    return max(dr, dc) - min(dr, dc) + min(dr, dc) * SQRT2


@pytest.mark.parametrize("corner_cutting", [False, True])
def test_the_open_grid_of_the_report_expands_the_path_alone(corner_cutting: bool) -> None:
    costs = np.ones((512, 512))
    path = astar(costs, (0, 0), (511, 250), corner_cutting=corner_cutting)
    assert path.expanded == len(path.cells) == 512  # 63,760 before
    assert math.isclose(path.cost, 261 + 250 * SQRT2, rel_tol=1e-13)
    assert_valid_path(costs, path.cells, (0, 0), (511, 250), corner_cutting=corner_cutting)


@pytest.mark.parametrize("cost", [1.0, 2.5, 7.0])
def test_open_grids_of_one_cost_expand_the_path_alone(cost: float) -> None:
    # Fixed queries (a seeded generator) between random cells of open grids:
    # with f compared exactly most of them expanded whole plateaus.
    rng = np.random.default_rng(43)
    for side in (64, 200, 700):
        costs = np.full((side, side), cost)
        planner = AStarPlanner(costs)
        for _ in range(6):
            start = (int(rng.integers(side)), int(rng.integers(side)))
            goal = (int(rng.integers(side)), int(rng.integers(side)))
            path = planner.plan(start, goal)
            assert path.expanded == len(path.cells), (side, start, goal)
            assert math.isclose(path.cost, cost * octile(start, goal), rel_tol=1e-13)


def test_weighted_and_four_connected_open_grids_expand_the_path_alone() -> None:
    costs = np.ones((300, 300))
    for options in ({"heuristic_weight": 1.5}, {"connectivity": 4}):
        path = astar(costs, (3, 290), (297, 7), **options)  # type: ignore[arg-type]
        assert path.expanded == len(path.cells)


def test_a_real_near_tie_inside_a_band_may_cost_less_than_a_band_more() -> None:
    # Two routes to (1, 2) whose costs differ by about 2**-44 (cells of cost
    # 1 + 2**-42 on one of them): the band counts them tied, and the tie goes
    # to (1, 1), nearer the goal. The excess is real and below one band.
    e = 2.0**-42
    costs = np.array([[1.0 + e, 1.0, 1.0 + e], [1.0, 1.0, 1.0]])
    path = astar(costs, (0, 0), (1, 2))
    assert path.cells.tolist() == [[0, 0], [1, 1], [1, 2]]
    optimum = scipy_costs_from(costs, (0, 0), 8, False)[1, 2]
    assert 0.0 < path.cost - optimum < BAND * optimum


@settings(max_examples=150, deadline=None)
@given(
    shape=st.tuples(st.integers(1, 9), st.integers(1, 9)),
    seed=st.integers(0, 2**32 - 1),
    corner_cutting=st.booleans(),
    connectivity=st.sampled_from([4, 8]),
)
def test_near_ties_cost_at_most_the_documented_bound(
    shape: tuple[int, int], seed: int, corner_cutting: bool, connectivity: int
) -> None:
    # Costs 2**-42 .. 2**-39 apart: routes within a band of each other
    # everywhere. The cost stays below C* / (1 - 2**-40)**m with m at most
    # the path's moves (F_TIE_BITS), plus the rounding of the sums.
    rng = np.random.default_rng(seed)
    values = [1.0, 1.0 + 2.0**-42, 1.0 + 2.0**-41, 1.0 + 2.0**-39, np.inf]
    costs = np.asarray(rng.choice(values, size=shape, p=[0.3, 0.2, 0.2, 0.2, 0.1]))
    free = np.argwhere(np.isfinite(costs))
    if free.shape[0] == 0:
        return
    start = tuple(int(x) for x in free[rng.integers(free.shape[0])])
    goal = tuple(int(x) for x in free[rng.integers(free.shape[0])])
    optimum = scipy_costs_from(costs, start, connectivity, corner_cutting)[goal]
    if not np.isfinite(optimum):
        return
    path = astar(costs, start, goal, connectivity=connectivity, corner_cutting=corner_cutting)
    moves = len(path.cells) - 1
    recomputed, _ = assert_valid_path(
        costs, path.cells, start, goal, connectivity=connectivity, corner_cutting=corner_cutting
    )
    assert math.isclose(path.cost, recomputed, rel_tol=1e-15 * (moves + 1))
    assert optimum * (1.0 - 1e-15 * (moves + 1)) <= path.cost
    assert path.cost <= optimum / (1.0 - BAND) ** max(moves, 1) * (1.0 + 1e-15 * (moves + 1))


def test_the_band_is_the_documented_mask() -> None:
    assert int(F_BAND) == 2**64 - 2**F_TIE_BITS
    # Keys equal only within 2**-40 of f, and ordered as f otherwise.
    f = np.array([1.0, np.nextafter(1.0, 2.0), 1.0 + 0.99 * BAND, 1.0 + BAND, 3.0])
    keys = f.view(np.uint64) & F_BAND
    assert keys[0] == keys[1] == keys[2] < keys[3] < keys[4]
