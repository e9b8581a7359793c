"""A* on cost grids: exactness against scipy, path validity, heuristics, errors."""

from __future__ import annotations

import json
import math
import subprocess
import sys
from concurrent.futures import ThreadPoolExecutor

import numpy as np
import pytest
from grid_oracle import assert_valid_path, scipy_costs_from, weighted_grids
from hypothesis import given, settings
from hypothesis import strategies as st
from record_heap import pop, pop_all, push, queued_node, replace_top
from skimage.graph import MCP_Geometric

from hypothesis_twins import slow_twin
from navkit import NavkitError, NoPathError
from navkit.planning import Path2D, astar, distance_field
from navkit.planning.grid import _workspace
from navkit.planning.grid._arguments import check_search_size
from navkit.planning.grid._search_heap import (
    REC_BASE,
    TIE_RESOLUTION,
    aligned_heap,
    tie_key,
)

SQRT2 = math.sqrt(2.0)


@settings(max_examples=50, deadline=None)
@given(
    case=weighted_grids(),
    connectivity=st.sampled_from([4, 8]),
    corner_cutting=st.booleans(),
)
def test_astar_equals_distance_field_and_scipy(
    case: tuple[np.ndarray, tuple[int, int], tuple[int, int]],
    connectivity: int,
    corner_cutting: bool,
) -> None:
    costs, start, goal = case
    reference = scipy_costs_from(costs, start, connectivity, corner_cutting)[goal]
    field = distance_field(costs, goal, connectivity=connectivity, corner_cutting=corner_cutting)
    if not math.isfinite(reference):
        assert field[start] == np.inf
        with pytest.raises(NoPathError) as info:
            astar(costs, start, goal, connectivity=connectivity, corner_cutting=corner_cutting)
        assert info.value.expanded >= 1
        return
    path = astar(costs, start, goal, connectivity=connectivity, corner_cutting=corner_cutting)
    assert path.cost == pytest.approx(reference, rel=1e-12)
    assert field[start] == pytest.approx(reference, rel=1e-12)
    cost, length = assert_valid_path(
        costs, path.cells, start, goal, connectivity=connectivity, corner_cutting=corner_cutting
    )
    assert path.cost == pytest.approx(cost, rel=1e-12)
    assert path.length == pytest.approx(length, rel=1e-12)
    # Dijkstra (weight 0) finds a path of the same optimal cost.
    dijkstra = astar(
        costs, start, goal, connectivity=connectivity, corner_cutting=corner_cutting,
        heuristic_weight=0.0,
    )
    assert dijkstra.cost == pytest.approx(reference, rel=1e-12)
    assert dijkstra.expanded >= path.expanded


test_astar_equals_distance_field_and_scipy_thoroughly = slow_twin(
    test_astar_equals_distance_field_and_scipy, max_examples=150
)


@pytest.mark.parametrize("fraction", [0.2, 0.35])
@pytest.mark.parametrize("corner_cutting", [True, False])
def test_astar_is_exact_on_larger_grids(fraction: float, corner_cutting: bool) -> None:
    # Half a million cells (past the sizes the other tests use, so heaps of
    # thousands of entries), with and without corner cutting: A* against the
    # bucket-queue field, from starts spread over the grid.
    rng = np.random.default_rng(17)
    shape = (620, 860)
    costs = np.where(rng.random(shape) < fraction, np.inf, 1.0 + 3.0 * rng.random(shape))
    goal = (619, 858)
    costs[goal] = 1.0
    field = distance_field(costs, goal, corner_cutting=corner_cutting)
    reached = np.argwhere(np.isfinite(field))
    assert len(reached) > 1000
    for k in np.linspace(0, len(reached) - 1, 7).astype(int):
        start = (int(reached[k][0]), int(reached[k][1]))
        path = astar(costs, start, goal, corner_cutting=corner_cutting)
        assert path.cost == pytest.approx(field[start], rel=1e-12)
        cost, _ = assert_valid_path(
            costs, path.cells, start, goal, connectivity=8, corner_cutting=corner_cutting
        )
        assert path.cost == pytest.approx(cost, rel=1e-12)
    blocked = np.argwhere(np.isinf(field) & np.isfinite(costs))
    if len(blocked):
        with pytest.raises(NoPathError):
            astar(costs, tuple(int(i) for i in blocked[0]), goal, corner_cutting=corner_cutting)


