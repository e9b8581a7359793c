"""Cost-to-go fields: closed forms, Bellman optimality, scipy, errors."""

from __future__ import annotations

import math

import numpy as np
import pytest
from grid_oracle import DIAG, ORTHO, move_allowed, move_cost, scipy_costs_from, weighted_grids
from hypothesis import given, settings
from hypothesis import strategies as st

from hypothesis_twins import slow_twin
from navkit.planning import AStarPlanner, astar, distance_field
from navkit.planning.grid import _distance_field as distance_field_module
from navkit.planning.grid._distance_field import _bucket_field
from navkit.planning.grid._limits import checked_cost_range

SQRT2 = math.sqrt(2.0)


@settings(max_examples=40, deadline=None)
@given(
    case=weighted_grids(max_side=9),
    connectivity=st.sampled_from([4, 8]),
    corner_cutting=st.booleans(),
)
def test_field_equals_scipy_and_satisfies_bellman(
    case: tuple[np.ndarray, tuple[int, int], tuple[int, int]],
    connectivity: int,
    corner_cutting: bool,
) -> None:
    costs, _, goal = case
    field = distance_field(costs, goal, connectivity=connectivity, corner_cutting=corner_cutting)
    reference = scipy_costs_from(costs, goal, connectivity, corner_cutting)
    np.testing.assert_array_equal(np.isinf(field), np.isinf(reference))
    finite = np.isfinite(reference)
    np.testing.assert_allclose(field[finite], reference[finite], rtol=1e-12)
    # Bellman: every reachable cell but the goal is one optimal move from a
    # cell nearer the goal.
    moves = ORTHO + DIAG if connectivity == 8 else ORTHO
    for r, c in np.argwhere(finite).tolist():
        if (r, c) == goal:
            assert field[r, c] == 0.0
            continue
        best = min(
            field[r + dr, c + dc] + move_cost(costs, r, c, dr, dc)
            for dr, dc in moves
            if move_allowed(costs, r, c, dr, dc, corner_cutting)
        )
        assert field[r, c] == pytest.approx(best, rel=1e-12)


test_field_equals_scipy_and_satisfies_bellman_thoroughly = slow_twin(
    test_field_equals_scipy_and_satisfies_bellman, max_examples=100
)


def test_empty_grid_gives_closed_form_distances() -> None:
    rows, cols = np.mgrid[0:30, 0:45]
    dr = np.abs(rows - 12)
    dc = np.abs(cols - 40)
    octile = np.maximum(dr, dc) + (SQRT2 - 1) * np.minimum(dr, dc)
    np.testing.assert_allclose(distance_field(np.ones((30, 45)), (12, 40)), octile, rtol=1e-12)
    np.testing.assert_allclose(
        distance_field(np.full((30, 45), 3.0), (12, 40), connectivity=4), 3.0 * (dr + dc),
        rtol=1e-12,
    )


def test_walls_make_cells_unreachable() -> None:
    costs = np.ones((5, 7))
    costs[:, 4] = np.inf
    field = distance_field(costs, (2, 1))
    assert np.all(np.isinf(field[:, 4:]))
    assert np.all(np.isfinite(field[:, :4]))
    # A one-cell gap lets the field through.
    costs[4, 4] = 1.0
    opened = distance_field(costs, (2, 1))
    assert np.all(np.isfinite(opened[:, 5:]))
    assert opened[0, 6] == pytest.approx(astar(costs, (0, 6), (2, 1)).cost, rel=1e-12)


def test_field_descent_reproduces_the_optimal_cost() -> None:
    rng = np.random.default_rng(3)
    costs = 1.0 + 3.0 * rng.random((40, 40))
    costs[rng.random(costs.shape) < 0.25] = np.inf
    costs[0, 0] = costs[39, 39] = 1.0
    field = distance_field(costs, (39, 39))
    path = astar(costs, (0, 0), (39, 39))
    assert field[0, 0] == pytest.approx(path.cost, rel=1e-12)
    # Along A*'s path the field drops by exactly each move's cost.
    for (r, c), (r2, c2) in zip(path.cells[:-1].tolist(), path.cells[1:].tolist(), strict=True):
        step = move_cost(costs, r, c, r2 - r, c2 - c)
        assert field[r, c] - field[r2, c2] == pytest.approx(step, rel=1e-9, abs=1e-9)


