"""numba kernel of the greedy local-grid planner (private).

Cells are ``(row, col)`` of a robot-centred square grid whose cell ``(i, j)`` has
its centre at ``x = j·res - half_width``, ``y = i·res - half_width`` in the robot
frame (x forward, y left); the robot is at the origin, in cell ``(r0, c0)``.
Line of sight is :func:`navkit._shared.lines.line_is_free`, the Bresenham
line shared with the mapping layer.
"""

from __future__ import annotations

import math

import numpy as np

from navkit._shared.jit import njit_cached, njit_inline
from navkit._shared.lines import line_is_free

__all__ = ["greedy_select"]


@njit_inline
def _candidate(
    occupied: np.ndarray,
    i: int,
    j: int,
    r0: int,
    c0: int,
    goal_x: float,
    goal_y: float,
    resolution: float,
    half_width: float,
    h_limit: float,
) -> tuple[bool, float, float]:
    """Whether cell (i, j) is a candidate (free, not the robot's, h < h_limit), and its g, h."""
    if (i == r0 and j == c0) or occupied[i, j]:
        return False, 0.0, 0.0
    x = j * resolution - half_width
    y = i * resolution - half_width
    h = math.hypot(goal_x - x, goal_y - y)
    return h < h_limit, math.hypot(x, y), h


@njit_cached
def greedy_select(
    occupied: np.ndarray,
    r0: int,
    c0: int,
    goal_x: float,
    goal_y: float,
    resolution: float,
    half_width: float,
    require_progress: bool,
    tol: float,
) -> tuple[int, int, float, float, int]:
    """Feasible free cell minimising ``g + h``.

    ``g`` is the distance from the robot to the cell centre and ``h`` from the
    cell centre to the goal. Two passes make ties exact: the first finds the
    least ``f = g + h`` over feasible cells (checking line of sight only for cells
    that would lower it), the second picks, among feasible cells with
    ``f <= f_min + tol``, the one with the smallest ``h`` (then the first in
    row-major order). With ``require_progress`` only cells with ``h`` below the
    robot's own distance to the goal are candidates.

    Returns
    -------
    (row, col, g, h, n_free)
        The chosen cell (``-1, -1`` when none is feasible), its ``g`` and ``h``,
        and the number of free candidate cells.
    """
    rows = occupied.shape[0]
    cols = occupied.shape[1]
    h_limit = math.hypot(goal_x, goal_y) if require_progress else math.inf
    f_min = math.inf
    n_free = 0
    for i in range(rows):
        for j in range(cols):
            ok, g, h = _candidate(
                occupied, i, j, r0, c0, goal_x, goal_y, resolution, half_width, h_limit
            )
            if not ok:
                continue
            n_free += 1
            if g + h < f_min and line_is_free(occupied, r0, c0, i, j):
                f_min = g + h
    best_r = -1
    best_c = -1
    best_g = math.inf
    best_h = math.inf
    if f_min == math.inf:
        return best_r, best_c, best_g, best_h, n_free
    for i in range(rows):
        for j in range(cols):
            ok, g, h = _candidate(
                occupied, i, j, r0, c0, goal_x, goal_y, resolution, half_width, h_limit
            )
            if ok and g + h <= f_min + tol and h < best_h and line_is_free(
                occupied, r0, c0, i, j
            ):
                best_r = i
                best_c = j
                best_g = g
                best_h = h
    return best_r, best_c, best_g, best_h, n_free