@settings(max_examples=40, deadline=None)
@given(case=weighted_grids(max_side=10), weight=st.floats(1.0, 5.0), corner_cutting=st.booleans())
def test_weighted_astar_respects_its_suboptimality_bound(
    case: tuple[np.ndarray, tuple[int, int], tuple[int, int]], weight: float, corner_cutting: bool
) -> None:
    costs, start, goal = case
    reference = scipy_costs_from(costs, start, 8, corner_cutting)[goal]
    if not math.isfinite(reference):
        return
    path = astar(costs, start, goal, corner_cutting=corner_cutting, heuristic_weight=weight)
    cost, _ = assert_valid_path(costs, path.cells, start, goal, corner_cutting=corner_cutting)
    assert path.cost == pytest.approx(cost, rel=1e-12)
    assert reference * (1 - 1e-12) <= path.cost <= weight * reference * (1 + 1e-12)


test_weighted_astar_respects_its_suboptimality_bound_thoroughly = slow_twin(
    test_weighted_astar_respects_its_suboptimality_bound, max_examples=100
)


def test_corner_cutting_matches_scikit_image_mcp_geometric() -> None:
    # MCP_Geometric charges step * (c_u + c_v) / 2 on a fully connected grid,
    # the corner-cutting model, and is an independent implementation.
    rng = np.random.default_rng(7)
    costs = 1.0 + 9.0 * rng.random((60, 80))
    costs[rng.random(costs.shape) < 0.2] = np.inf
    costs[0, 0] = costs[59, 79] = 1.0
    mcp = MCP_Geometric(costs, fully_connected=True)
    cumulative, _ = mcp.find_costs([(0, 0)])
    field = distance_field(costs, (0, 0), corner_cutting=True)
    reachable = np.isfinite(field)
    assert reachable.sum() > 0.5 * costs.size
    np.testing.assert_allclose(field[reachable], cumulative[reachable], rtol=1e-9)
    path = astar(costs, (0, 0), (59, 79), corner_cutting=True)
    assert path.cost == pytest.approx(cumulative[59, 79], rel=1e-9)


def test_open_grid_octile_and_tie_breaking() -> None:
    costs = np.full((40, 70), 2.5)
    path = astar(costs, (3, 5), (30, 66))
    dr, dc = 27, 61
    octile = max(dr, dc) + (SQRT2 - 1) * min(dr, dc)
    assert path.length == pytest.approx(octile, rel=1e-12)
    assert path.cost == pytest.approx(2.5 * octile, rel=1e-12)
    # The heuristic is exact on an obstacle-free uniform grid and ties in f go to
    # the smaller h, so A* expands exactly the cells of its path.
    assert path.expanded == path.cells.shape[0]
    assert astar(costs, (3, 5), (30, 66), heuristic_weight=0.0).expanded > 20 * path.expanded


def test_four_connectivity_uses_manhattan_moves() -> None:
    costs = np.ones((10, 10))
    path = astar(costs, (0, 0), (9, 9), connectivity=4)
    assert path.cost == 18.0
    assert path.length == 18.0
    assert np.all(np.abs(np.diff(path.cells, axis=0)).sum(axis=1) == 1)
    assert path.expanded == path.cells.shape[0]


def test_corner_cutting_through_a_diagonal_gap() -> None:
    costs = np.ones((2, 2))
    costs[0, 1] = costs[1, 0] = np.inf
    assert astar(costs, (0, 0), (1, 1), corner_cutting=True).cost == pytest.approx(SQRT2)
    with pytest.raises(NoPathError):
        astar(costs, (0, 0), (1, 1))
    with pytest.raises(NoPathError):
        astar(costs, (0, 0), (1, 1), connectivity=4, corner_cutting=True)


def test_start_equals_goal() -> None:
    path = astar(np.ones((3, 3)), (1, 2), (1, 2))
    assert path.cells.tolist() == [[1, 2]]
    assert path.cost == 0.0
    assert path.length == 0.0
    assert path.expanded == 1


def test_result_is_a_frozen_grid_path2d_through_cell_centres() -> None:
    path = astar(np.ones((4, 4)), (0, 0), (3, 3))
    assert isinstance(path, Path2D)
    assert path.frame == "grid"
    assert path.points.dtype == np.float64
    # A* paths run through cell centres: integer continuous coordinates.
    np.testing.assert_array_equal(path.points, path.cells)
    assert path.cells.dtype == np.int64
    assert path.cells.tolist() == [[0, 0], [1, 1], [2, 2], [3, 3]]
    with pytest.raises(ValueError):
        path.cells[0, 0] = 5
    with pytest.raises(ValueError):
        path.points[0, 0] = 5.0
    with pytest.raises(AttributeError):
        path.cost = 1.0  # type: ignore[misc]


