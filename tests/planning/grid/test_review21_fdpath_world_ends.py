"""FieldDStar's world paths begin and end at the points given, exactly (session 25, FDPATH).

They began at ``node_to_world(world_to_node(start_xy))``: (0.8500000000000001,
0.25) for (0.85, 0.25) at 0.1 m cells, where ``MapPlanner`` returns the points
given. Checked here on random grids, origins (yaw too), resolutions and points:
``plan_world``, ``replan_world`` with a new and a kept start, escaped starts
(``start_tolerance``), copies and pickles, and that cost, length and every
inner point are still those of the polyline in node coordinates. The refusals
of kept points name the point given, not its round trip.
"""

from __future__ import annotations

import copy
import math
import pickle
from typing import Any

import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st
from numpy.typing import NDArray

from navkit.errors import NoPathError
from navkit.mapping import OccupancyGrid
from navkit.planning import FieldDStar, MapPlanner
from navkit.planning.grid import Path2D


@st.composite
def _grids(draw: st.DrawFn) -> NDArray[np.float64]:
    rows = draw(st.integers(2, 12))
    cols = draw(st.integers(2, 12))
    seed = draw(st.integers(0, 2**32 - 1))
    rng = np.random.default_rng(seed)
    costs = rng.choice([1.0, 1.0, 2.5, 7.0, np.inf], size=(rows, cols))
    costs[draw(st.integers(0, rows - 1)), draw(st.integers(0, cols - 1))] = 1.0  # one free
    return np.asarray(costs, dtype=np.float64)


# Decimal resolutions (0.1 m does not convert exactly) as well as powers of two.
_RESOLUTIONS = st.sampled_from([0.05, 0.1, 0.3, 0.25, 1.0 / 3.0, 1.7])
_ORIGINS = st.tuples(
    st.floats(-1e4, 1e4, allow_nan=False),
    st.floats(-1e4, 1e4, allow_nan=False),
    st.sampled_from([0.0, 0.3, -2.0, math.pi / 2]),
)


def _point(draw: Any, planner: FieldDStar, costs: NDArray[np.float64]) -> tuple[float, float]:
    """A world point inside a passable cell: some on a decimal lattice, some anywhere.

    The cell is drawn among the passable ones, and a point rounded out of them
    keeps its digits: drawn anywhere and filtered, the inputs failed
    hypothesis's filter_too_much health check now and then (review 52).
    """
    rows, cols = costs.shape

    def passable(xy: NDArray[np.float64]) -> bool:
        p = planner.world_to_node(xy, continuous=True)
        r, c = math.floor(p[0]), math.floor(p[1])
        return 0 <= r < rows and 0 <= c < cols and math.isfinite(costs[r, c])

    free = np.argwhere(np.isfinite(costs))
    row, col = free[draw(st.integers(0, free.shape[0] - 1))]
    node = (
        float(row) + draw(st.floats(0.0, 1.0, exclude_max=True)),
        float(col) + draw(st.floats(0.0, 1.0, exclude_max=True)),
    )
    xy = planner.node_to_world(node)
    if draw(st.booleans()):
        rounded = np.round(xy, draw(st.integers(1, 3)))  # as a user types them
        if passable(rounded):
            xy = rounded
    assume(passable(xy))  # a point on a cell's edge may round into its neighbour
    return float(xy[0]), float(xy[1])


def _ends_exact(path: Path2D, start: tuple[float, float], goal: tuple[float, float]) -> None:
    assert path.frame == "world"
    assert path.points.dtype == np.float64
    assert path.points[0].tolist() == list(start)
    assert path.points[-1].tolist() == list(goal)


def _node_polyline(planner: FieldDStar, path: Path2D) -> None:
    """Inner points are the node polyline's; the ends within a rounding step of theirs."""
    trip = planner.node_to_world(planner.world_to_node(path.points, continuous=True))
    scale = max(1.0, float(np.abs(path.points).max()))
    np.testing.assert_allclose(path.points, trip, rtol=0, atol=1e-9 * scale)


