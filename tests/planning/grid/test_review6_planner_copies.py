"""Copies of the stateful grid planners (sixth review): independent, read-only where documented."""

from __future__ import annotations

import copy
import pickle
from collections.abc import Callable
from typing import Any, Literal

import numpy as np
import pytest

from navkit.mapping import OccupancyGrid
from navkit.planning import AStarPlanner, FieldDStar, MapPlanner

COPIES: list[Callable[[Any], Any]] = [
    copy.copy,
    copy.deepcopy,
    lambda obj: pickle.loads(pickle.dumps(obj)),
]
COPY_IDS = ["copy", "deepcopy", "pickle"]


def _costs() -> np.ndarray:
    costs = np.ones((12, 15))
    costs[5, 1:12] = np.inf
    costs[8:, 7] = 3.0
    return costs


@pytest.mark.parametrize("clone", COPIES, ids=COPY_IDS)
def test_field_dstar_copies_do_not_share_search_state(clone: Callable[[Any], Any]) -> None:
    # copy.copy shared the cost grid and the D* Lite state: update_costs() on the
    # copy changed the original's costs without queueing the change there, so
    # the original's replan no longer matched a fresh plan on its own costs.
    costs = _costs()
    planner = FieldDStar(costs)
    first = planner.plan((0, 0), (12, 15))
    twin = clone(planner)
    twin.update_costs(np.argwhere(np.ones((12, 15)))[::3], 4.0)
    twin.update_costs([(10, 3), (11, 3)], np.inf)
    twin_path = twin.replan((1, 1))
    np.testing.assert_array_equal(planner.costs, costs)
    again = planner.replan()
    np.testing.assert_array_equal(again.points, first.points)
    assert again.cost == first.cost
    # Each side still equals a fresh plan on its own costs.
    fresh_twin = FieldDStar(twin.costs).plan((1, 1), (12, 15))
    np.testing.assert_array_equal(twin_path.points, fresh_twin.points)
    assert twin_path.cost == fresh_twin.cost
    planner.update_costs((0, 3), 2.0)
    mine = planner.replan((0, 1))
    fresh = FieldDStar(planner.costs).plan((0, 1), (12, 15))
    np.testing.assert_array_equal(mine.points, fresh.points)


@pytest.mark.parametrize("clone", COPIES, ids=COPY_IDS)
@pytest.mark.parametrize("method", ["astar", "jps"])
def test_astar_planner_copies_keep_a_read_only_grid(
    clone: Callable[[Any], Any], method: str
) -> None:
    # pickle and deepcopy handed back the kernels' flat grid writable: a second
    # compiled specialisation of every search kernel, and a grid no longer a
    # view of the planner's own (twice the memory).
    costs = _costs()
    if method == "jps":
        costs[np.isfinite(costs)] = 1.0  # JPS needs one cost
    planner = AStarPlanner(costs, method=method)
    twin = clone(planner)
    assert not twin._flat.flags.writeable
    assert np.shares_memory(twin._flat, twin._costs)
    assert not twin.costs.flags.writeable
    for start, goal in [((0, 0), (11, 14)), ((11, 0), (0, 14))]:
        path, expected = twin.plan(start, goal), planner.plan(start, goal)
        np.testing.assert_array_equal(path.points, expected.points)
        assert path.cost == expected.cost
    np.testing.assert_array_equal(twin.distance_field((0, 0)), planner.distance_field((0, 0)))


@pytest.mark.parametrize("clone", COPIES, ids=COPY_IDS)
@pytest.mark.parametrize("name", ["astar", "field_dstar"])
def test_map_planner_copies_keep_read_only_costs(
    clone: Callable[[Any], Any], name: Literal["astar", "field_dstar"]
) -> None:
    # MapPlanner.costs is documented read-only; pickle and deepcopy made it writable.
    occupied = np.zeros((12, 16), dtype=bool)
    occupied[4, 2:12] = True
    planner = MapPlanner(OccupancyGrid.from_occupancy(occupied, resolution=0.1), planner=name)
    twin = clone(planner)
    assert not twin.costs.flags.writeable
    with pytest.raises(ValueError, match="read-only"):
        twin.costs[0, 0] = np.nan
    np.testing.assert_array_equal(twin.costs, planner.costs)
    path = twin.plan((0.05, 0.05), (1.05, 1.05))
    expected = planner.plan((0.05, 0.05), (1.05, 1.05))
    np.testing.assert_array_equal(path.points, expected.points)
    assert path.cost == expected.cost
