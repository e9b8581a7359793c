"""Issue 12 on the grid planners: documented ranges, float64 limits, hostile arguments."""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from hypothesis_twins import slow_twin
from navkit import NoPathError
from navkit.planning import AStarPlanner, FieldDStar, astar, distance_field, field_dstar
from navkit.planning.grid import _limits

INF = math.inf
# The issue's grid: the only way from node (3, 0) to node (0, 4) crosses cell (1, 1).
ISSUE_GRID = [[INF, 1, 1, 1], [INF, None, 1, INF], [1, INF, 1, 1]]


def issue_grid(middle: float) -> np.ndarray:
    return np.array([[middle if v is None else v for v in row] for row in ISSUE_GRID], float)


ONE_SHOT = {
    "astar": lambda c: astar(c, (0, 0), (0, 1)),
    "distance_field": lambda c: distance_field(c, (0, 0)),
    "AStarPlanner": lambda c: AStarPlanner(c),
    "field_dstar": lambda c: field_dstar(c, (0, 0), (1, 1)),
    "FieldDStar": lambda c: FieldDStar(c),
}


# --- costs: [1, 1e12] or inf, on every planner -------------------------------------


@pytest.mark.parametrize("interpolate", [True, False])
@pytest.mark.parametrize("middle", [1e20, 1e300, np.finfo(float).max])
def test_issue_grid_with_huge_costs_is_refused(interpolate: bool, middle: float) -> None:
    # Issue 12: 1e20 raised RuntimeError "path extraction failed to reach the goal".
    with pytest.raises(ValueError, match=r"costs must be <= 1e\+12 .* at \(1, 1\)"):
        field_dstar(issue_grid(middle), (3, 0), (0, 4), interpolate=interpolate)


@pytest.mark.parametrize("interpolate", [True, False])
@pytest.mark.parametrize("middle", [1e9, 1e11, 1e12])
def test_issue_grid_works_up_to_the_maximum_cost(interpolate: bool, middle: float) -> None:
    path = field_dstar(issue_grid(middle), (3, 0), (0, 4), interpolate=interpolate)
    assert path.points[0].tolist() == [2.5, -0.5] and path.points[-1].tolist() == [-0.5, 3.5]
    assert middle < path.cost < 2.0 * middle  # it must cross the dear cell once
    a = astar(issue_grid(middle), (2, 0), (0, 3), corner_cutting=True)
    assert middle < a.cost < 2.0 * middle


@pytest.mark.parametrize("name", list(ONE_SHOT))
@pytest.mark.parametrize(
    ("value", "error"),
    [(1e12 * (1 + 2**-52), ValueError), (1e300, ValueError), (np.nan, ValueError),
     (-np.inf, ValueError), (0.5, ValueError)],
)
def test_every_planner_has_the_same_cost_range(name: str, value: float, error: type) -> None:
    costs = np.ones((2, 2))
    costs[1, 0] = value
    with pytest.raises(error, match="costs"):
        ONE_SHOT[name](costs)
    costs[1, 0] = 1e12  # the maximum itself is fine
    ONE_SHOT[name](costs)


@pytest.mark.parametrize("name", list(ONE_SHOT))
@pytest.mark.parametrize(
    "costs",
    [np.ones((2, 2)) * (1 + 1j), np.full((2, 2), "1"), np.ones((2, 2), bool),
     [[1.0, 1.0], [1.0]], {"a": 1}, "11", [[1.0, True], [1.0, 1.0]]],
    ids=["complex", "str", "bool", "ragged", "dict", "string", "bool among numbers"],
)
def test_costs_that_are_not_real_numbers(name: str, costs: Any) -> None:
    with pytest.raises(ValueError, match="costs"):
        ONE_SHOT[name](costs)


@pytest.mark.parametrize("build", [AStarPlanner, FieldDStar])
def test_too_many_cells_are_refused_before_allocating(build: Any) -> None:
    # A broadcast view: 2**31 cells, no memory. The size is checked first.
    costs = np.broadcast_to(1.0, (46341, 46341))
    with pytest.raises(ValueError, match=r"would need 2\.15e\+09 .*GiB.*2\*\*31 - 1"):
        build(costs)


