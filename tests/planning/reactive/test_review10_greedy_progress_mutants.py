"""greedy_step(require_progress=True) counts only cells strictly nearer the goal.

Found by mutation testing (session 14): ``h < h_limit`` replaced by ``h <= h_limit``
in the candidate rule survived every other test. A cell exactly as far from the goal
as the robot is never the best step (the cells between them are nearer and cost
less), so only the documented candidate count shows the difference.
"""

from __future__ import annotations

import numpy as np

from navkit.mapping import LocalGrid
from navkit.planning import greedy_step


def test_a_cell_as_far_from_the_goal_as_the_robot_is_not_a_candidate() -> None:
    grid = LocalGrid.from_points(np.empty((0, 2)))
    # The goal lies on the perpendicular bisector of the robot (0, 0) and the cell
    # centre (1, 0): that cell is exactly as far from the goal as the robot.
    goal = (0.5, 0.0123)
    h0 = float(np.hypot(*goal))
    cells = np.array([(r, c) for r in range(grid.size) for c in range(grid.size)])
    centres = grid.cell_to_world(cells)
    dist = np.hypot(goal[0] - centres[:, 0], goal[1] - centres[:, 1])
    tied = cells[np.abs(dist - h0) < 1e-9].tolist()
    centre = grid.size // 2
    assert sorted(map(tuple, tied)) == [(centre, centre), (centre, grid.size - 1)]
    nearer = int(np.sum(dist < h0 - 1e-9))  # the robot's own cell is not among them
    step = greedy_step(grid, goal, require_progress=True)
    assert step.candidates == nearer
    assert step.h < h0
    # Without the progress rule every free cell but the robot's own is a candidate.
    assert greedy_step(grid, goal).candidates == grid.size**2 - 1
