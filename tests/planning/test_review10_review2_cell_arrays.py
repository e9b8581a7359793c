"""Cells as NumPy integer arrays: what ``world_to_cell`` and ``np.argwhere`` give (review 10).

The planners take a cell as two integers, and at run time also as an integer array
of shape (2,); their ``CellLike`` annotation (a sequence of integers) made mypy
refuse the arrays the library itself returns for a cell.
"""

from __future__ import annotations

import importlib.util
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from navkit.mapping import OccupancyGrid
from navkit.planning import AStarPlanner, FieldDStar, astar, distance_field

ROOT = Path(__file__).resolve().parents[2]

USER_SCRIPT = """
import numpy as np
from numpy.typing import NDArray
from navkit.mapping import OccupancyGrid
from navkit.planning import AStarPlanner, FieldDStar, astar, distance_field
from navkit.planning.grid import Path2D

grid = OccupancyGrid.empty(width=2.0, height=2.0, resolution=0.5)
costs = np.ones((4, 4))
start = grid.world_to_cell([0.1, 0.1])
goal = grid.world_to_cell([1.6, 1.6])
cells = np.argwhere(costs > 0)
a: Path2D = astar(costs, start, goal)
b: Path2D = AStarPlanner(costs).plan(cells[0], cells[-1])
c: Path2D = FieldDStar(costs).plan_cells(start, np.array([3, 3], dtype=np.int32))
field = distance_field(costs, goal)
# Still refused: cells that are not integers.
floats: NDArray[np.float64] = np.zeros(2)
astar(costs, floats, goal)  # type: ignore[arg-type]
astar(costs, (0.5, 0.0), goal)  # type: ignore[arg-type]
distance_field(costs, "0, 1")  # type: ignore[arg-type]
"""


def _cells() -> tuple[np.ndarray, np.ndarray]:
    grid = OccupancyGrid.empty(width=2.0, height=2.0, resolution=0.5)
    return grid.world_to_cell([0.1, 0.1]), grid.world_to_cell([1.6, 1.6])


def test_array_cells_plan_as_tuples_do() -> None:
    # What the annotation promises must hold at run time: an integer array is the cell
    # its two integers name, for every planner entry point.
    costs = np.arange(1.0, 17.0).reshape(4, 4)
    start, goal = _cells()
    assert start.dtype.kind == "i" and start.shape == (2,)
    as_tuple = (int(start[0]), int(start[1])), (int(goal[0]), int(goal[1]))
    expected = astar(costs, *as_tuple)
    for cell_start, cell_goal in ((start, goal), (start.astype(np.int32), goal.astype(np.uint8))):
        got = astar(costs, cell_start, cell_goal)
        assert got.cost == expected.cost
        np.testing.assert_array_equal(got.points, expected.points)
        np.testing.assert_array_equal(
            AStarPlanner(costs).plan(cell_start, cell_goal).points, expected.points
        )
        np.testing.assert_array_equal(
            distance_field(costs, cell_goal), distance_field(costs, as_tuple[1])
        )
        assert (
            FieldDStar(costs).plan_cells(cell_start, cell_goal).cost
            == FieldDStar(costs).plan_cells(*as_tuple).cost
        )


@pytest.mark.slow
@pytest.mark.skipif(importlib.util.find_spec("mypy") is None, reason="mypy is not installed")
def test_array_cells_type_check_under_mypy_strict(tmp_path: Path) -> None:
    script = tmp_path / "cells_user.py"
    script.write_text(USER_SCRIPT, encoding="utf-8")
    proc = subprocess.run(
        [sys.executable, "-m", "mypy", "--strict", "--cache-dir", str(tmp_path / "mypy_cache"),
         str(script)],
        cwd=ROOT,
        capture_output=True,
        text=True,
        check=False,
    )  # fmt: skip
    assert proc.returncode == 0, proc.stdout + proc.stderr