def test_integer_and_float32_grids_up_to_the_maximum() -> None:
    ints = np.full((3, 3), 10**12, dtype=np.int64)
    assert astar(ints, (0, 0), (2, 2)).cost == pytest.approx(2e12 * math.sqrt(2))
    with pytest.raises(ValueError, match="1e\\+12"):
        astar(ints + 1, (0, 0), (2, 2))
    single = np.ones((3, 3), np.float32)
    assert astar(single, (0, 0), (2, 2)).cost == pytest.approx(2 * math.sqrt(2))


@pytest.mark.parametrize("weight", [-1e-300, 1e6 * (1 + 2**-52), 1e308, math.inf, math.nan])
def test_heuristic_weight_range(weight: float) -> None:
    with pytest.raises(ValueError, match=r"heuristic_weight must (lie in \[0, 1e\+06\]|be fin)"):
        astar(np.ones((3, 3)), (0, 0), (2, 2), heuristic_weight=weight)


@pytest.mark.parametrize("weight", [True, "1", 1 + 0j, None])
def test_heuristic_weight_type(weight: Any) -> None:
    with pytest.raises(TypeError, match="heuristic_weight"):
        AStarPlanner(np.ones((3, 3)), heuristic_weight=weight)


def test_largest_weight_and_costs_stay_finite() -> None:
    costs = np.full((40, 50), 1e12)
    path = astar(costs, (0, 0), (39, 49), heuristic_weight=1e6)
    assert math.isfinite(path.cost) and path.cells[-1].tolist() == [39, 49]
    assert np.all(np.isfinite(distance_field(costs, (0, 0))))


# --- Field D*: the float64 limit and the walk ----------------------------------------


def test_field_dstar_path_cost_limit() -> None:
    # 4,000 cells at 1e12 is 4e15 < 2**52: fine. 5,000 is beyond float64's resolution.
    ok = field_dstar(np.full((1, 4000), 1e12), (0, 0), (1, 4000))
    assert ok.cost == pytest.approx(1e12 * math.hypot(1, 4000), rel=1e-12)
    for interpolate in (True, False):
        limit = r"is 5\d{15}\.0 \(cost units .*below 2\*\*52 = 4503599627370496"
        with pytest.raises(ValueError, match=limit):
            field_dstar(np.full((1, 5000), 1e12), (0, 0), (1, 5000), interpolate=interpolate)


# A grid found by random search on which the walk stopped at an edge point whose
# interpolated value rounded to exactly that of node (3, 5) (costs of 1e9 next to ~5).
ROUNDED_EDGE_GRID = np.array([
    [INF, 2602830.6646243823, 77.90996070854636, 1e9, 294.0347524131588, INF,
     1493043.7007096678, 1349790.0740335411],
    [1e9, 1e9, 1e9, 1e9, 2.887345915739406, 1e9, 20898.515234943847, 510.2349828735274],
    [1e9, 23339.94418941429, 33801419.90732689, 304.170811580372, 1e9, 5.383097732341978,
     1e9, 9835.706126592318],
    [9847.333897046583, 3191.8276974052865, 234191.15533415225, 78598617.0806656,
     450039545.0371566, 311.681275027267, 126138.72152654406, INF],
    [1368.577284836821, 3.402068764853022, 1e9, 833120.1043443613, 1e9, INF, 1e9,
     258.05718899705874],
])


def test_walk_past_an_edge_point_rounded_to_a_corner_value() -> None:
    path = field_dstar(ROUNDED_EDGE_GRID, (2, 5), (5, 5))
    assert path.points[0].tolist() == [1.5, 4.5]
    assert path.points[-1].tolist() == [4.5, 4.5]
    exact = field_dstar(ROUNDED_EDGE_GRID, (2, 5), (5, 5), interpolate=False)
    assert path.cost <= exact.cost * (1 + 1e-9)


