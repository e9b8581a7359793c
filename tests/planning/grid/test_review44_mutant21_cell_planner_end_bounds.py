"""A cell planner's path ends may lie on their cells' edges, not beyond (review 44, MUTANT21).

``MapPlanner.plan`` takes a caller's path whose ends are within half a cell
(each of row and column) of the start and goal cells: the closed squares,
edges included, as its docstring and :func:`_check_ends` say. The tests used
ends well inside or well outside, so a mutant refusing an end exactly on the
edge (``<`` for ``<=``) survived. Here both edges, and just beyond them.
"""

from __future__ import annotations

from typing import Any

import numpy as np
import pytest

from navkit.mapping import OccupancyGrid
from navkit.planning import MapPlanner, Path2D

_START, _GOAL = (1, 2), (1, 7)


def _fixed(cells: list[list[float]]) -> Any:
    def planner(costs: Any, start: tuple[int, int], goal: tuple[int, int]) -> Path2D:
        assert (start, goal) == (_START, _GOAL)
        return Path2D(np.array(cells, dtype=float), "grid", cost=1.0, length=1.0, expanded=0)

    return planner


def _plan(cells: list[list[float]]) -> Path2D:
    grid = OccupancyGrid.from_occupancy(np.zeros((4, 10), dtype=bool), resolution=1.0)
    return MapPlanner(grid, planner=_fixed(cells)).plan((2.5, 1.5), (7.5, 1.5))


@pytest.mark.parametrize(
    "cells",
    [[[1.5, 2.0], [1.0, 7.0]], [[0.5, 1.5], [1.0, 7.0]], [[1.0, 2.0], [1.5, 7.5]],
     [[1.0, 2.0], [0.5, 6.5]]],
    ids=["start-row-edge", "start-corner", "goal-corner", "goal-low-corner"],
)  # fmt: skip
def test_ends_on_their_cells_edges_are_taken(cells: list[list[float]]) -> None:
    path = _plan(cells)
    assert path.points[0].tolist() == [2.5, 1.5] and path.points[-1].tolist() == [7.5, 1.5]


@pytest.mark.parametrize(
    "cells",
    [[[1.5000001, 2.0], [1.0, 7.0]], [[1.0, 1.4999999], [1.0, 7.0]],
     [[1.0, 2.0], [1.0, 7.5000001]], [[1.0, 2.0], [0.4999999, 7.0]]],
    ids=["start-row", "start-col", "goal-col", "goal-row"],
)  # fmt: skip
def test_ends_just_beyond_their_cells_are_refused(cells: list[list[float]]) -> None:
    with pytest.raises(ValueError, match=r"must return a path from start_cell \(1, 2\)"):
        _plan(cells)
