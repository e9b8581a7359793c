"""Grid planners (seventh review): copies usable side by side, errors naming the caller's
arguments, and the documented bounds of smoothing and of ``Path2D.cells``."""

from __future__ import annotations

import copy
import math
import sys
import threading

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays

from hypothesis_twins import slow_twin
from navkit import NoPathError
from navkit.mapping import OccupancyGrid
from navkit.planning import FieldDStar, MapPlanner, Path2D, field_dstar

# --- copy.copy of a MapPlanner planning with Field D* -------------------------------


class _Tagged(MapPlanner):
    __slots__ = ("tag",)
    tag: list[str]


def _walled_map() -> OccupancyGrid:
    occupied = np.zeros((40, 40), dtype=bool)
    occupied[10:30, 20] = True
    return OccupancyGrid.from_occupancy(occupied, resolution=0.1)


def test_map_planner_copies_plan_side_by_side_in_threads() -> None:
    # copy.copy shared the prepared FieldDStar, whose search state every query
    # rewrites: an original and its copy planning in two threads read each
    # other's half-finished searches (wrong paths, false NoPathError, even a
    # "least cost is inf" ValueError).
    base = MapPlanner(_walled_map(), planner="field_dstar")
    queries = [((0.05, 0.05), (3.95, 3.95)), ((3.95, 0.05), (0.05, 3.95))]
    expected = [base.plan(*query).points for query in queries]
    failures: list[str] = []

    def work(planner: MapPlanner, k: int) -> None:
        for _ in range(60):
            try:
                points = planner.plan(*queries[k]).points
            except (ValueError, NoPathError) as exc:
                failures.append(repr(exc))
                continue
            if not np.array_equal(points, expected[k]):
                failures.append("another path")

    planners = [base, copy.copy(base)]
    threads = [threading.Thread(target=work, args=(planners[k], k)) for k in (0, 1)]
    interval = sys.getswitchinterval()
    sys.setswitchinterval(1e-5)  # switch threads often, inside the Python steps of a query
    try:
        for thread in threads:
            thread.start()
        for thread in threads:
            thread.join()
    finally:
        sys.setswitchinterval(interval)
    assert failures == []


def test_map_planner_copy_keeps_its_class_the_callers_grid_and_shares_read_only_data() -> None:
    grid = _walled_map()
    planner = _Tagged(grid, planner="field_dstar")
    planner.tag = ["mine"]
    twin = copy.copy(planner)
    assert type(twin) is _Tagged and twin.tag is planner.tag
    assert twin.grid is grid and twin.costs is planner.costs
    assert not twin.costs.flags.writeable
    assert twin._prepared is not planner._prepared  # its own search state
    path, expected = twin.plan((0.05, 0.05), (3.95, 0.05)), planner.plan((0.05, 0.05), (3.95, 0.05))
    np.testing.assert_array_equal(path.points, expected.points)
    astar_planner = MapPlanner(grid)
    assert copy.copy(astar_planner)._prepared is astar_planner._prepared  # immutable: shared


# --- errors name what the caller gave -----------------------------------------------


def _split_costs() -> np.ndarray:
    costs = np.ones((4, 6))
    costs[:, 3] = np.inf
    return costs


def test_field_dstar_no_path_names_the_ends_as_given() -> None:
    # plan_cells and plan_world named "start_node"/"goal_node" (nodes the caller
    # never gave: (0, 1) for start_cell (0, 0)).
    planner = FieldDStar(_split_costs(), resolution=0.5, origin=(1.0, 2.0, 0.0))
    unreachable = r"^no path from {} to {} \(expanded \d+ nodes\)$"
    cells = unreachable.format(r"start_cell \(0, 0\)", r"goal_cell \(0, 5\)")
    with pytest.raises(NoPathError, match=cells):
        planner.plan_cells((0, 0), (0, 5))
    points = unreachable.format(r"start_xy \(1\.25, 2\.25\)", r"goal_xy \(3\.75, 2\.25\)")
    with pytest.raises(NoPathError, match=points):
        planner.plan_world((1.25, 2.25), (3.75, 2.25))
    nodes = unreachable.format(r"start_node \(1, 1\)", r"goal_node \(1, 5\)")
    with pytest.raises(NoPathError, match=nodes):
        planner.plan((1, 1), (1, 5))
    # A replan names its ends as its own method takes them.
    open_costs = np.ones((4, 6))
    planner = FieldDStar(open_costs, resolution=0.5, origin=(1.0, 2.0, 0.0))
    planner.plan_world((1.25, 2.25), (3.75, 2.25))
    planner.update_costs([(r, 3) for r in range(4)], np.inf)
    with pytest.raises(NoPathError, match=points):
        planner.replan_world()
    # The goal kept from plan_world is its nearest node, (1, 6).
    kept = unreachable.format(r"start_node \(1, 1\)", r"goal_node \(1, 6\)")
    with pytest.raises(NoPathError, match=kept):
        planner.replan((1, 1))


