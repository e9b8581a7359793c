"""A ``CellPlanner`` callable's path must run from the start cell to the goal cell (review 22).

``MapPlanner.plan`` now links the points given straight to the ends of the
cell planner's path, a link that is collision-free only inside the end's own
cell. A callable breaking the contract (a path from another cell, or
reversed) got a straight segment across the map, through the wall between:
now it gets a ValueError naming the cells it should have joined.
"""

from __future__ import annotations

from functools import partial
from typing import Any

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from navkit.mapping import OccupancyGrid
from navkit.planning import MapPlanner, Path2D, astar, plan_path


def _wall_grid() -> OccupancyGrid:
    """2 x 1 m at 0.1 m: a wall at x = 1 m from y = 0 to 0.6 m."""
    occupied = np.zeros((10, 20), dtype=bool)
    occupied[:6, 10] = True
    return OccupancyGrid.from_occupancy(occupied, resolution=0.1)


def _fixed(cells: list[list[float]]) -> Any:
    """A cell planner answering every query with ``cells`` (whatever it is asked)."""

    def planner(costs: Any, start: tuple[int, int], goal: tuple[int, int]) -> Path2D:
        return Path2D(np.array(cells, dtype=float), "grid", cost=1.0, length=1.0, expanded=0)

    return planner


def _reversed(costs: Any, start: tuple[int, int], goal: tuple[int, int]) -> Path2D:
    """A* from goal to start: the contract's ends swapped."""
    return astar(costs, goal, start)


@pytest.mark.parametrize(
    "planner",
    [_fixed([[9.0, 19.0], [9.0, 18.0]]), _fixed([[0.0, 0.0]]), _reversed],
    ids=["elsewhere", "one-cell-elsewhere", "reversed"],
)
def test_a_path_between_other_cells_is_refused(planner: Any) -> None:
    grid = _wall_grid()
    with pytest.raises(ValueError, match=r"from start_cell \(1, 2\) to goal_cell \(1, 17\)"):
        MapPlanner(grid, planner=planner).plan((0.25, 0.15), (1.75, 0.15))
    with pytest.raises(ValueError, match=r"cell planner must return a path from start_cell"):
        plan_path(grid, (0.25, 0.15), (1.75, 0.15), planner=planner)


def test_ends_off_centre_inside_their_cells_are_kept() -> None:
    # Continuous (row, col) ends inside the right cells keep the contract's
    # purpose (links inside those cells): taken, linked to the points given.
    grid = _wall_grid()
    path = MapPlanner(grid, planner=_fixed([[1.4, 2.4], [8.0, 10.0], [1.4, 16.6]])).plan(
        (0.25, 0.15), (1.75, 0.15)
    )
    assert path.points[0].tolist() == [0.25, 0.15]
    assert path.points[-1].tolist() == [1.75, 0.15]
    assert path.points.shape == (5, 2)


@settings(max_examples=30, deadline=None)
@given(
    sx=st.floats(0.0, 0.99), sy=st.floats(0.0, 0.99), gx=st.floats(1.1, 1.99),
    gy=st.floats(0.0, 0.99),
)  # fmt: skip
def test_a_keeping_callable_is_accepted_and_its_links_stay_in_their_cells(
    sx: float, sy: float, gx: float, gy: float
) -> None:
    grid = _wall_grid()
    planner = MapPlanner(grid, planner=partial(astar, corner_cutting=True))
    start, goal = np.array([sx, sy]), np.array([gx, gy])
    path = planner.plan(start, goal)
    assert np.array_equal(path.points[0], start) and np.array_equal(path.points[-1], goal)
    # Each link (the first and last segments) joins its end to the centre of the
    # end's own cell, as the grid places it (or the end took the centre's place).
    for end, inner in ((start, path.points[1]), (goal, path.points[-2])):
        centre = np.asarray(grid.cell_to_world(grid.world_to_cell(end)), dtype=float)
        assert np.allclose(inner, centre, rtol=0.0, atol=1e-12) or np.allclose(
            end, centre, rtol=0.0, atol=1e-6 * grid.resolution
        )