@settings(max_examples=150, deadline=None)
@given(data=st.data(), costs=_grids(), resolution=_RESOLUTIONS, origin=_ORIGINS)
def test_world_paths_begin_and_end_at_the_points_given(
    data: st.DataObject,
    costs: NDArray[np.float64],
    resolution: float,
    origin: tuple[float, float, float],
) -> None:
    planner = FieldDStar(costs, resolution=resolution, origin=origin)
    start = _point(data.draw, planner, costs)
    goal = _point(data.draw, planner, costs)
    try:
        path = planner.plan_world(start, goal)
    except NoPathError:
        return
    _ends_exact(path, start, goal)
    _node_polyline(planner, path)
    # Cost as a planner whose ends are given as the nodes' round trip: it comes
    # from node coordinates, which the points given and their trips share; the
    # length is that of the points (review 54, FOUND7), whose ends differ by the trip.
    p_s = planner.world_to_node(start, continuous=True)
    p_g = planner.world_to_node(goal, continuous=True)
    trip_s = tuple(planner.node_to_world(p_s).tolist())
    trip_g = tuple(planner.node_to_world(p_g).tolist())
    same = planner.world_to_node([trip_s, trip_g], continuous=True)
    if same.tolist() == [p_s.tolist(), p_g.tolist()]:
        other = FieldDStar(costs, resolution=resolution, origin=origin).plan_world(trip_s, trip_g)
        assert other.cost == path.cost
        # Ends moved by the trip change the length by at most the distances moved.
        moved = math.dist(start, trip_s) + math.dist(goal, trip_g)
        assert abs(other.length - path.length) <= moved + 1e-12 * path.length
        np.testing.assert_array_equal(other.points[1:-1], path.points[1:-1])
        _ends_exact(other, trip_s, trip_g)

    # A kept start and goal, in the replan, in a copy and a pickle.
    twin = copy.deepcopy(planner)
    loaded = pickle.loads(pickle.dumps(planner))
    for p in (planner, twin, loaded):
        again = p.replan_world()
        _ends_exact(again, start, goal)
        assert (again.cost, again.length) == (path.cost, path.length)
    # A new start, then kept again.
    moved = _point(data.draw, planner, costs)
    try:
        replanned = planner.replan_world(moved)
    except NoPathError:
        return
    _ends_exact(replanned, moved, goal)
    _ends_exact(planner.replan_world(), moved, goal)
    fresh = FieldDStar(costs, resolution=resolution, origin=origin).plan_world(moved, goal)
    np.testing.assert_array_equal(replanned.points, fresh.points)
    assert (replanned.cost, replanned.length) == (fresh.cost, fresh.length)


def test_the_reported_case() -> None:
    planner = FieldDStar(np.ones((10, 10)), resolution=0.1)
    node = planner.world_to_node((0.85, 0.25), continuous=True)
    # The round trip is a rounding step off: what the paths began at.
    assert planner.node_to_world(node).tolist() == [0.8500000000000001, 0.25]
    path = planner.plan_world((0.85, 0.25), (0.15, 0.95))
    _ends_exact(path, (0.85, 0.25), (0.15, 0.95))
    # An escaped start, as MapPlanner's (whose paths otherwise run from cell centres).
    occupied = np.zeros((10, 20), dtype=bool)
    occupied[:6, 10] = True
    grid = OccupancyGrid.from_occupancy(occupied, resolution=0.1)
    mp = MapPlanner(grid, robot_radius=0.2, planner="field_dstar")
    theirs = mp.plan((0.85, 0.25), (1.55, 0.25), start_tolerance=0.2)
    ours = _band_planner().plan_world((0.85, 0.25), (1.55, 0.25), start_tolerance=0.2)
    assert theirs.points[0].tolist() == ours.points[0].tolist() == [0.85, 0.25]
    assert ours.points[-1].tolist() == [1.55, 0.25]


def test_equal_points_give_one_point() -> None:
    planner = FieldDStar(np.ones((4, 4)), resolution=0.1, origin=(0.3, 0.7, 0.2))
    path = planner.plan_world((0.55, 0.95), (0.55, 0.95))
    assert path.points.tolist() == [[0.55, 0.95]]
    assert (path.cost, path.length) == (0.0, 0.0)


