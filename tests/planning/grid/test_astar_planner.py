"""AStarPlanner: validate once, answer many queries exactly as the one-shot functions do."""

from __future__ import annotations

import math
from collections.abc import Callable
from concurrent.futures import ThreadPoolExecutor

import numpy as np
import pytest
from grid_oracle import assert_valid_path, grid_graph, scipy_costs_from, weighted_grids
from hypothesis import given, settings
from hypothesis import strategies as st
from numpy.typing import ArrayLike
from scipy.sparse.csgraph import dijkstra

from hypothesis_twins import slow_twin
from navkit import NoPathError
from navkit.planning import AStarPlanner, Path2D, astar, distance_field
from navkit.planning.grid import _astar as astar_module
from navkit.planning.grid import _distance_field


def _same_path(a: Path2D, b: Path2D) -> None:
    np.testing.assert_array_equal(a.points, b.points)
    assert a.frame == b.frame == "grid"
    assert a.cost == b.cost
    assert a.length == b.length
    assert a.expanded == b.expanded


@settings(max_examples=40, deadline=None)
@given(
    case=weighted_grids(),
    connectivity=st.sampled_from([4, 8]),
    corner_cutting=st.booleans(),
    weight=st.sampled_from([0.0, 1.0, 1.7]),
    data=st.data(),
)
def test_prepared_queries_equal_the_one_shot_functions_and_scipy(
    case: tuple[np.ndarray, tuple[int, int], tuple[int, int]],
    connectivity: int,
    corner_cutting: bool,
    weight: float,
    data: st.DataObject,
) -> None:
    costs, start, goal = case
    options = {"connectivity": connectivity, "corner_cutting": corner_cutting}
    planner = AStarPlanner(costs, heuristic_weight=weight, **options)
    free = np.argwhere(np.isfinite(costs))
    # Several queries on the one planner, each against the one-shot form and scipy.
    pairs = [(start, goal)] + [
        tuple(tuple(int(v) for v in free[data.draw(st.integers(0, len(free) - 1))])
              for _ in range(2))
        for _ in range(3)
    ]
    for s, t in pairs:
        reference = scipy_costs_from(costs, s, connectivity, corner_cutting)[t]
        if not math.isfinite(reference):
            with pytest.raises(NoPathError) as prepared_error:
                planner.plan(s, t)
            with pytest.raises(NoPathError) as one_shot_error:
                astar(costs, s, t, heuristic_weight=weight, **options)
            assert prepared_error.value.expanded == one_shot_error.value.expanded >= 1
            continue
        path = planner.plan(s, t)
        _same_path(path, astar(costs, s, t, heuristic_weight=weight, **options))
        cost, length = assert_valid_path(costs, path.cells, s, t, **options)
        assert path.cost == pytest.approx(cost, rel=1e-12)
        assert path.length == pytest.approx(length, rel=1e-12)
        if weight <= 1.0:
            assert path.cost == pytest.approx(reference, rel=1e-12)
        else:
            assert reference * (1 - 1e-12) <= path.cost <= weight * reference * (1 + 1e-12)
        field = planner.distance_field(t)
        np.testing.assert_array_equal(field, distance_field(costs, t, **options))
        assert field[s] == pytest.approx(reference, rel=1e-12)


test_prepared_queries_equal_the_one_shot_functions_and_scipy_thoroughly = slow_twin(
    test_prepared_queries_equal_the_one_shot_functions_and_scipy, max_examples=100
)


def test_grid_is_validated_and_converted_once(monkeypatch: pytest.MonkeyPatch) -> None:
    rng = np.random.default_rng(5)
    costs = (1 + 4 * rng.random((50, 60))).astype(np.float32)
    costs[rng.random(costs.shape) < 0.2] = np.inf
    costs[0, 0] = costs[-1, -1] = 1.0
    planner = AStarPlanner(costs)
    assert planner.costs.dtype == np.float64
    assert planner.costs.flags.c_contiguous
    assert not planner.costs.flags.writeable
    expected = [astar(costs, (0, 0), (49, 59)), distance_field(costs, (49, 59))]

    # From here on any validation would fail: queries must not validate the grid.
    def no_validation(*args: object, **kwargs: object) -> None:
        raise AssertionError("the grid was validated again")

    monkeypatch.setattr(astar_module, "checked_cost_range", no_validation)
    for _ in range(3):
        _same_path(planner.plan((0, 0), (49, 59)), expected[0])
        np.testing.assert_array_equal(planner.distance_field((49, 59)), expected[1])


def test_planner_owns_a_copy_of_the_grid() -> None:
    costs = np.ones((6, 8))
    planner = AStarPlanner(costs)
    before = planner.plan((0, 0), (5, 7))
    costs[:, 4] = np.inf  # the caller's array changes; the planner's copy does not
    costs[2, 2] = 0.0
    _same_path(planner.plan((0, 0), (5, 7)), before)
    assert np.all(planner.costs == 1.0)
    assert costs.flags.writeable  # the caller's array is never frozen
    with pytest.raises(ValueError):
        planner.costs[0, 0] = 2.0



class _OwnArray:
    """An array-like whose ``__array__`` hands over its own array (base None)."""

    def __init__(self, data: np.ndarray) -> None:
        self.data = data

    def __array__(self, dtype: object = None, copy: object = None) -> np.ndarray:
        return self.data