def test_inputs_are_not_modified_and_int_costs_accepted() -> None:
    costs = np.ones((5, 6), dtype=np.int32) * 3
    before = costs.copy()
    path = astar(costs, (0, 0), (4, 5))
    assert path.cost == pytest.approx(3 * (1 + 4 * SQRT2))
    np.testing.assert_array_equal(costs, before)
    fortran = np.asfortranarray(np.ones((5, 6)))
    assert astar(fortran, (0, 0), (4, 5)).cost == pytest.approx(1 + 4 * SQRT2)


def test_no_path_error_reports_expanded_cells() -> None:
    costs = np.ones((6, 6))
    costs[:, 3] = np.inf
    with pytest.raises(NoPathError) as info:
        astar(costs, (0, 0), (5, 5))
    assert isinstance(info.value, NavkitError)
    # Everything left of the wall is expanded, nothing more.
    assert info.value.expanded == 18
    assert "expanded 18" in str(info.value)


@pytest.mark.parametrize(
    ("costs", "message"),
    [
        (np.ones(5), "2-D"),
        (np.ones((2, 2, 2)), "2-D"),
        (np.ones((0, 3)), "empty"),
        (np.ones((3, 3), dtype=bool), "dtype"),
        (np.array([["a", "b"], ["c", "d"]]), "dtype"),
        (np.array([[1.0, np.nan], [1.0, 1.0]]), r"NaN \(found at \(0, 1\)\)"),
        (np.array([[1.0, 1.0], [0.5, 1.0]]), r">= 1 .* found 0.5 at \(1, 0\)"),
        (np.array([[1.0, -np.inf], [1.0, 1.0]]), r">= 1 .* found -inf at \(0, 1\)"),
    ],
)
def test_bad_costs(costs: np.ndarray, message: str) -> None:
    with pytest.raises(ValueError, match=message):
        astar(costs, (0, 0), (0, 1))


def test_grids_beyond_the_heap_index_range_are_rejected() -> None:
    # A read-only broadcast view stands in for a 2**31-cell grid without the memory.
    huge = np.broadcast_to(np.float64(1.0), (2**16, 2**15))
    with pytest.raises(ValueError, match=r"costs has 2147483648 cells; .* at most 2147483647"):
        check_search_size(huge)
    check_search_size(huge[:, :-1])


def test_bad_endpoints_and_options() -> None:
    costs = np.ones((4, 5))
    costs[2, 2] = np.inf
    with pytest.raises(ValueError, match=r"start_cell .* outside"):
        astar(costs, (4, 0), (0, 0))
    with pytest.raises(ValueError, match=r"goal_cell .* outside"):
        astar(costs, (0, 0), (0, -1))
    with pytest.raises(ValueError, match=r"start_cell \(2, 2\) is on an impassable"):
        astar(costs, (2, 2), (0, 0))
    with pytest.raises(ValueError, match=r"goal_cell \(2, 2\) is on an impassable"):
        astar(costs, (0, 0), (2, 2))
    with pytest.raises(TypeError, match="start_cell"):
        astar(costs, (0.5, 1), (0, 0))
    with pytest.raises(ValueError, match="start_cell"):
        astar(costs, (0, 1, 2), (0, 0))
    with pytest.raises(ValueError, match="connectivity"):
        astar(costs, (0, 0), (1, 1), connectivity=6)
    with pytest.raises(TypeError, match="connectivity"):
        astar(costs, (0, 0), (1, 1), connectivity=8.0)  # type: ignore[arg-type]
    with pytest.raises(TypeError, match="corner_cutting"):
        astar(costs, (0, 0), (1, 1), corner_cutting=1)  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="heuristic_weight"):
        astar(costs, (0, 0), (1, 1), heuristic_weight=-1.0)
    with pytest.raises(ValueError, match="heuristic_weight"):
        astar(costs, (0, 0), (1, 1), heuristic_weight=math.nan)


FRESH_PROCESS = """
import json
import numpy as np
from navkit.planning import astar, distance_field
from navkit.planning.grid import _astar_kernels as _kernels
costs = np.ones((8, 8))
costs[2:6, 4] = np.inf
astar(costs, (0, 0), (7, 7))
distance_field(costs, (0, 0))
print(json.dumps({name: [sum(getattr(_kernels, name).stats.cache_hits.values()),
                         sum(getattr(_kernels, name).stats.cache_misses.values())]
                  for name in ("grid_search",)}))
"""


def test_fresh_process_loads_compiled_kernels_from_cache() -> None:
    # This process compiles (or loads) the kernels and numba writes its cache;
    # a new interpreter must then load them instead of compiling again.
    astar(np.ones((3, 3)), (0, 0), (2, 2))
    out = subprocess.run(
        [sys.executable, "-c", FRESH_PROCESS], check=True, capture_output=True, text=True
    )
    stats = json.loads(out.stdout)
    assert stats == {"grid_search": [1, 0]}