def test_map_planner_no_path_names_start_and_goal() -> None:
    occupied = np.zeros((4, 6), dtype=bool)
    occupied[:, 3] = True
    grid = OccupancyGrid.from_occupancy(occupied, resolution=1.0)
    for name in ("astar", "field_dstar"):
        with pytest.raises(
            NoPathError,
            match=r"^no collision-free path from start \(0\.5, 0\.5\) \(cell \(0, 0\)\) "
            r"to goal \(5\.5, 0\.5\) \(cell \(0, 5\)\) \(expanded \d+ (cells|nodes)\)$",
        ) as info:
            MapPlanner(grid, planner=name).plan((0.5, 0.5), (5.5, 0.5))
        assert info.value.expanded > 0


@pytest.mark.parametrize("value", [1e9 + 0.5, -1e9 - 0.5, 1e9 * (1 + 2**-52)])
def test_world_range_errors_print_the_value_given(value: float) -> None:
    # ":g" printed 1e9 + 0.5 as "1e+09", the limit itself, and dropped the sign.
    planner = FieldDStar(np.ones((3, 3)))
    for call in (
        lambda: planner.world_to_node((0.0, value)),
        lambda: planner.plan_world((value, 0.0), (0.5, 0.5)),
    ):
        with pytest.raises(ValueError, match=r"must lie within ±1e\+09 m, got (.*)") as info:
            call()
        assert float(str(info.value).rsplit("got ", 1)[1]) == value


def test_path_cost_limit_error_prints_the_cost_exactly() -> None:
    with pytest.raises(ValueError, match="below 2\\*\\*52 = 4503599627370496") as info:
        FieldDStar(np.full((1, 5000), 1e12)).plan_cells((0, 0), (0, 4999))
    text = str(info.value)
    assert text.startswith("costs: the least cost from start_cell (0, 0) to goal_cell (0, 4999) ")
    cost = float(text.split(" is ", 1)[1].split(" ", 1)[0])
    # From corner (0, 1) to the goal cell's centre.
    assert cost == pytest.approx((4998 + math.hypot(0.5, 0.5)) * 1e12, rel=1e-9)


# --- documented bounds ---------------------------------------------------------------


def test_smoothing_may_raise_the_cost_by_rounding_as_documented() -> None:
    # The shortcut accepts a straight run costing up to a relative 1e-12 more
    # (rounding must not block it): here the one segment along a grid line
    # sums to 1 ulp more than its pieces.
    costs = np.full((3, 7), 31.0)
    costs[2, 4] = 1.0
    raw = field_dstar(costs, (1, 5), (2, 0), smooth=False, lookahead=False)
    smooth = field_dstar(costs, (1, 5), (2, 0), smooth=True, lookahead=False)
    assert len(smooth.points) < len(raw.points)
    assert raw.cost < smooth.cost <= raw.cost * (1 + 1e-12)


@settings(max_examples=50, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(
    st.integers(2, 8).flatmap(
        lambda rows: st.integers(2, 8).flatmap(
            lambda cols: arrays(
                np.float64,
                (rows, cols),
                elements=st.one_of(st.just(np.inf), st.just(1.0), st.floats(1.0, 50.0)),
            )
        )
    ),
    st.data(),
    st.booleans(),
)
def test_smoothing_raises_the_cost_by_at_most_the_documented_allowance(
    costs: np.ndarray, data: st.DataObject, lookahead: bool
) -> None:
    rows, cols = costs.shape
    start = (data.draw(st.integers(0, rows)), data.draw(st.integers(0, cols)))
    goal = (data.draw(st.integers(0, rows)), data.draw(st.integers(0, cols)))
    try:
        raw = field_dstar(costs, start, goal, smooth=False, lookahead=lookahead)
    except (ValueError, NoPathError):
        return
    smooth = field_dstar(costs, start, goal, smooth=True, lookahead=lookahead)
    assert smooth.cost <= raw.cost * (1 + 1e-12)


test_smoothing_raises_the_cost_by_at_most_the_documented_allowance_thoroughly = slow_twin(
    test_smoothing_raises_the_cost_by_at_most_the_documented_allowance, max_examples=150
)


def test_path_cells_beyond_the_int64_range_are_clipped_as_documented() -> None:
    far = np.array([[1e300, -1e300], [2.0**62 + 2.0**11, 3.5]])
    assert Path2D(far, "grid", 0.0, 0.0, 0).cells.tolist() == [[2**62, -(2**62)], [2**62, 4]]
    # Within the range a coordinate keeps its own cell, however large.
    near = np.array([[2.0**61, -(2.0**61) - 1024.0]])
    assert Path2D(near, "grid", 0.0, 0.0, 0).cells.tolist() == [[2**61, -(2**61) - 1024]]
