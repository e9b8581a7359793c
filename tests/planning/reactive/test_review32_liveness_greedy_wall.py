"""Review 32 (LIVENESS): the greedy step's stall in front of a wall, and how a loop sees it.

A robot stepping cell by cell toward a goal 3 m ahead, behind a wall 0.6 m wide
(points at x = 1 m, |y| <= 0.3 m), reaches the cell in front of the wall and
then, under the paper's rule (``require_progress=False``), steps sideways and
back for ever: each sideways cell costs the same ``g + h`` (0.1 m on, ``h``
unchanged), less than any cell beside the wall. No step says so; ``h`` simply
stops decreasing. With ``require_progress=True`` the same call raises
:class:`~navkit.errors.NoPathError` there instead. The rule is the paper's
(a greedy local planner's local minimum): these tests pin the two signals a
loop has, so the guide can point to them.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from navkit.errors import NoPathError
from navkit.mapping import LocalGrid
from navkit.planning import greedy_step

RES = 0.1
HALF = 1.0
GOAL = (3.0, 0.0)


def _grid_at(x: float, y: float) -> LocalGrid:
    """The 21 x 21 grid of the wall seen from ``(x, y)`` (robot heading +x)."""
    n = 21
    occupied = np.zeros((n, n), dtype=bool)
    for wy in np.arange(-0.3, 0.3 + 1e-9, 0.02):
        i = math.floor((wy - y + HALF) / RES + 0.5)
        j = math.floor((1.0 - x + HALF) / RES + 0.5)
        if 0 <= i < n and 0 <= j < n:
            occupied[i, j] = True
    return LocalGrid(occupied, resolution=RES, half_width=HALF)


def _walk(steps: int) -> tuple[list[tuple[float, float]], list[float]]:
    x, y = 0.0, 0.05
    visited, hs = [], []
    for _ in range(steps):
        step = greedy_step(_grid_at(x, y), (GOAL[0] - x, GOAL[1] - y))
        hs.append(step.h)
        wx, wy = step.waypoint_robot_xy
        x, y = round(x + float(wx), 9), round(y + float(wy), 9)
        visited.append((x, y))
    return visited, hs


def test_the_papers_rule_steps_sideways_for_ever_in_front_of_the_wall() -> None:
    visited, hs = _walk(40)
    assert visited[8] == (0.9, 0.05)  # in front of the wall after 9 steps
    assert set(visited[9:]) == {(0.9, -0.05), (0.9, 0.05)}  # then side to side
    assert hs[-1] == hs[9]  # the signal a loop has: h no longer decreases
    assert min(hs) > 2.0  # the goal is 2.1 m away, never reached


def test_require_progress_raises_where_the_papers_rule_starts_to_cycle() -> None:
    with pytest.raises(NoPathError, match="no free cell nearer the goal"):
        greedy_step(_grid_at(0.9, 0.05), (GOAL[0] - 0.9, GOAL[1] - 0.05), require_progress=True)
    step = greedy_step(_grid_at(0.8, 0.05), (GOAL[0] - 0.8, GOAL[1] - 0.05), require_progress=True)
    assert step.cell == (10, 11)  # one cell before: it still advances, along +x