def test_reused_workspace_survives_stamp_restart_and_threads() -> None:
    rng = np.random.default_rng(11)
    grids = []
    for shape in [(40, 30), (25, 60), (40, 30)]:
        costs = 1.0 + 3.0 * rng.random(shape)
        costs[rng.random(shape) < 0.1] = np.inf
        costs[0, 0] = costs[-1, -1] = 1.0
        grids.append(costs)
    expected = [scipy_costs_from(c, (0, 0), 8, False)[-1, -1] for c in grids]
    assert np.all(np.isfinite(expected))
    # Bring the int32 stamp next to its limit so that it restarts between these
    # searches. (Not monkeypatched back: an older stamp would misread the marks
    # written here; leaving the stamp high is a valid state.)
    astar(grids[0], (0, 0), (39, 29))
    _workspace._local.stamp = _workspace._STAMP_LIMIT - 4
    for costs, cost in zip(grids * 2, expected * 2, strict=True):
        assert astar(costs, (0, 0), (-1 + costs.shape[0], -1 + costs.shape[1])).cost == (
            pytest.approx(cost, rel=1e-12)
        )
        field = distance_field(costs, (0, 0))
        assert field[-1, -1] == pytest.approx(cost, rel=1e-12)
    assert _workspace._local.stamp < 100
    # Each thread has its own workspace.
    with ThreadPoolExecutor(max_workers=3) as pool:
        jobs = [
            pool.submit(lambda c: astar(c, (0, 0), (c.shape[0] - 1, c.shape[1] - 1)).cost, c)
            for c in grids * 4
        ]
        got = [job.result() for job in jobs]
    np.testing.assert_allclose(got, expected * 4, rtol=1e-12)


def test_search_restarts_with_a_larger_queue_when_it_fills_up() -> None:
    rng = np.random.default_rng(5)
    costs = 1.0 + 4.0 * rng.random((70, 90))
    costs[rng.random(costs.shape) < 0.25] = np.inf
    costs[0, 0] = costs[-1, -1] = 1.0
    reference = scipy_costs_from(costs, (0, 0), 8, True)[-1, -1]
    assert math.isfinite(reference)
    expected = astar(costs, (0, 0), (69, 89), corner_cutting=True)
    _workspace._local.heap = aligned_heap(1)
    path = astar(costs, (0, 0), (69, 89), corner_cutting=True)
    assert _workspace._local.heap.size > 2 * (16 + REC_BASE)
    assert path.cost == expected.cost == pytest.approx(reference, rel=1e-12)
    np.testing.assert_array_equal(path.cells, expected.cells)
    assert path.expanded == expected.expanded


def test_aligned_heap_puts_sibling_slots_in_one_cache_line() -> None:
    heap = aligned_heap(100)
    assert heap.ctypes.data % 64 == 0
    assert heap.size >= 2 * (100 + REC_BASE)
    # Slots 4i + 1 .. 4i + 4 sit at entries 4(i + 1) .. 4(i + 1) + 3: 64 bytes.
    for i in range(5):
        assert (2 * (4 * i + 1 + REC_BASE) * 8) % 64 == 0


rec_ops = st.lists(
    st.tuples(
        st.sampled_from(["push", "push", "pop", "replace"]),
        st.integers(0, 199),
        st.integers(0, 10).map(float),
        st.floats(0, 5000, allow_nan=False),
    ),
    max_size=400,
)


@settings(max_examples=40, deadline=None)
@given(rec_ops)
def test_record_heap_pops_in_priority_order(sequence: list[tuple[str, int, float, float]]) -> None:
    # The packed kernel's heap keeps slots in the cell records (meta[4 v + 3]).
    heap = aligned_heap(200)
    meta = np.zeros(4 * 200, dtype=np.int32)
    ref: dict[int, tuple[float, float]] = {}
    for op, node, f, tie in sequence:
        new = (f, tie_key(tie, node, TIE_RESOLUTION))
        if op == "push":
            push(heap, meta, ref, node, new)
        elif op == "replace" and ref and node not in ref:
            best = min(ref, key=ref.__getitem__)
            assert replace_top(heap, meta, len(ref), *new) == best
            del ref[best]
            ref[node] = new
        elif op == "pop" and ref:
            best = min(ref, key=ref.__getitem__)
            assert pop(heap, meta, len(ref)) == best
            del ref[best]
        for v in ref:  # every queued node knows its slot
            slot = int(meta[4 * v + 3])
            assert queued_node(heap, slot) == v
    pop_all(heap, meta, ref)


test_record_heap_pops_in_priority_order_thoroughly = slow_twin(
    test_record_heap_pops_in_priority_order, max_examples=100
)
