"""Jump point search (``method="jps"`` / ``"auto"`` of astar and AStarPlanner).

JPS must return the optimal cost A* and scipy's Dijkstra find, on a valid
8-connected path without corner cutting through every cell. The MovingAI
optimal lengths are checked in ``test_movingai.py``, the corner-cutting
variant in ``test_jps_corner_cutting.py``.
"""

from __future__ import annotations

import json
import math
import subprocess
import sys
from concurrent.futures import ThreadPoolExecutor

import numpy as np
import pytest
from grid_oracle import assert_valid_path, scipy_costs_from
from hypothesis import given, settings
from hypothesis import strategies as st

from hypothesis_twins import slow_twin
from navkit import NoPathError
from navkit.planning import AStarPlanner, astar, distance_field
from navkit.planning.grid import _astar

SQRT2 = math.sqrt(2.0)


@st.composite
def uniform_grids(
    draw: st.DrawFn,
    max_rows: int = 24,
    max_cols: int = 140,
    densities: tuple[float, ...] = (0.0, 0.1, 0.25, 0.4),
    strips: bool = False,
    same_goal: bool = False,
) -> tuple[np.ndarray, tuple[int, int], tuple[int, int]]:
    """A random grid of one cost with obstacles; widths cross 64-cell words.

    With ``strips`` half the grids are 1-3 cells wide and up to 140 long,
    either way round; with ``same_goal`` a tenth have the goal at the start.
    """
    if strips and draw(st.booleans()):
        rows = draw(st.integers(1, 3))
        cols = draw(st.integers(1, 140))
        if draw(st.booleans()):
            rows, cols = cols, rows
    else:
        rows = draw(st.integers(1, max_rows))
        cols = draw(st.integers(1, max_cols))
    rng = np.random.default_rng(draw(st.integers(0, 2**32 - 1)))
    blocked = rng.random((rows, cols)) < draw(st.sampled_from(densities))
    if draw(st.booleans()):
        # Long walls with gaps, as in rooms and mazes.
        for r in rng.choice(rows, size=min(rows, 3), replace=False):
            blocked[r, :] = rng.random(cols) < 0.9
    cost = draw(st.sampled_from([1.0, 2.5, 7.0]))
    costs = np.where(blocked, np.inf, cost)
    free = np.argwhere(~blocked)
    if free.shape[0] == 0:
        costs[0, 0] = cost
        free = np.array([[0, 0]])
    i = draw(st.integers(0, free.shape[0] - 1))
    same = same_goal and draw(st.integers(0, 9)) == 0
    j = i if same else draw(st.integers(0, free.shape[0] - 1))
    return costs, (int(free[i, 0]), int(free[i, 1])), (int(free[j, 0]), int(free[j, 1]))


def expandable_cells(
    costs: np.ndarray,
    start: tuple[int, int],
    goal: tuple[int, int],
    optimum: float,
    corner_cutting: bool,
) -> int:
    """Number of cells v with d(start, v) + h(v) <= the optimal cost.

    A best-first search with the octile heuristic h (consistent) expands
    only such cells (each node it closes has f = g + h <= the optimum and
    g >= d), each at most once: an upper bound on A*'s and JPS's
    expansion counts.
    """
    lowest = float(np.min(costs))
    rows, cols = np.indices(costs.shape)
    dr, dc = np.abs(rows - goal[0]), np.abs(cols - goal[1])
    h = lowest * (np.maximum(dr, dc) + (SQRT2 - 1.0) * np.minimum(dr, dc))
    d = distance_field(costs, start, corner_cutting=corner_cutting)
    return int(np.count_nonzero(d + h <= optimum * (1.0 + 1e-12) + 1e-9))


