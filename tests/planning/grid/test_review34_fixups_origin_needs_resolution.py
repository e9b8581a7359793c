"""``FieldDStar(costs, origin=grid.origin)`` without ``resolution`` is refused.

It planned on 1 m cells, silently: the world methods placed a 5 cm map's
nodes a metre apart, so the map's wall 0.75 m to the right of the start lay
15 m away and a route across it came back straight through the wall (1.30 m
where the route around it is 1.78 m; found by this session's reviewers; no
doc or test gave ``origin`` alone). ``origin`` is in metres and only means
something with the cell side of the same grid, so the pair is required
together, as every ``OccupancyGrid`` constructor requires ``resolution``.
``MapPlanner`` reads both from its grid; ``astar``, ``AStarPlanner`` and
``distance_field`` work in grid coordinates and take neither.
"""

from __future__ import annotations

import inspect

import numpy as np
import pytest

from navkit.mapping import OccupancyGrid
from navkit.planning import AStarPlanner, FieldDStar, MapPlanner, astar, distance_field


def _grid() -> OccupancyGrid:
    occupied = np.zeros((20, 30), dtype=bool)
    occupied[:14, 15] = True
    return OccupancyGrid.from_occupancy(occupied, resolution=0.05, origin=(-1.0, 2.0, 0.0))


@pytest.mark.parametrize(
    "origin", [(-1.0, 2.0, 0.0), (0.0, 0.0, 0.0), [0.5, 0.5, 1.0]], ids=["grid", "zero", "list"]
)
def test_origin_alone_is_refused_naming_both(origin: object) -> None:
    costs = _grid().traversal_costs()
    with pytest.raises(ValueError, match=r"^origin needs resolution") as info:
        FieldDStar(costs, origin=origin)
    assert "resolution=grid.resolution, origin=grid.origin" in str(info.value)
    with pytest.raises(ValueError, match=r"^origin needs resolution"):
        FieldDStar(costs, resolution=None, origin=origin)


def test_the_grids_origin_given_alone_is_refused() -> None:
    grid = _grid()
    with pytest.raises(ValueError, match="origin needs resolution"):
        FieldDStar(grid.traversal_costs(), origin=grid.origin)


def test_with_both_the_world_plan_is_in_metres_on_the_map() -> None:
    grid = _grid()
    costs = grid.traversal_costs()
    planner = FieldDStar(costs, resolution=grid.resolution, origin=grid.origin)
    start, goal = (-0.9, 2.1), (0.4, 2.1)
    path = planner.plan_world(start, goal)
    assert path.frame == "world"
    np.testing.assert_allclose(path.points[0], start, atol=1e-12)
    np.testing.assert_allclose(path.points[-1], goal, atol=1e-12)
    # Metres on the 1.5 x 1.0 m map, not 1 m cells.
    assert 1.5 < path.length < 3.0  # around the wall (the straight line is 1.3 m)
    assert (path.points[:, 0] >= -1.0).all() and (path.points[:, 0] <= 0.5).all()
    assert (path.points[:, 1] >= 2.0).all() and (path.points[:, 1] <= 3.0).all()


def test_the_defaults_without_origin_are_unchanged() -> None:
    costs = np.ones((4, 6))
    bare = FieldDStar(costs)
    assert bare.resolution == 1.0
    assert bare.origin.x == bare.origin.y == bare.origin.theta == 0.0
    one_metre = FieldDStar(costs, resolution=1.0, origin=(0.0, 0.0, 0.0))
    a = bare.plan_world((0.5, 0.5), (5.5, 3.5))
    b = one_metre.plan_world((0.5, 0.5), (5.5, 3.5))
    np.testing.assert_array_equal(a.points, b.points)
    assert FieldDStar(costs, resolution=0.5).plan_world((0.1, 0.1), (2.9, 1.9)).length < 4.0


def test_no_other_grid_planner_takes_the_pair() -> None:
    # Consistency: only FieldDStar has world methods of its own; the rest are grid-frame.
    for planner in (astar, AStarPlanner, distance_field):
        parameters = inspect.signature(planner).parameters
        assert "origin" not in parameters and "resolution" not in parameters, planner
    assert {"origin", "resolution"} & set(inspect.signature(MapPlanner).parameters) == set()