def _band_planner() -> FieldDStar:
    occupied = np.zeros((10, 20), dtype=bool)
    occupied[:6, 10] = True
    grid = OccupancyGrid.from_occupancy(occupied, resolution=0.1)
    return FieldDStar(
        grid.traversal_costs(robot_radius=0.2), resolution=0.1, obstacles=grid.occupied()
    )


@settings(max_examples=60, deadline=None)
@given(
    x=st.floats(0.8, 0.899),
    y=st.floats(0.0, 0.5),
    digits=st.sampled_from([None, 2, 3]),
)
def test_escaped_starts_begin_at_the_point_given(x: float, y: float, digits: int | None) -> None:
    start = (x, y) if digits is None else (round(x, digits), round(y, digits))
    goal = (1.55, 0.25)
    planner = _band_planner()
    try:
        path = planner.plan_world(start, goal, start_tolerance=0.25)
    except ValueError:
        return  # not in the band, or no escape within the tolerance
    _ends_exact(path, start, goal)
    # Kept (escaped again), and given again to replan_world.
    _ends_exact(planner.replan_world(start_tolerance=0.25), start, goal)
    _ends_exact(planner.replan_world(start, start_tolerance=0.25), start, goal)
    _ends_exact(pickle.loads(pickle.dumps(planner)).replan_world(start_tolerance=0.25), start, goal)


def test_refusals_of_kept_points_name_the_point_given() -> None:
    # An escaped start kept, refused without a tolerance.
    planner = _band_planner()
    planner.plan_world((0.85, 0.25), (1.55, 0.25), start_tolerance=0.2)
    with pytest.raises(ValueError, match=r"start_xy \(0\.85, 0\.25\) \(kept from the last plan\)"):
        planner.replan_world()
    # A kept start and a kept goal whose cells update_costs() closed.
    planner = FieldDStar(np.ones((10, 10)), resolution=0.1)
    planner.plan_world((0.85, 0.25), (0.15, 0.95))
    planner.update_costs([(2, 8)], np.inf)
    with pytest.raises(ValueError, match=r"start_xy \(0\.85, 0\.25\) \(kept from the last plan\)"):
        planner.replan_world()
    planner.update_costs([(2, 8)], 1.0)
    planner.update_costs([(9, 1)], np.inf)
    with pytest.raises(ValueError, match=r"goal_xy \(0\.15, 0\.95\) \(kept from the last plan\)"):
        planner.replan_world()
    # No path: the message names the ends as given.
    planner.update_costs([(9, 1)], 1.0)
    planner.update_costs([(r, 5) for r in range(10)], np.inf)
    unreachable = r"no path from start_xy \(0\.85, 0\.25\) to goal_xy \(0\.15, 0\.95\)"
    with pytest.raises(NoPathError, match=unreachable):
        planner.replan_world()


def test_node_and_cell_ends_keep_their_world_points() -> None:
    # Ends given as nodes or cells have no world point given: their world points.
    planner = FieldDStar(np.ones((6, 6)), resolution=0.1, origin=(0.05, 0.0, 0.0))
    planner.plan((1, 1), (5, 5))
    path = planner.replan_world()
    assert path.points[[0, -1]].tolist() == planner.node_to_world([(1, 1), (5, 5)]).tolist()
    planner.plan_world((0.25, 0.15), (0.45, 0.55))
    planner.replan((2, 2))  # a node start replaces the point given; the goal point stays
    path = planner.replan_world()
    assert path.points[0].tolist() == planner.node_to_world((2, 2)).tolist()
    assert path.points[-1].tolist() == [0.45, 0.55]
    planner.plan_cells((0, 0), (4, 4))
    path = planner.replan_world((0.25, 0.15))
    assert path.points[0].tolist() == [0.25, 0.15]
    assert path.points[-1].tolist() == planner.node_to_world((4.5, 4.5)).tolist()