@settings(max_examples=50, deadline=None)
@given(case=uniform_grids())
def test_jps_cost_equals_astar_on_a_valid_path(
    case: tuple[np.ndarray, tuple[int, int], tuple[int, int]],
) -> None:
    costs, start, goal = case
    try:
        reference = astar(costs, start, goal)
    except NoPathError:
        with pytest.raises(NoPathError) as info:
            astar(costs, start, goal, method="jps")
        assert info.value.expanded >= 1
        return
    path = astar(costs, start, goal, method="jps")
    assert path.cost == pytest.approx(reference.cost, rel=1e-12)
    cost, length = assert_valid_path(costs, path.cells, start, goal)
    assert path.cost == pytest.approx(cost, rel=1e-12)
    assert path.length == pytest.approx(length, rel=1e-12)
    assert path.cost == pytest.approx(costs[start] * path.length, rel=1e-15)
    # Like A*, JPS closes each node once and only while its f is at most the
    # optimal cost (the comparison with A*'s own count, allowing 8 more for
    # ties, failed on a 14 x 96 grid: 49 jump points against 40 cells).
    assert path.expanded <= expandable_cells(costs, start, goal, reference.cost, False)


test_jps_cost_equals_astar_on_a_valid_path_thoroughly = slow_twin(
    test_jps_cost_equals_astar_on_a_valid_path, max_examples=200
)


@settings(max_examples=60, deadline=None)
@given(case=uniform_grids(max_rows=12, max_cols=12))
def test_jps_matches_scipy_dijkstra(
    case: tuple[np.ndarray, tuple[int, int], tuple[int, int]],
) -> None:
    costs, start, goal = case
    reference = scipy_costs_from(costs, start, 8, False)[goal]
    planner = AStarPlanner(costs, method="jps")
    if not math.isfinite(reference):
        with pytest.raises(NoPathError):
            planner.plan(start, goal)
        return
    assert planner.plan(start, goal).cost == pytest.approx(reference, rel=1e-12)


def test_jps_on_an_open_grid_expands_few_jump_points() -> None:
    costs = np.full((300, 500), 3.0)
    path = astar(costs, (3, 5), (280, 490), method="jps")
    dr, dc = 277, 485
    octile = max(dr, dc) + (SQRT2 - 1) * min(dr, dc)
    assert path.length == pytest.approx(octile, rel=1e-12)
    assert path.cost == pytest.approx(3.0 * octile, rel=1e-12)
    assert path.cells.shape[0] == max(dr, dc) + 1
    assert path.expanded <= 3