@pytest.mark.parametrize(
    "wrap",
    [
        _OwnArray,
        memoryview,
        lambda a: a[:, :],  # a view
        lambda a: a,
    ],
    ids=["__array__", "memoryview", "view", "ndarray"],
)
@pytest.mark.parametrize("method", ["astar", "jps"])
def test_planner_copies_array_likes_sharing_the_callers_memory(
    wrap: Callable[[np.ndarray], ArrayLike], method: str
) -> None:
    # Only ndarrays and lists were recognised: an object whose __array__
    # returned its own array (no base) was used in place, so later changes
    # to it reached the planner.
    data = np.ones((6, 8))
    planner = AStarPlanner(wrap(data), method=method)
    before = planner.plan((0, 0), (5, 7))
    data[:, 4] = np.inf
    _same_path(planner.plan((0, 0), (5, 7)), before)
    assert np.all(planner.costs == 1.0)
    assert not np.shares_memory(planner.costs, data)


def test_many_queries_on_one_grid_and_threads() -> None:
    rng = np.random.default_rng(8)
    costs = 1.0 + 3.0 * rng.random((80, 90))
    costs[rng.random(costs.shape) < 0.15] = np.inf
    free = np.argwhere(np.isfinite(costs))
    pairs = [tuple(map(tuple, free[rng.choice(len(free), 2, replace=False)].tolist()))
             for _ in range(40)]
    planner = AStarPlanner(costs, corner_cutting=True)

    def one(pair: tuple[tuple[int, int], tuple[int, int]]) -> float:
        try:
            return planner.plan(*pair).cost
        except NoPathError:
            return math.inf

    # scipy's Dijkstra from every start on the one graph (scipy_costs_from, built once).
    graph = grid_graph(costs, 8, True)
    cols = costs.shape[1]
    dist = dijkstra(graph, directed=True, indices=[r * cols + c for (r, c), _ in pairs])
    expected = [float(row[r * cols + c]) for row, (_, (r, c)) in zip(dist, pairs, strict=True)]
    assert sum(math.isfinite(e) for e in expected) > 30
    np.testing.assert_allclose([one(p) for p in pairs], expected, rtol=1e-12)
    with ThreadPoolExecutor(max_workers=3) as pool:
        got = list(pool.map(one, pairs * 3))
    np.testing.assert_allclose(got, expected * 3, rtol=1e-12)


def test_properties_and_repr() -> None:
    planner = AStarPlanner(
        np.ones((3, 5), dtype=np.uint8), connectivity=4, corner_cutting=True,
        heuristic_weight=2,
    )
    assert planner.shape == (3, 5)
    assert planner.connectivity == 4
    assert planner.corner_cutting is True
    assert planner.heuristic_weight == 2.0
    assert repr(planner) == (
        "AStarPlanner(<3x5 costs>, connectivity=4, corner_cutting=True, heuristic_weight=2.0)"
    )
    path = planner.plan((0, 0), (2, 4))
    assert path.cost == 6.0
    assert np.all(np.abs(np.diff(path.cells, axis=0)).sum(axis=1) == 1)


def test_errors() -> None:
    costs = np.ones((4, 5))
    costs[2, 2] = np.inf
    with pytest.raises(ValueError, match="costs"):
        AStarPlanner(np.zeros((3, 3)))
    with pytest.raises(ValueError, match="connectivity"):
        AStarPlanner(costs, connectivity=6)
    with pytest.raises(TypeError, match="corner_cutting"):
        AStarPlanner(costs, corner_cutting=1)  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="heuristic_weight"):
        AStarPlanner(costs, heuristic_weight=-0.5)
    with pytest.raises(TypeError):
        AStarPlanner(costs, 4)  # type: ignore[misc]
    planner = AStarPlanner(costs)
    with pytest.raises(ValueError, match=r"start_cell \(2, 2\) is on an impassable"):
        planner.plan((2, 2), (0, 0))
    with pytest.raises(ValueError, match=r"goal_cell .* outside"):
        planner.plan((0, 0), (4, 0))
    with pytest.raises(ValueError, match=r"goal_cell \(2, 2\) is on an impassable"):
        planner.distance_field((2, 2))
    with pytest.raises(TypeError, match="start_cell"):
        planner.plan((0.5, 0), (0, 0))
    walled = np.ones((3, 3))
    walled[:, 1] = np.inf
    with pytest.raises(NoPathError) as info:
        AStarPlanner(walled).plan((0, 0), (0, 2))
    assert info.value.expanded == 3


@pytest.mark.parametrize("connectivity", [4, 8])
@pytest.mark.parametrize("corner_cutting", [False, True])
def test_distance_field_heap_fallback_equals_the_bucket_queue(
    monkeypatch: pytest.MonkeyPatch, connectivity: int, corner_cutting: bool
) -> None:
    rng = np.random.default_rng(connectivity + corner_cutting)
    costs = 1.0 + 9.0 * rng.random((45, 37))
    costs[rng.random(costs.shape) < 0.2] = np.inf
    costs[3, 4] = 1.0
    planner = AStarPlanner(costs, connectivity=connectivity, corner_cutting=corner_cutting)
    bucket = planner.distance_field((3, 4))
    monkeypatch.setattr(_distance_field, "_bucket_field", lambda *args, **kwargs: None)
    heap = planner.distance_field((3, 4))
    np.testing.assert_array_equal(heap, bucket)
    reference = scipy_costs_from(costs, (3, 4), connectivity, corner_cutting)
    np.testing.assert_allclose(heap, reference, rtol=1e-12)
