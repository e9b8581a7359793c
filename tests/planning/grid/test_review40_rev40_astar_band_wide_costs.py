"""A*'s f band (F_TIE_BITS, session 43) on grids of widely spread costs (review 40, REV40).

Since session 43 A*'s queue ignores f's lowest 12 bits: f within 2**-40 of f
ties, then goes towards the goal. The band's width is relative to f, and f
counts every cost on the way: a path that first crosses a few cells of cost
1e12 (the documented maximum) has f about 2.5e12, where a band is 2 cost
units wide, so the cells of a cheap room behind them were expanded nearly in
the order of their distance to the goal, not of f. Through the 40 x 40 room
below, A* returned a path 6.6 cost units (cells) dearer than the optimum,
which the code before the band found (to 0.002, the rounding of f at 2.5e12)
and which Dijkstra to exhaustion (the distance field) finds. The band now
applies only below ``F_BAND_COSTS`` times the smallest cell cost, where it is
narrower than 2**-21 of the cheapest move.
"""

from __future__ import annotations

import numpy as np
import pytest

from navkit.planning import AStarPlanner, astar
from navkit.planning.grid import _search_heap

#: The rounding of f near 1e13 is 2**-9 a move (an ulp 0.002); 50 moves of it and more.
ROUNDING = 0.05


def _room_behind(expensive_cells: int, side: int = 40) -> tuple[np.ndarray, tuple[int, int]]:
    """A corridor of cells of cost 1e12 from (0, 0), then a room of cost 1 with a hooked wall.

    The wall runs across the room's middle with a gap at its far end, a hook above
    the gap: a path towards the goal first runs into the wall.
    """
    k = expensive_cells
    grid = np.ones((side, k + side))
    grid[1:, :k] = np.inf
    grid[0, :k] = 1e12
    middle = side // 2
    grid[middle, k : k + side - 3] = np.inf
    grid[middle - 8 : middle, k + side - 4] = np.inf
    return grid, (side - 1, k + side - 1)


@pytest.mark.parametrize("expensive_cells", [3, 10])
def test_a_room_behind_expensive_cells_is_crossed_optimally(expensive_cells: int) -> None:
    grid, goal = _room_behind(expensive_cells)
    planner = AStarPlanner(grid)
    optimum = float(planner.distance_field(goal)[0, 0])  # Dijkstra, every bit of f kept
    path = planner.plan((0, 0), goal)
    # Before: 6.62 units above the optimum for both (f 2.5e12 and 9.5e12; a band
    # there is 2 and 8 units wide).
    assert abs(path.cost - optimum) <= ROUNDING, path.cost - optimum
    assert abs(astar(grid, (0, 0), goal).cost - optimum) <= ROUNDING


def test_the_band_ends_where_it_stays_below_a_two_millionth_of_the_cheapest_move() -> None:
    end = _search_heap.F_BAND_COSTS  # times the smallest cell cost
    # The widest band below the end: 2**-40 of f < F_BAND_COSTS c_min.
    assert 2.0 ** (_search_heap.F_TIE_BITS - 52) * end <= 2.0**-21
    # On a grid of one cost c distinct f below about 741,455 c differ by more than a
    # band (the bound at F_TIE_BITS): the end lies below that.
    assert end < 2.0**19.5


def test_open_rooms_of_one_cost_keep_the_plateau_fix_up_to_the_end() -> None:
    # Cost 3, an empty 300 x 300 room: f up to about 1270 c, far below the end; the
    # search expands the path alone as with session 43's band.
    grid = np.full((300, 300), 3.0)
    path = AStarPlanner(grid).plan((0, 0), (299, 120))
    assert path.expanded == len(path.cells)
