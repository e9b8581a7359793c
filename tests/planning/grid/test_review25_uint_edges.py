"""Searches along the map's edges and corners, on 1-row and 1-column maps, start == goal.

Review 25 (issue 17, unsigned indices): the jump point search's bit scans
index the bit tables with ``np.uint64`` (numba then emits no wraparound code
for a negative index); the same was tried, and dropped for want of speed, in
the search's node records and queue, the distance field's bucket Dijkstra
and Field D*'s D* Lite search and path walk. An unsigned index that could be
negative after all (a line above row 0 or left of column 0, a word before
a line's first) would no longer read the array's other end but far outside
it. These tests put each of the three searches where such indices arise
(and guard the dropped changes, should they return): paths along the four
edges of a map whose interior is blocked, ends at the four corners (start ==
goal among them), maps of one row or one column, 1 x 1, lines longer than a
64-cell word of the bit tables, with and without corner cutting, 4- and
8-connected. Each result is checked against an oracle that shares no code
with the kernels (scipy's Dijkstra on the graph the planners document); the
distance field also against the heap Dijkstra of the A* kernel, bit for bit,
and Field D*'s repairs against fresh plans, bit for bit.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
import scipy.sparse
from grid_oracle import assert_valid_path, scipy_costs_from
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.sparse.csgraph import dijkstra

from hypothesis_twins import slow_twin
from navkit.errors import NoPathError
from navkit.planning import AStarPlanner, FieldDStar, distance_field


def _corners(rows: int, cols: int) -> list[tuple[int, int]]:
    return [(0, 0), (0, cols - 1), (rows - 1, 0), (rows - 1, cols - 1)]


@st.composite
def edge_grids(draw: st.DrawFn, uniform: bool) -> np.ndarray:
    """A grid whose border ring is free: 1-9 rows and columns, or long and thin.

    Long ones (1-6 rows of 60-140 cells, or the transpose) cross a word of
    the jump point search's bit rows (64 cells), where a scan borrows the
    edge bit of the next word. Its interior is blocked (paths go round the
    edges), free, or blocked at random; costs 1 or, unless ``uniform``, drawn
    from 1-5.
    """
    if draw(st.booleans()):
        rows = draw(st.integers(1, 9))
        cols = draw(st.integers(1, 9))
    else:
        rows = draw(st.integers(1, 6))
        cols = draw(st.integers(60, 140))
        if draw(st.booleans()):
            rows, cols = cols, rows
    rng = np.random.default_rng(draw(st.integers(0, 2**32 - 1)))
    costs = np.ones((rows, cols)) if uniform else rng.integers(1, 6, (rows, cols)).astype(float)
    kind = draw(st.sampled_from(["frame", "open", "random"]))
    inner = costs[1:-1, 1:-1]
    if kind == "frame":
        inner[...] = np.inf
    elif kind == "random":
        inner[rng.random(inner.shape) < 0.4] = np.inf
    return costs


FIXED = [
    np.ones((1, 1)),
    np.ones((1, 9)),
    np.ones((9, 1)),
    np.ones((2, 9)),
    np.pad(np.full((3, 5), np.inf), 1, constant_values=1.0),  # a 5 x 7 frame
    np.pad(np.full((1, 1), np.inf), 1, constant_values=1.0),  # a 3 x 3 ring
]


# ------------------------------------------------------------------- jump point search


def _check_jps(costs: np.ndarray, corner_cutting: bool) -> None:
    rows, cols = costs.shape
    planner = AStarPlanner(costs, method="jps", corner_cutting=corner_cutting)
    for start in _corners(rows, cols):
        want = scipy_costs_from(costs, start, 8, corner_cutting)
        for goal in _corners(rows, cols):
            if not math.isfinite(want[goal]):
                with pytest.raises(NoPathError):
                    planner.plan(start, goal)
                continue
            path = planner.plan(start, goal)
            cost, _ = assert_valid_path(
                costs, path.cells, start, goal, corner_cutting=corner_cutting
            )
            assert path.cost == pytest.approx(want[goal], rel=1e-12, abs=1e-12)
            assert cost == pytest.approx(want[goal], rel=1e-12, abs=1e-12)


@pytest.mark.parametrize("corner_cutting", [False, True])
@pytest.mark.parametrize("costs", FIXED, ids=lambda c: "x".join(map(str, c.shape)))
def test_jps_between_corners_of_thin_and_framed_maps(
    costs: np.ndarray, corner_cutting: bool
) -> None:
    _check_jps(costs, corner_cutting)


@settings(max_examples=40, deadline=None)
@given(edge_grids(uniform=True), st.booleans())
def test_jps_between_corners_is_optimal(costs: np.ndarray, corner_cutting: bool) -> None:
    _check_jps(costs, corner_cutting)


test_jps_between_corners_is_optimal_thoroughly = slow_twin(
    test_jps_between_corners_is_optimal, max_examples=400
)


# ------------------------------------------------------------------------ distance field


def _check_field(costs: np.ndarray, connectivity: int, corner_cutting: bool) -> None:
    rows, cols = costs.shape
    heap = AStarPlanner(costs, connectivity=connectivity, corner_cutting=corner_cutting)
    for goal in _corners(rows, cols):
        field = distance_field(
            costs, goal, connectivity=connectivity, corner_cutting=corner_cutting
        )
        # The bucket queue's field is the heap Dijkstra's, bit for bit (the documented
        # promise), and the oracle's (the graph is symmetric: costs to = costs from).
        np.testing.assert_array_equal(field, heap.distance_field(goal))
        want = scipy_costs_from(costs, goal, connectivity, corner_cutting)
        np.testing.assert_array_equal(np.isfinite(field), np.isfinite(want))
        reach = np.isfinite(want)
        np.testing.assert_allclose(field[reach], want[reach], rtol=1e-12)


@pytest.mark.parametrize(("connectivity", "corner_cutting"), [(8, False), (8, True), (4, False)])
@pytest.mark.parametrize("costs", FIXED, ids=lambda c: "x".join(map(str, c.shape)))
def test_distance_field_from_corners_of_thin_and_framed_maps(
    costs: np.ndarray, connectivity: int, corner_cutting: bool
) -> None:
    _check_field(costs, connectivity, corner_cutting)
    _check_field(costs * 3.0, connectivity, corner_cutting)  # uniform, not 1


@settings(max_examples=40, deadline=None)
@given(
    edge_grids(uniform=False),
    st.sampled_from([(8, False), (8, True), (4, False)]),
)
def test_distance_field_from_corners_is_dijkstra(
    costs: np.ndarray, moves: tuple[int, bool]
) -> None:
    _check_field(costs, *moves)


test_distance_field_from_corners_is_dijkstra_thoroughly = slow_twin(
    test_distance_field_from_corners_is_dijkstra, max_examples=400
)


# ------------------------------------------------------------------------------ Field D*


def _node_costs_from(costs: np.ndarray, source: tuple[int, int]) -> np.ndarray:
    """8-connected node-graph costs from node ``source`` (the class's interpolate=False model).

    Node (i, j) is the top-left corner of cell (i, j); an axis move pays the
    cheaper of the two cells beside its edge, a diagonal sqrt(2) times the cell
    it crosses (cells off the grid are impassable).
    """
    rows, cols = costs.shape
    n_cols = cols + 1

    def cell(r: int, c: int) -> float:
        return float(costs[r, c]) if 0 <= r < rows and 0 <= c < cols else math.inf

    src: list[int] = []
    dst: list[int] = []
    weight: list[float] = []
    for i in range(rows + 1):
        for j in range(cols + 1):
            for di in (-1, 0, 1):
                for dj in (-1, 0, 1):
                    i2, j2 = i + di, j + dj
                    if (di, dj) == (0, 0) or not (0 <= i2 <= rows and 0 <= j2 <= cols):
                        continue
                    r, c = min(i, i2), min(j, j2)
                    if di == 0:
                        w = min(cell(i - 1, c), cell(i, c))
                    elif dj == 0:
                        w = min(cell(r, j - 1), cell(r, j))
                    else:
                        w = math.sqrt(2.0) * cell(r, c)
                    if math.isfinite(w):
                        src.append(i * n_cols + j)
                        dst.append(i2 * n_cols + j2)
                        weight.append(w)
    n = (rows + 1) * n_cols
    graph = scipy.sparse.csr_matrix((weight, (src, dst)), shape=(n, n))
    dist = dijkstra(graph, directed=True, indices=source[0] * n_cols + source[1])
    return np.asarray(dist).reshape(rows + 1, n_cols)


def _check_field_dstar(costs: np.ndarray) -> None:
    rows, cols = costs.shape
    corners = [(0, 0), (0, cols), (rows, 0), (rows, cols)]
    eight = FieldDStar(costs, interpolate=False)
    for goal in corners:
        want = _node_costs_from(costs, goal)
        for start in corners:
            # Every corner node touches a free corner cell (the border ring is free).
            path = eight.plan(start, goal)
            assert path.cost == pytest.approx(want[start], rel=1e-9, abs=1e-12)
            planner = FieldDStar(costs)
            fresh = planner.plan(start, goal)
            # (No bound against the 8-connected cost: the interpolated polyline may
            # cost a little more, 0.1 % on one of these grids, as before review 25.)
            np.testing.assert_array_equal(fresh.points[0], np.array(start) - 0.5)
            np.testing.assert_array_equal(fresh.points[-1], np.array(goal) - 0.5)
            assert np.all(fresh.points >= -0.5)
            assert np.all(fresh.points <= np.array([rows, cols]) - 0.5)
            # A repair after a corner cell's cost rises and falls again is the
            # fresh plan on the final costs, bit for bit.
            for value in (costs[0, 0] + 2.0, costs[0, 0]):
                planner.update_costs([(0, 0)], value)
                changed = costs.copy()
                changed[0, 0] = value
                repaired = planner.replan()
                again = FieldDStar(changed).plan(start, goal)
                np.testing.assert_array_equal(repaired.points, again.points)
                assert repaired.cost == again.cost


@pytest.mark.parametrize("costs", FIXED, ids=lambda c: "x".join(map(str, c.shape)))
def test_field_dstar_between_corner_nodes_of_thin_and_framed_maps(costs: np.ndarray) -> None:
    _check_field_dstar(costs)


@settings(max_examples=25, deadline=None)
@given(edge_grids(uniform=False))
def test_field_dstar_between_corner_nodes(costs: np.ndarray) -> None:
    _check_field_dstar(costs)


test_field_dstar_between_corner_nodes_thoroughly = slow_twin(
    test_field_dstar_between_corner_nodes, max_examples=200
)