def test_jps_through_corridors_across_word_boundaries() -> None:
    # A serpentine of 1-cell corridors whose turns fall on and beside the
    # 64-cell word edges of the bit rows.
    rows, cols = 21, 200
    costs = np.ones((rows, cols))
    for r in range(1, rows, 2):
        costs[r, :] = np.inf
        gap = cols - 1 if (r // 2) % 2 == 0 else 0
        costs[r, gap] = 1.0
    for c in (63, 64, 65, 127, 128):
        costs[0, c] = np.inf  # forced neighbours near word edges in row 0 ...
        costs[0, c] = 1.0
    costs[2, 64] = np.inf
    costs[2, 64] = 1.0
    start, goal = (0, 0), (rows - 1, 0)
    path = astar(costs, start, goal, method="jps")
    reference = astar(costs, start, goal)
    assert path.cost == pytest.approx(reference.cost, rel=1e-12)
    assert_valid_path(costs, path.cells, start, goal)
    # Same on the transposed grid (the column bit tables).
    path_t = astar(costs.T.copy(), start[::-1], goal[::-1], method="jps")
    assert path_t.cost == pytest.approx(reference.cost, rel=1e-12)
    assert_valid_path(costs.T, path_t.cells, start[::-1], goal[::-1])


def test_goal_inside_a_straight_scan_and_start_equals_goal() -> None:
    costs = np.ones((5, 300))
    costs[1:, 150] = np.inf
    for goal in [(0, 0), (0, 299), (0, 64), (0, 63), (4, 299), (4, 151)]:
        path = astar(costs, (0, 10), goal, method="jps")
        assert path.cost == pytest.approx(astar(costs, (0, 10), goal).cost, rel=1e-12)
        assert_valid_path(costs, path.cells, (0, 10), goal)
    same = astar(costs, (2, 7), (2, 7), method="jps")
    assert same.cells.tolist() == [[2, 7]]
    assert (same.cost, same.length, same.expanded) == (0.0, 0.0, 1)


def test_no_corner_cutting_in_jps() -> None:
    costs = np.ones((2, 2))
    costs[0, 1] = costs[1, 0] = np.inf
    with pytest.raises(NoPathError):
        astar(costs, (0, 0), (1, 1), method="jps")


def test_auto_picks_jps_only_where_it_applies() -> None:
    uniform = np.ones((20, 30))
    uniform[5:15, 10] = np.inf
    varying = uniform.copy()
    varying[0, 0] = 2.0
    assert AStarPlanner(uniform, method="auto").method == "jps"
    assert AStarPlanner(uniform).method == "astar"
    assert AStarPlanner(varying, method="auto").method == "astar"
    assert AStarPlanner(uniform, method="auto", corner_cutting=True).method == "jps"
    assert AStarPlanner(varying, method="auto", corner_cutting=True).method == "astar"
    assert AStarPlanner(uniform, method="auto", connectivity=4).method == "astar"
    assert AStarPlanner(uniform, method="auto", heuristic_weight=2.0).method == "astar"
    assert "method='jps'" in repr(AStarPlanner(uniform, method="auto"))
    for costs in (uniform, varying):
        auto = astar(costs, (0, 0), (19, 29), method="auto")
        assert auto.cost == pytest.approx(astar(costs, (0, 0), (19, 29)).cost, rel=1e-12)
    # distance_field ignores the method.
    np.testing.assert_array_equal(
        AStarPlanner(uniform, method="jps").distance_field((0, 0)),
        AStarPlanner(uniform).distance_field((0, 0)),
    )


def test_jps_rejects_grids_and_options_it_does_not_support() -> None:
    costs = np.ones((4, 5))
    varying = costs.copy()
    varying[1, 1] = 3.0
    with pytest.raises(ValueError, match="cost the same"):
        astar(varying, (0, 0), (3, 4), method="jps")
    for options in ({"connectivity": 4}, {"heuristic_weight": 0.5}):
        for cutting in (False, True):
            with pytest.raises(ValueError, match="method='jps' needs connectivity=8 and"):
                AStarPlanner(costs, method="jps", corner_cutting=cutting, **options)
    with pytest.raises(ValueError, match="cost the same"):
        astar(varying, (0, 0), (3, 4), method="jps", corner_cutting=True)
    with pytest.raises(TypeError, match="corner_cutting"):
        AStarPlanner(costs, method="jps", corner_cutting=1)  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="method must be"):
        astar(costs, (0, 0), (3, 4), method="dijkstra")
    with pytest.raises(TypeError, match="method must be"):
        astar(costs, (0, 0), (3, 4), method=None)  # type: ignore[arg-type]
    # An all-blocked grid apart from the endpoints still works.
    lone = np.full((3, 3), np.inf)
    lone[1, 1] = 1.0
    assert astar(lone, (1, 1), (1, 1), method="jps").cost == 0.0


def test_planner_copies_costs_and_inputs_are_not_modified() -> None:
    costs = np.full((6, 70), 2, dtype=np.int32)
    before = costs.copy()
    planner = AStarPlanner(costs, method="jps")
    costs[:, 35] = 10**6
    path = planner.plan((0, 0), (5, 69))
    assert path.cost == pytest.approx(2 * (64 + 5 * SQRT2), rel=1e-12)
    np.testing.assert_array_equal(costs[:, :35], before[:, :35])


