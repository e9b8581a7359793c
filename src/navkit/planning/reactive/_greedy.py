"""Greedy local planner on the robot-centred laser grid (the TurtleBot3 paper)."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from navkit._shared.types import FloatArray
from navkit._shared.validation import as_bool, as_float_array
from navkit.errors import NoPathError
from navkit.mapping import LocalGrid
from navkit.planning.reactive._greedy_kernels import greedy_select

__all__ = ["GreedyStep", "greedy_step"]


@dataclass(frozen=True, slots=True, eq=False)
class GreedyStep:
    """The cell chosen by :func:`greedy_step`.

    Parameters
    ----------
    cell : tuple of int
        ``(row, col)`` of the chosen cell in ``local_grid.occupied``.
    waypoint_xy : array_like, shape (2,)
        Its centre ``(x, y)`` in metres in the robot frame: where to move next.
        Stored as a read-only copy.
    g : float
        Distance from the robot to the waypoint (m).
    h : float
        Distance from the waypoint to the goal (m).
    candidates : int
        Number of free cells that were candidates.

    Examples
    --------
    >>> step = GreedyStep((10, 12), (0.2, 0.0), g=0.2, h=1.8, candidates=440)
    >>> step.cost
    2.0
    """

    cell: tuple[int, int]
    waypoint_xy: FloatArray
    g: float
    h: float
    candidates: int

    def __post_init__(self) -> None:
        # A result type: conversions only, kept cheap (greedy_step runs every scan).
        row, col = self.cell
        waypoint = np.array(self.waypoint_xy, dtype=np.float64)
        if waypoint.shape != (2,):
            raise ValueError(f"waypoint_xy must have shape (2,), got {waypoint.shape}")
        waypoint.setflags(write=False)
        object.__setattr__(self, "cell", (int(row), int(col)))
        object.__setattr__(self, "waypoint_xy", waypoint)
        object.__setattr__(self, "g", float(self.g))
        object.__setattr__(self, "h", float(self.h))
        object.__setattr__(self, "candidates", int(self.candidates))

    @property
    def cost(self) -> float:
        """``g + h``, the quantity the planner minimises (m)."""
        return self.g + self.h


def greedy_step(
    local_grid: LocalGrid, goal_xy: ArrayLike, *, require_progress: bool = False
) -> GreedyStep:
    """One step of the TurtleBot3 greedy planner on a robot-centred grid.

    Every free cell of the grid except the robot's own is a candidate; a
    candidate is feasible when the Bresenham line from the robot's cell to it
    crosses no occupied cell. The feasible cell minimising ``g + h`` (robot to
    cell plus cell to goal, Euclidean, between cell centres) is chosen; ties
    (within 1e-9 relative) go to the cell nearer the goal. The robot moves
    toward it and calls again with a new scan until it reaches the goal.

    Works on any :class:`~navkit.mapping.LocalGrid` (the paper's 21 × 21 grid of
    0.1 m cells is ``scan.to_local_grid()``). The robot's own cell never blocks
    its lines of sight, even if a return fell into it. Lines are the mapping
    layer's 8-connected Bresenham lines, which can pass diagonally between two
    occupied cells that touch only at a corner.

    Parameters
    ----------
    local_grid : navkit.mapping.LocalGrid
        Occupancy around the robot; rows along y, columns along x (robot frame).
    goal_xy : array_like, shape (2,)
        Goal ``(x, y)`` in metres in the robot frame (x forward, y left); it may
        lie outside the grid.
    require_progress : bool, default False
        Only consider cells strictly nearer the goal than the robot. The paper's
        rule (False) may choose a cell behind the robot in front of a wide wall;
        with True the planner never retreats and raises instead.

    Returns
    -------
    GreedyStep
        The chosen cell, its robot-frame centre ``waypoint_xy`` and its ``g`` and ``h``.

    Raises
    ------
    TypeError
        ``local_grid`` is not a LocalGrid, or ``require_progress`` not a bool.
    ValueError
        ``goal_xy`` is not two finite numbers.
    NoPathError
        No candidate is feasible (e.g. the robot is walled in, or with
        ``require_progress`` every cell nearer the goal is hidden behind walls).

    Examples
    --------
    >>> grid = LocalGrid.from_points([[0.1, 0.0]])        # a return right ahead
    >>> step = greedy_step(grid, (2.0, 0.0))
    >>> step.cell != (10, 11), bool(step.waypoint_xy[1] != 0.0)  # not straight ahead
    (True, True)
    >>> greedy_step(LocalGrid.from_points([]), (2.0, 0.0)).waypoint_xy  # free: goal-ward edge
    array([1., 0.])
    """
    grid = _check_grid(local_grid)
    target = as_float_array(goal_xy, "goal_xy", shape=(2,))
    progress = as_bool(require_progress, "require_progress")
    gx, gy = float(target[0]), float(target[1])
    occupied = grid.occupied
    centre = grid.size // 2
    if occupied[centre, centre]:
        occupied = occupied.copy()
        occupied[centre, centre] = False
    tol = 1e-9 * (1.0 + float(np.hypot(gx, gy)))
    row, col, g, h, n_free = greedy_select(
        occupied, centre, centre, gx, gy, grid.resolution, grid.half_width,
        progress, tol,
    )
    if row < 0:
        reason = "nearer the goal " if progress else ""
        raise NoPathError(
            f"no free cell {reason}is in line of sight of the robot ({n_free} candidates)",
            expanded=n_free,
        )
    waypoint_xy = grid.cell_to_world(np.array([[row, col]]))[0]
    return GreedyStep((int(row), int(col)), waypoint_xy, float(g), float(h), int(n_free))


def _check_grid(value: Any) -> LocalGrid:
    if not isinstance(value, LocalGrid):
        raise TypeError(
            f"local_grid must be a navkit.mapping.LocalGrid, got {type(value).__name__}"
        )
    return value
