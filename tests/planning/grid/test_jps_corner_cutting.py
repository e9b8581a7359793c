"""Jump point search on the corner-cutting graph (``method="jps"``, ``corner_cutting=True``).

There a diagonal move needs only its two end cells to be traversable (the
graph of pyastar2d, tcod and scikit-image's ``MCP_Geometric``), the graph of
the original jump point search (Harabor & Grastien, AAAI 2011). JPS must
return A*'s optimal cost on that graph, on a valid path through every cell,
and raise the same ``NoPathError`` where A* finds no path.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
from grid_oracle import assert_valid_path, scipy_costs_from
from hypothesis import given, settings
from hypothesis import strategies as st
from test_jps import expandable_cells, uniform_grids
from test_movingai import load, sample

from hypothesis_twins import slow_twin
from navkit import NoPathError
from navkit.planning import AStarPlanner, astar
from navkit.planning.grid import _astar

SQRT2 = math.sqrt(2.0)
Case = tuple[np.ndarray, tuple[int, int], tuple[int, int]]


def corner_cutting_grids(max_side: int = 70) -> st.SearchStrategy[Case]:
    """Grids of one cost up to ``max_side`` square or narrow strips, 0-60 % blocked."""
    return uniform_grids(
        max_rows=max_side,
        max_cols=max_side,
        densities=(0.0, 0.05, 0.2, 0.35, 0.5, 0.6),
        strips=True,
        same_goal=True,
    )


def check_against_astar(costs: np.ndarray, start: tuple[int, int], goal: tuple[int, int]) -> None:
    """JPS and A* on the corner-cutting graph: the same cost, or both no path."""
    try:
        reference = astar(costs, start, goal, corner_cutting=True)
    except NoPathError as error:
        with pytest.raises(NoPathError, match="no path from start_cell") as info:
            astar(costs, start, goal, method="jps", corner_cutting=True)
        assert info.value.expanded >= 1
        assert error.expanded >= 1
        return
    path = astar(costs, start, goal, method="jps", corner_cutting=True)
    assert path.cost == pytest.approx(reference.cost, rel=1e-12, abs=1e-12)
    cost, length = assert_valid_path(costs, path.cells, start, goal, corner_cutting=True)
    assert path.cost == pytest.approx(cost, rel=1e-12, abs=1e-12)
    assert path.length == pytest.approx(length, rel=1e-12, abs=1e-12)
    assert path.cost == pytest.approx(costs[start] * path.length, rel=1e-15, abs=0.0)
    assert path.expanded <= expandable_cells(costs, start, goal, reference.cost, True)


@settings(max_examples=50, deadline=None)
@given(case=corner_cutting_grids())
def test_cost_equals_corner_cutting_astar_on_a_valid_path(case: Case) -> None:
    check_against_astar(*case)


test_cost_equals_corner_cutting_astar_on_a_valid_path_thoroughly = slow_twin(
    test_cost_equals_corner_cutting_astar_on_a_valid_path, max_examples=400
)


@settings(max_examples=80, deadline=None)
@given(case=corner_cutting_grids(max_side=12))
def test_cost_equals_scipy_dijkstra_on_the_corner_cutting_graph(case: Case) -> None:
    costs, start, goal = case
    reference = scipy_costs_from(costs, start, 8, True)[goal]
    planner = AStarPlanner(costs, method="jps", corner_cutting=True)
    assert planner.method == "jps"
    if not math.isfinite(reference):
        with pytest.raises(NoPathError):
            planner.plan(start, goal)
        return
    assert planner.plan(start, goal).cost == pytest.approx(reference, rel=1e-12, abs=1e-12)


def test_diagonal_squeeze_between_two_blocked_cells() -> None:
    # Passable only by cutting both corners of each diagonal step.
    costs = np.full((5, 5), np.inf)
    np.fill_diagonal(costs, 2.0)
    path = astar(costs, (0, 0), (4, 4), method="jps", corner_cutting=True)
    assert path.cells.tolist() == [[i, i] for i in range(5)]
    assert path.cost == pytest.approx(2.0 * 4 * SQRT2, rel=1e-15)
    with pytest.raises(NoPathError):
        astar(costs, (0, 0), (4, 4), method="jps")


def test_start_equals_goal_and_a_lone_cell() -> None:
    costs = np.ones((4, 130))
    costs[1:, 64] = np.inf
    same = astar(costs, (2, 70), (2, 70), method="jps", corner_cutting=True)
    assert same.cells.tolist() == [[2, 70]]
    assert (same.cost, same.length, same.expanded) == (0.0, 0.0, 1)
    lone = np.full((1, 1), 3.0)
    assert astar(lone, (0, 0), (0, 0), method="jps", corner_cutting=True).cost == 0.0


def test_forced_neighbours_on_both_sides_of_word_edges() -> None:
    # Single obstacles beside a row and a column, at and around the 64-cell
    # word edges of the bit tables (padded positions 63-65 and 127-129),
    # force turns there; every goal is checked against A*.
    size = 140
    costs = np.ones((size, size))
    for k in (61, 62, 63, 64, 65, 126, 127, 128):
        costs[10, k] = np.inf
        costs[k, 20] = np.inf
        costs[k - 1, k] = np.inf
    rng = np.random.default_rng(7)
    free = np.argwhere(np.isfinite(costs))
    for start, goal in free[rng.choice(len(free), size=(60, 2))]:
        check_against_astar(costs, (int(start[0]), int(start[1])), (int(goal[0]), int(goal[1])))
    # Along the obstacle rows themselves: the goal on a scanned line.
    for goal in [(11, 139), (11, 0), (139, 21), (0, 21), (9, 64), (64, 19)]:
        check_against_astar(costs, (11, 30), goal)
        check_against_astar(costs.T.copy(), (30, 11), goal[::-1])


def test_unreachable_goal_raises_like_astar() -> None:
    # A full wall row: no diagonal move crosses it, corner cutting or not.
    costs = np.ones((30, 90))
    costs[10, :] = np.inf
    costs[:10, 40] = np.inf
    with pytest.raises(NoPathError) as jps_error:
        astar(costs, (0, 0), (29, 89), method="jps", corner_cutting=True)
    with pytest.raises(NoPathError):
        astar(costs, (0, 0), (29, 89), corner_cutting=True)
    assert "no path from start_cell (0, 0) to goal_cell (29, 89)" in str(jps_error.value)
    # One free wall cell opens the way, also diagonally through it.
    costs[10, 70] = 1.0
    check_against_astar(costs, (0, 0), (29, 89))
    check_against_astar(costs, (9, 69), (11, 71))


def test_a_narrower_grid_after_a_wider_one_sees_only_its_own_cells() -> None:
    # 52 and 48 columns pack into the same number of 64-bit words, so the
    # second grid reuses the first one's table and search scratch: the
    # columns 48-51 the first left traversable must not become a way around
    # the wall (diagonally past its end, with corner cutting).
    astar(np.ones((10, 52)), (0, 0), (9, 51), method="jps", corner_cutting=True)
    walled = np.ones((10, 48))
    walled[5, :] = np.inf
    with pytest.raises(NoPathError):
        astar(walled, (0, 46), (9, 46), method="jps", corner_cutting=True)
    with pytest.raises(NoPathError):
        AStarPlanner(walled, method="jps", corner_cutting=True).plan((4, 47), (6, 47))
    walled[5, 47] = 1.0
    path = astar(walled, (0, 46), (9, 46), method="jps", corner_cutting=True)
    assert path.cells[:, 1].max() == 47
    check_against_astar(walled, (0, 46), (9, 46))


def test_queue_growth_gives_the_same_path() -> None:
    rng = np.random.default_rng(11)
    costs = np.where(rng.random((150, 170)) < 0.35, np.inf, 1.0)
    costs[0, 0] = costs[-1, -1] = 1.0
    planner = AStarPlanner(costs, method="jps", corner_cutting=True)
    expected = planner.plan((0, 0), (149, 169))
    assert expected.cost == pytest.approx(
        astar(costs, (0, 0), (149, 169), corner_cutting=True).cost, rel=1e-12
    )
    scratch = _astar._jps_scratch
    scratch.heap = np.empty(2, dtype=np.float64)  # room for one entry: must grow
    again = planner.plan((0, 0), (149, 169))
    assert scratch.heap.size > 2
    np.testing.assert_array_equal(again.cells, expected.cells)
    assert (again.cost, again.expanded) == (expected.cost, expected.expanded)


def test_jps_expands_far_fewer_nodes_than_astar_in_rooms() -> None:
    # Open rooms joined by doors: JPS jumps across them.
    costs = np.ones((200, 200))
    for k in (50, 100, 150):
        costs[k, :] = np.inf
        costs[:, k] = np.inf
        for a in (25, 75, 125, 175):
            costs[k, a : a + 3] = 1.0
            costs[a : a + 3, k] = 1.0
    reference = astar(costs, (0, 0), (199, 199), corner_cutting=True)
    path = astar(costs, (0, 0), (199, 199), method="jps", corner_cutting=True)
    assert path.cost == pytest.approx(reference.cost, rel=1e-12)
    assert_valid_path(costs, path.cells, (0, 0), (199, 199), corner_cutting=True)
    assert path.expanded * 20 < reference.expanded


def test_integer_grids_are_converted_and_inputs_not_modified() -> None:
    costs = np.full((20, 70), 2, dtype=np.int32)
    before = costs.copy()
    planner = AStarPlanner(costs, method="jps", corner_cutting=True)
    costs[:, 10] = 10**6  # the planner holds its own copy
    path = planner.plan((10, 0), (10, 69))
    assert path.cost == pytest.approx(2 * 69, rel=1e-15)
    np.testing.assert_array_equal(costs[:, 11:], before[:, 11:])


MOVINGAI_MAPS = ["dao/arena2", "maze/maze512-1-0", "room/8room_000", "street/Berlin_0_256"]


@pytest.mark.parametrize("name", MOVINGAI_MAPS)
def test_movingai_maps_match_corner_cutting_astar(shared_data: Path, name: str) -> None:
    # The published optima are for the graph without corner cutting: compare
    # with A* on the corner-cutting graph instead (never longer than them).
    costs, scenarios = load(shared_data, name)
    jps = AStarPlanner(costs, method="jps", corner_cutting=True)
    reference = AStarPlanner(costs, corner_cutting=True)
    assert jps.method == "jps"
    for i, sc in enumerate(sample(scenarios, 60)):
        path = jps.plan(sc.start, sc.goal)
        expected = reference.plan(sc.start, sc.goal).cost
        assert path.cost == pytest.approx(expected, rel=1e-12)
        assert path.cost <= sc.optimal * (1 + 1e-9)
        if i % 6 == 0:
            cost, _ = assert_valid_path(costs, path.cells, sc.start, sc.goal, corner_cutting=True)
            assert cost == pytest.approx(path.cost, rel=1e-9)