def test_a_narrower_grid_after_a_wider_one_sees_only_its_own_cells() -> None:
    # 52 and 48 columns pack into the same number of 64-bit words, so the
    # second grid reuses the first one's bit-table scratch: the columns 48-51
    # the first left traversable must not become a way around the wall.
    astar(np.ones((10, 52)), (0, 0), (9, 51), method="jps")
    walled = np.ones((10, 48))
    walled[5, :] = np.inf
    with pytest.raises(NoPathError):
        astar(walled, (0, 46), (9, 46), method="jps")
    with pytest.raises(NoPathError):
        AStarPlanner(walled, method="jps").plan((0, 47), (9, 47))
    # And a grid that does have a way: the path stays inside it.
    walled[5, 47] = 1.0
    path = astar(walled, (0, 46), (9, 46), method="jps")
    assert path.cells[:, 1].max() == 47
    assert path.cost == pytest.approx(astar(walled, (0, 46), (9, 46)).cost, rel=1e-12)


def test_queue_growth_and_stamp_restart_give_the_same_paths() -> None:
    rng = np.random.default_rng(3)
    costs = np.where(rng.random((120, 160)) < 0.25, np.inf, 1.0)
    costs[59:62, 79:82] = 1.0
    planner = AStarPlanner(costs, method="jps")
    field = planner.distance_field((60, 80))
    far = np.unravel_index(np.argmax(np.where(np.isfinite(field), field, -1.0)), field.shape)
    goal = (int(far[0]), int(far[1]))
    assert field[goal] > 50.0
    expected = planner.plan((60, 80), goal)
    scratch = _astar._jps_scratch
    scratch.heap = np.empty(2, dtype=np.float64)  # room for one entry: must grow
    scratch.stamp = 2**40  # stamps are int64: no restart needed
    again = planner.plan((60, 80), goal)
    assert scratch.heap.size > 2
    assert scratch.stamp > 2**40  # each regrowth of the queue takes a new stamp
    np.testing.assert_array_equal(again.cells, expected.cells)
    assert again.cost == expected.cost


def test_threads_get_their_own_scratch() -> None:
    rng = np.random.default_rng(5)
    costs = np.where(rng.random((90, 130)) < 0.25, np.inf, 1.0)
    free = np.argwhere(np.isfinite(costs))
    pairs = [(tuple(free[i]), tuple(free[j])) for i, j in rng.integers(len(free), size=(40, 2))]
    planner = AStarPlanner(costs, method="jps")

    def cost(pair: tuple[tuple[int, int], tuple[int, int]]) -> float:
        try:
            return planner.plan(*pair).cost
        except NoPathError:
            return math.inf

    expected = [cost(p) for p in pairs]
    with ThreadPoolExecutor(4) as pool:
        assert list(pool.map(cost, pairs * 3)) == expected * 3


FRESH_PROCESS = """
import json
import numpy as np
from navkit.planning import astar
from navkit.planning.grid import _jps_cut_kernels as _cut, _jps_kernels as _kernels
costs = np.ones((8, 8))
costs[2:6, 4] = np.inf
astar(costs, (0, 0), (7, 7), method="jps")
astar(costs, (0, 0), (7, 7), method="jps", corner_cutting=True)
print(json.dumps({name: sum(getattr(module, name).stats.cache_misses.values())
                  for module, name in ((_kernels, "_build_tables"), (_kernels, "jps_search"),
                                       (_cut, "jps_cut_search"))}))
"""


def test_fresh_process_loads_jps_kernels_from_cache() -> None:
    astar(np.ones((3, 3)), (0, 0), (2, 2), method="jps")
    astar(np.ones((3, 3)), (0, 0), (2, 2), method="jps", corner_cutting=True)
    out = subprocess.run(
        [sys.executable, "-c", FRESH_PROCESS], check=True, capture_output=True, text=True
    )
    assert json.loads(out.stdout) == {"_build_tables": 0, "jps_search": 0, "jps_cut_search": 0}