@st.composite
def hostile_grids(draw: st.DrawFn) -> tuple[np.ndarray, tuple[int, int], tuple[int, int]]:
    rows = draw(st.integers(1, 12))
    cols = draw(st.integers(1, 12))
    seed = draw(st.integers(0, 2**32 - 1))
    rng = np.random.default_rng(seed)
    top = draw(st.sampled_from([1e3, 1e6, 1e9, 1e12]))
    costs = np.exp(rng.uniform(0.0, math.log(top), (rows, cols)))
    costs[rng.random((rows, cols)) < draw(st.floats(0.0, 0.4))] = top
    costs[rng.random((rows, cols)) < 0.1] = np.inf
    start = (draw(st.integers(0, rows)), draw(st.integers(0, cols)))
    goal = (draw(st.integers(0, rows)), draw(st.integers(0, cols)))
    return costs, start, goal


@settings(max_examples=50, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(hostile_grids(), st.booleans(), st.booleans())
def test_field_dstar_reaches_the_goal_on_costs_up_to_the_maximum(
    case: tuple[np.ndarray, tuple[int, int], tuple[int, int]], interpolate: bool, lookahead: bool
) -> None:
    costs, start, goal = case
    try:
        path = field_dstar(costs, start, goal, interpolate=interpolate, lookahead=lookahead)
    except NoPathError:
        return
    except ValueError as exc:  # an end node surrounded by impassable cells
        assert "impassable" in str(exc)
        return
    assert path.points[0].tolist() == [start[0] - 0.5, start[1] - 0.5]
    assert path.points[-1].tolist() == [goal[0] - 0.5, goal[1] - 0.5]
    assert math.isfinite(path.cost) and path.cost >= 0.0


test_field_dstar_reaches_the_goal_on_costs_up_to_the_maximum_thoroughly = slow_twin(
    test_field_dstar_reaches_the_goal_on_costs_up_to_the_maximum, max_examples=300
)


# --- flags, cells and coordinates ----------------------------------------------------


@pytest.mark.parametrize("flag", ["interpolate", "lookahead", "smooth"])
@pytest.mark.parametrize("value", ["no", None, 2, 0, 1.0, np.array([True])])
def test_field_dstar_flags_must_be_bools(flag: str, value: Any) -> None:
    # Issue 12: interpolate="no" planned with interpolation on.
    with pytest.raises(TypeError, match=flag):
        field_dstar(np.ones((3, 3)), (0, 0), (3, 3), **{flag: value})
    with pytest.raises(TypeError, match=flag):
        FieldDStar(np.ones((3, 3)), **{flag: value})
    FieldDStar(np.ones((3, 3)), **{flag: np.bool_(False)})


@pytest.mark.parametrize("cell", [{0: 1, 1: 2}, (True, False), (np.True_, 0), "01", (0.5, 1),
                                  {1, 2}, None, 3])
def test_cells_must_be_integer_pairs(cell: Any) -> None:
    costs = np.ones((3, 3))
    for call in (
        lambda: astar(costs, cell, (2, 2)),
        lambda: astar(costs, (2, 2), cell),
        lambda: distance_field(costs, cell),
        lambda: field_dstar(costs, cell, (3, 3)),
        lambda: FieldDStar(costs).plan_cells(cell, (2, 2)),
    ):
        with pytest.raises((TypeError, ValueError), match=r"cell|node"):
            call()


@pytest.mark.parametrize(
    ("cells", "costs", "error", "match"),
    [
        ({0: 1, 1: 2}, 2.0, TypeError, "cells"),
        ([True, False], 2.0, TypeError, "cells"),
        ([[1, 1]], "2", TypeError, "new_costs"),
        ([[1, 1]], 2 + 1j, TypeError, "new_costs"),
        ([[1, 1]], True, TypeError, "new_costs"),
        ("11", 2.0, TypeError, "cells"),
        ([["1", "1"]], 2.0, TypeError, "cells"),
        ([[1, 1]], 1e13, ValueError, "new_costs"),
        ([[1, 1]], 1e308, ValueError, "new_costs"),
        ([[1, 1]], -np.inf, ValueError, "new_costs"),
        ([[1, np.inf]], 2.0, ValueError, "cells"),
        ([[1, 2**62]], 2.0, ValueError, "cells"),
    ],
)
def test_update_costs_refuses(cells: Any, costs: Any, error: type, match: str) -> None:
    planner = FieldDStar(np.ones((3, 3)))
    planner.plan((0, 0), (3, 3))
    before = planner.costs
    with pytest.raises(error, match=match):
        planner.update_costs(cells, costs)
    np.testing.assert_array_equal(planner.costs, before)  # nothing half-applied


def test_update_costs_accepts_the_range_and_int_arrays() -> None:
    planner = FieldDStar(np.ones((3, 4)))
    planner.plan((0, 0), (3, 4))
    planner.update_costs(np.array([[1, 1], [1, 3]], dtype=np.uint8), [1e12, np.inf])
    planner.update_costs([(0.0, 2.0)], 3.0)
    assert planner.costs[1, 1] == 1e12 and planner.costs[1, 3] == np.inf
    assert planner.costs[0, 2] == 3.0
    assert planner.replan().cost == field_dstar(planner.costs, (0, 0), (3, 4)).cost


@pytest.mark.parametrize("resolution", [0.0, 5e-324, 1e-7, 1e7, 1e308, math.inf])
def test_field_dstar_resolution_range(resolution: float) -> None:
    with pytest.raises(ValueError, match="resolution"):
        FieldDStar(np.ones((3, 3)), resolution=resolution)


def test_field_dstar_origin_and_points_range() -> None:
    with pytest.raises(ValueError, match="origin"):
        FieldDStar(np.ones((3, 3)), origin=(1e308, 0.0, 0.0))
    planner = FieldDStar(np.ones((3, 3)), resolution=1e-6, origin=(-1e9, 1e9, 0.5))
    for far in ([1e308, 0.0], [[0.0, -1e308]], [1e9 * (1 + 1e-15), 0.0]):
        with pytest.raises(ValueError, match="points_xy"):
            planner.world_to_node(far)
        with pytest.raises(ValueError, match="start_xy"):
            planner.plan_world(np.asarray(far).reshape(2), (0.0, 0.0))
    # Inside the range: finite node coordinates, exact integers when rounded.
    nodes = planner.world_to_node([1e9, -1e9], continuous=True)
    assert np.all(np.isfinite(nodes))
    with pytest.raises(ValueError, match="outside the grid"):
        planner.plan_world((1e9, -1e9), (0.0, 0.0))
    with pytest.raises(ValueError, match="nodes"):
        planner.node_to_world([2.0**60, 0.0])
    with pytest.raises(TypeError, match="continuous"):
        planner.world_to_node([0.0, 0.0], continuous="no")  # type: ignore[arg-type]
    with pytest.raises(TypeError, match="points_xy"):
        planner.world_to_node([1 + 1j, 0.0])


@pytest.mark.parametrize(
    ("value", "message"), [(math.nan, "NaN"), (0.5, ">= 1"), (2e12, "<= 1e\\+12")]
)
def test_cost_range_checks_every_block_of_a_large_grid(value: float, message: str) -> None:
    # 300 x 300 cells span two blocks of the value scan: the largest finite
    # cost and a bad value in the second block are found as in the first.
    costs = np.full((300, 300), 2.0)
    costs[::7, ::5] = np.inf
    costs[299, 298] = 9.5
    costs[0, 1] = 1.25
    grid = costs.copy()
    grid.flags.writeable = False
    path = astar(grid, (1, 1), (299, 299))
    assert path.cost > 0.0
    lowest, highest = _limits.cost_range(grid)
    assert (lowest, highest) == (1.25, 9.5)
    assert _limits.highest_finite(grid) == 9.5
    assert _limits.highest_finite(np.full((300, 300), np.inf)) == -np.inf
    costs[250, 100] = value
    with pytest.raises(ValueError, match=message):
        astar(costs, (1, 1), (299, 299))
    with pytest.raises(ValueError, match=message):
        distance_field(costs, (1, 1))


@pytest.mark.parametrize("name", list(ONE_SHOT))
def test_masked_costs_are_refused(name: str) -> None:
    # np.asarray drops the mask: a cell masked as "no value" would be planned through.
    costs = np.ma.masked_greater(np.array([[1.0, 50.0], [1.0, 1.0]]), 10.0)
    with pytest.raises(ValueError, match="costs has masked entries"):
        ONE_SHOT[name](costs)
