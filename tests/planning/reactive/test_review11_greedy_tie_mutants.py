"""greedy_step's tie rule down to its last step (mutation testing).

Equal ``g + h`` goes to the cell nearer the goal; the kernel's docstring adds
"then the first in row-major order" for cells equally near. On a grid whose
cell centres are exact binary fractions, a world mirror-symmetric about the
robot-goal line gives mirror cells bit-identical ``g`` and ``h``: the lower
``(row, col)`` must win, whichever one a scan of the grid meets last.
"""

from __future__ import annotations

import math

import numpy as np

from navkit._shared.lines import line_is_free
from navkit.mapping import LocalGrid
from navkit.planning import greedy_step


def exact_ties(grid: LocalGrid, gx: float, gy: float) -> list[tuple[int, int]]:
    """The feasible cells of least ``g + h`` (up to the documented tolerance) and least ``h``."""
    occ = grid.occupied.copy()
    n = occ.shape[0]
    c = n // 2
    occ[c, c] = False
    res, hw = grid.resolution, grid.half_width
    cells = []
    for i in range(n):
        for j in range(n):
            if (i, j) == (c, c) or occ[i, j] or not line_is_free(occ, c, c, i, j):
                continue
            x, y = j * res - hw, i * res - hw
            g, h = math.hypot(x, y), math.hypot(gx - x, gy - y)
            cells.append((g + h, h, (i, j)))
    tol = 1e-12 * (math.hypot(gx, gy) + hw)
    f_min = min(f for f, _, _ in cells)
    near = [(h, cell) for f, h, cell in cells if f <= f_min + tol]
    h_min = min(h for h, _ in near)
    return sorted(cell for h, cell in near if h == h_min)


def test_mirror_cells_equally_near_the_goal_go_to_the_lower_row() -> None:
    # 9 x 9 cells of 0.25 m; walls in columns 3 and 5 beside the robot (4, 4),
    # symmetric about its row: the goal straight ahead is reached round them.
    occupied = np.zeros((9, 9), dtype=bool)
    occupied[3:6, 3] = occupied[3:6, 5] = True
    grid = LocalGrid(occupied, resolution=0.25, half_width=1.0)
    for goal in ((1.5, 0.0), (3.0, 0.0), (-2.0, 0.0)):
        ties = exact_ties(grid, *goal)
        assert len(ties) >= 2, ties  # the case really tests the rule
        step = greedy_step(grid, goal)
        assert step.cell == ties[0]