def test_input_not_modified_and_errors() -> None:
    costs = np.ones((4, 4))
    costs[1, 1] = np.inf
    before = costs.copy()
    distance_field(costs, (0, 0))
    np.testing.assert_array_equal(costs, before)
    with pytest.raises(ValueError, match=r"goal_cell \(1, 1\) is on an impassable"):
        distance_field(costs, (1, 1))
    with pytest.raises(ValueError, match=r"goal_cell .* outside"):
        distance_field(costs, (9, 0))
    with pytest.raises(ValueError, match=">= 1"):
        distance_field(np.zeros((3, 3)), (0, 0))
    with pytest.raises(ValueError, match="connectivity"):
        distance_field(costs, (0, 0), connectivity=3)
    with pytest.raises(TypeError, match="corner_cutting"):
        distance_field(costs, (0, 0), corner_cutting="yes")  # type: ignore[arg-type]


@st.composite
def _cost_grids(draw: st.DrawFn) -> tuple[np.ndarray, tuple[int, int]]:
    """Grids of the bucket queue's three regimes: uniform, narrow-range and wide-range costs."""
    rows = draw(st.integers(1, 24))
    cols = draw(st.integers(1, 24))
    seed = draw(st.integers(0, 2**32 - 1))
    kind = draw(st.sampled_from(["uniform", "integer", "wide"]))
    rng = np.random.default_rng(seed)
    if kind == "uniform":
        costs = np.full((rows, cols), draw(st.sampled_from([1.0, 3.0, 0.1 + 2.0**30])))
    elif kind == "integer":
        costs = rng.integers(1, 41, (rows, cols)).astype(np.float64)
    else:
        costs = np.exp(rng.random((rows, cols)) * 27.0)
    costs[rng.random((rows, cols)) < draw(st.floats(0.0, 0.6))] = np.inf
    goal = (int(rng.integers(rows)), int(rng.integers(cols)))
    costs[goal] = 1.5
    return costs, goal


@settings(max_examples=50, deadline=None)
@given(case=_cost_grids(), connectivity=st.sampled_from([4, 8]), corner_cutting=st.booleans())
def test_field_is_bit_identical_to_the_heap_dijkstra(
    case: tuple[np.ndarray, tuple[int, int]], connectivity: int, corner_cutting: bool
) -> None:
    # The bucket queue and the A* kernel's heap reach the same least
    # fixed point of the Bellman equations with the same float operations.
    costs, goal = case
    options = {"connectivity": connectivity, "corner_cutting": corner_cutting}
    expected = AStarPlanner(costs, **options).distance_field(goal)
    np.testing.assert_array_equal(distance_field(costs, goal, **options), expected)


test_field_is_bit_identical_to_the_heap_dijkstra_thoroughly = slow_twin(
    test_field_is_bit_identical_to_the_heap_dijkstra, max_examples=150
)


def test_bucket_segments_grow_and_wide_cost_ranges_fall_back() -> None:
    rng = np.random.default_rng(11)
    costs = rng.integers(1, 5, (70, 90)).astype(np.float64)
    costs[rng.random(costs.shape) < 0.2] = np.inf
    costs[35, 45] = 1.0
    grid, lowest, highest = checked_cost_range(costs)
    for eight in (False, True):
        default = _bucket_field(grid, lowest, highest, (35, 45), eight, False)
        tiny = _bucket_field(grid, lowest, highest, (35, 45), eight, False, cap=8)
        assert default is not None and tiny is not None
        np.testing.assert_array_equal(tiny, default)
    # Costs spanning 1..1e6 would need a million buckets: the heap answers.
    costs[0, 0] = 1e6
    grid, lowest, highest = checked_cost_range(costs)
    assert highest == 1e6
    assert _bucket_field(grid, lowest, highest, (35, 45), True, False) is None
    np.testing.assert_array_equal(
        distance_field(costs, (35, 45)), AStarPlanner(costs).distance_field((35, 45))
    )


def test_grids_whose_padded_cells_overflow_int32_use_the_heap(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    # The bucket queue stores padded cell ids, (rows + 2) * (cols + 2) of them, in
    # int32: a 46340 x 46340 grid is within the 2**31 - 1 cell limit, but its padded
    # ids above 2**31 - 1 wrapped around (wrong cells relaxed, out-of-range writes).
    assert 46340**2 <= distance_field_module.MAX_PADDED_CELLS < 46342**2
    # A read-only broadcast view stands in for the grid: refused before allocating.
    huge = np.broadcast_to(np.float64(1.0), (46340, 46340))
    assert _bucket_field(huge, 1.0, 1.0, (0, 0), True, False) is None
    # Past the limit the field comes from the heap Dijkstra, bit for bit the same.
    costs = np.ones((4, 4))
    costs[1, 1:3] = np.inf
    costs[3, 0] = 2.5
    expected = distance_field(costs, (0, 0))
    monkeypatch.setattr(distance_field_module, "MAX_PADDED_CELLS", 35)
    grid, lowest, highest = checked_cost_range(costs)
    assert _bucket_field(grid, lowest, highest, (0, 0), True, False) is None
    np.testing.assert_array_equal(distance_field(costs, (0, 0)), expected)
