"""Greedy local planner on the robot-centred laser grid (the TurtleBot3 paper)."""

from __future__ import annotations

import math
import numbers
from collections.abc import Mapping
from dataclasses import dataclass
from types import MappingProxyType
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import ArrayLike

from navkit._shared.counts import counted
from navkit._shared.deprecation import renamed_keyword
from navkit._shared.frozen import frozen_setattr, reduce_record
from navkit._shared.types import FloatArray
from navkit._shared.validation import (
    as_bool,
    as_float_array,
    bounded_int,
    finite_float,
    has_array_protocol,
    shown,
    unpack,
)
from navkit.errors import NoPathError
from navkit.mapping import LocalGrid
from navkit.planning.reactive._greedy_kernels import greedy_select
from navkit.planning.reactive._limits import point
from navkit.planning.reactive._potential_field import _restore

__all__ = ["GreedyStep", "greedy_step"]

_INT64_MAX = 2**63 - 1
#: Fraction of a half cell by which a goal may lie beyond the robot's cell and still
#: be in it: world coordinates made robot-frame carry rounding of ~1e-16 of their size
#: (~1e-9 m at a UTM northing of 1e7 m, 4e-8 of a 5 cm cell's half), and the last step
#: goes to the goal itself, so a larger slack costs no accuracy.
_BORDER_SLACK = 1e-6


@frozen_setattr
@dataclass(frozen=True, slots=True, eq=False)
class GreedyStep:
    """The cell chosen by :func:`greedy_step`.

    Parameters
    ----------
    cell : tuple of int
        ``(row, col)`` of the chosen cell in ``local_grid.occupied``, integers
        >= 0 (not booleans); the robot's own cell for the last step, when the
        goal lies in it.
    waypoint_xy : array_like, shape (2,)
        Its centre ``(x, y)`` in metres in the robot frame: where to move next
        (the goal itself for the last step, with ``h = 0``).
        Finite; stored as a read-only copy (the caller's array is neither kept
        nor frozen). Read it as :attr:`waypoint_robot_xy`, whose name says the
        frame (every other ``*_xy`` point of navkit is in the world frame).
    g : float
        Distance from the robot to the waypoint (m), finite, >= 0.
    h : float
        Distance from the waypoint to the goal (m), finite, >= 0.
    candidates : int
        Number of free cells that were candidates, >= 0.

    Raises
    ------
    ValueError
        Negative or non-finite values, a waypoint of the wrong shape.
    TypeError
        Values of the wrong type (strings, complex numbers, booleans, a cell
        that is not a pair of integers).

    Examples
    --------
    >>> step = GreedyStep((10, 12), (0.2, 0.0), g=0.2, h=1.8, candidates=440)
    >>> step.cost, step.waypoint_robot_xy
    (2.0, array([0.2, 0. ]))
    """

    cell: tuple[int, int]
    waypoint_xy: FloatArray
    g: float
    h: float
    candidates: int

    __reduce__ = reduce_record
    __setstate__ = _restore
    # A field renamed since a release (issue 11), for pickles made before (see
    # navkit._shared.frozen.restore_read_only). Not annotated: it would be a field.
    _renamed_fields = MappingProxyType({"waypoint": "waypoint_xy"})

    if TYPE_CHECKING:
        # The generated ``__init__`` takes the arrays as array_like (``__post_init__``
        # converts them); this signature tells type checkers so, at no runtime cost.
        def __init__(
            self,
            cell: tuple[int, int],
            waypoint_xy: ArrayLike,
            g: float,
            h: float,
            candidates: int,
        ) -> None: ...

    def __post_init__(self) -> None:
        cell: Any = self.cell
        if type(cell) is memoryview or (
            not issubclass(type(cell), (str, bytes, list, tuple, np.ndarray))
            and has_array_protocol(cell)
        ):
            # A buffer (Python cannot iterate over a big-endian one) or a foreign
            # array type: its items as NumPy reads them.
            try:
                cell = unpack(cell, "cell")
            except TypeError:
                raise TypeError(
                    f"cell must be a (row, col) pair of integers, got {self.cell!r}"
                ) from None
        if (
            isinstance(cell, (str, bytes, Mapping, set, frozenset))
            or not hasattr(cell, "__len__")
            or len(cell) != 2
        ):
            raise TypeError(f"cell must be a (row, col) pair of integers, got {cell!r}")
        row, col = (_count(v, "cell") for v in cell)
        waypoint = np.array(as_float_array(self.waypoint_xy, "waypoint_xy", shape=(2,)))
        waypoint.setflags(write=False)
        object.__setattr__(self, "cell", (row, col))
        object.__setattr__(self, "waypoint_xy", waypoint)
        for name in ("g", "h"):
            value = finite_float(getattr(self, name), name)
            if value < 0.0:
                raise ValueError(f"{name} must be >= 0, got {value}")
            object.__setattr__(self, name, value)
        object.__setattr__(self, "candidates", _count(self.candidates, "candidates"))

    @classmethod
    def _owned(
        cls, cell: tuple[int, int], waypoint_xy: FloatArray, g: float, h: float, candidates: int
    ) -> GreedyStep:
        """A step from :func:`greedy_step`'s own valid values; skips the checks."""
        step = object.__new__(cls)
        waypoint_xy.setflags(write=False)
        object.__setattr__(step, "cell", cell)
        object.__setattr__(step, "waypoint_xy", waypoint_xy)
        object.__setattr__(step, "g", g)
        object.__setattr__(step, "h", h)
        object.__setattr__(step, "candidates", candidates)
        return step

    @property
    def cost(self) -> float:
        """``g + h``, the quantity the planner minimises (m)."""
        return self.g + self.h

    @property
    def waypoint_robot_xy(self) -> FloatArray:
        """The waypoint ``(x, y)`` in metres in the robot frame (x forward, y left).

        The field ``waypoint_xy`` itself, read-only, under a name that says its
        frame. The field keeps its name, so that the constructor,
        :func:`dataclasses.replace` and pickles are unchanged.

        Examples
        --------
        >>> step = greedy_step(LocalGrid.from_points([]), (2.0, 0.0))
        >>> step.waypoint_robot_xy  # 1 m ahead: the grid's goal-ward edge
        array([1., 0.])
        """
        return self.waypoint_xy


def greedy_step(
    local_grid: LocalGrid,
    goal_robot_xy: ArrayLike | None = None,
    *,
    require_progress: bool = False,
    goal_xy: ArrayLike | None = None,
) -> GreedyStep:
    """One step of the TurtleBot3 greedy planner on a robot-centred grid.

    Every free cell of the grid except the robot's own is a candidate; a
    candidate is feasible when the Bresenham line from the robot's cell to it
    crosses no occupied cell. The feasible cell minimising ``g + h`` (robot to
    cell plus cell to goal, Euclidean, between cell centres) is chosen; ties
    (equal up to rounding: within ``1e-12·(‖goal‖ + half_width)``) go to the
    cell nearer the goal. The robot moves toward it and calls again with a new
    scan until it reaches the goal.

    When the goal lies in the robot's own cell (within half a cell of the robot
    along x and along y, the border included, and 1e-6 of a half cell beyond it
    for the rounding of robot-frame coordinates, which at UTM-sized world
    coordinates is about 1e-9 m) the step is the goal itself, the
    last one: ``cell`` is the robot's cell, ``waypoint_robot_xy`` the goal,
    ``g`` its distance and ``h`` 0. Its cost ``|goal|`` is no more than any
    cell's ``g + h``, and the robot's cell is never blocked, so this is the
    rule's own answer once the goal is nearer than the cells' centres can say;
    without it the robot, never offered its own cell, would stop a neighbour
    short. A loop "step until arrival" can stop when ``h == 0`` (which a step
    to a cell whose centre is the goal also gives: moving there arrives). On
    the robot cell's +x and +y borders this counts as the robot's cell a goal
    that :class:`~navkit.mapping.LocalGrid` (rounding half up) puts in the
    neighbouring cell, so that a goal on a border ends the walk from either
    side instead of sending the robot back and forth across it.

    Works on any :class:`~navkit.mapping.LocalGrid` (the paper's 21 × 21 grid of
    0.1 m cells is ``scan.to_local_grid()``). The robot's own cell never blocks
    its lines of sight, even if a return fell into it. Lines are the mapping
    layer's 8-connected Bresenham lines, which can pass diagonally between two
    occupied cells that touch only at a corner. Where a line passes exactly
    halfway between two cells (the line to the cell 1 row and 2 columns away
    crosses the middle column on the border of two rows) Bresenham's rounding
    picks one of them by the direction of the trace, which always runs toward
    higher rows; so the lines, and with them which cells are in sight, are
    symmetric under mirroring the grid front to back (x → -x) but not left to
    right (y → -y), under transposing it or under turns: mirrored or rotated
    worlds can give steps of different cost.

    Parameters
    ----------
    local_grid : navkit.mapping.LocalGrid
        Occupancy around the robot; rows along y, columns along x (robot frame).
    goal_robot_xy : array_like, shape (2,)
        Goal ``(x, y)`` in metres in the robot frame (x forward, y left),
        ``|x|, |y| <= 1e9``; it may lie outside the grid. Required (its default
        None only lets the deprecated ``goal_xy`` stand in for it).
    require_progress : bool, default False
        Only consider cells strictly nearer the goal than the robot. The paper's
        rule (False) may choose a cell behind the robot in front of a wide wall;
        with True the planner never retreats and raises instead.

    Other Parameters
    ----------------
    goal_xy : array_like, shape (2,), optional
        Deprecated name of `goal_robot_xy` (every other ``goal_xy`` of navkit
        is a world point).

    Returns
    -------
    GreedyStep
        The chosen cell, its robot-frame centre ``waypoint_robot_xy`` and its
        ``g`` and ``h``.

    Raises
    ------
    TypeError
        ``local_grid`` is not a LocalGrid, ``require_progress`` not a bool, the
        goal missing, or given under both names.
    ValueError
        ``goal_robot_xy`` is not two finite numbers within ±1e9 m.
    NoPathError
        No candidate is feasible (e.g. the robot is walled in, or with
        ``require_progress`` every cell nearer the goal is hidden behind walls),
        and the goal is not in the robot's own cell.

    Examples
    --------
    >>> grid = LocalGrid.from_points([[0.1, 0.0]])        # a return right ahead
    >>> step = greedy_step(grid, (2.0, 0.0))
    >>> step.cell != (10, 11), bool(step.waypoint_robot_xy[1] != 0.0)  # not straight ahead
    (True, True)
    >>> greedy_step(LocalGrid.from_points([]), (2.0, 0.0)).waypoint_robot_xy  # goal-ward edge
    array([1., 0.])
    >>> last = greedy_step(LocalGrid.from_points([]), (0.03, -0.04))  # in the robot's cell
    >>> last.cell, last.waypoint_robot_xy, round(last.g, 12), last.h
    ((10, 10), array([ 0.03, -0.04]), 0.05, 0.0)
    """
    grid = _check_grid(local_grid)
    # The goal is in the robot frame: the name says so (goal_xy is a world point
    # everywhere else); the old name warns, and errors name what the caller wrote.
    named = "goal_robot_xy" if goal_xy is None else "goal_xy"
    goal = renamed_keyword("goal_xy", goal_xy, "goal_robot_xy", goal_robot_xy, None)
    if goal is None:
        raise TypeError("greedy_step() missing the argument goal_robot_xy")
    target = point(goal, named)
    progress = as_bool(require_progress, "require_progress")
    gx, gy = float(target[0]), float(target[1])
    occupied = grid.occupied
    centre = grid.size // 2
    if occupied[centre, centre]:
        occupied = occupied.copy()
        occupied[centre, centre] = False
        # Read-only as LocalGrid.occupied: numba compiles a kernel once per array type
        # (a writable copy compiled greedy_select again, after navkit warmup too).
        occupied.flags.writeable = False
    # g + h is exact to a few ulps of ‖goal‖ + half_width: this tolerance only makes
    # exact ties (cells on the straight line, mirror images) deterministic. It
    # scales with the goal distance but must stay far below the cell size: at
    # 1e-9·‖goal‖ a goal 1e9 m away made cells costing up to 1 m more "tie".
    tol = 1e-12 * (float(np.hypot(gx, gy)) + grid.half_width)
    row, col, g, h, n_free = greedy_select(
        occupied, centre, centre, gx, gy, grid.resolution, grid.half_width,
        progress, tol,
    )
    # The goal in the robot's own cell, border included (up to rounding): the robot
    # stepping between two cells each on the other side of a goal on their common
    # border would never arrive.
    reach = 0.5 * grid.resolution * (1.0 + _BORDER_SLACK)
    if abs(gx) <= reach and abs(gy) <= reach:
        # No candidate is the robot's cell, so a loop "step until arrival" stopped a
        # neighbour short. The goal itself costs |goal|, no more than any cell's g + h
        # (triangle inequality), and the robot's cell never blocks its sight.
        arrived = np.array([gx, gy], dtype=np.float64)
        return GreedyStep._owned((centre, centre), arrived, math.hypot(gx, gy), 0.0, n_free)
    if row < 0:
        reason = "nearer the goal " if progress else ""
        raise NoPathError(
            f"no free cell {reason}is in line of sight of the robot "
            f"({counted(n_free, 'candidate')})",
            expanded=n_free,
        )
    waypoint_xy = np.array(grid.cell_to_world(np.array([[row, col]]))[0], dtype=np.float64)
    return GreedyStep._owned((int(row), int(col)), waypoint_xy, float(g), float(h), int(n_free))


def _count(value: Any, name: str) -> int:
    """An integer in [0, 2**63 - 1] (integral floats accepted, booleans refused)."""
    if isinstance(value, numbers.Real) and not isinstance(value, numbers.Integral):
        # Unlike other integer options, a whole float passes: cells come from
        # arithmetic on coordinates (2.0), as in every (row, col) argument.
        number = finite_float(value, name)
        if not number.is_integer():
            raise TypeError(f"{name} must hold integers, got {shown(value)}")
        value = int(number)
    return bounded_int(value, name, 0, _INT64_MAX)


def _check_grid(value: Any) -> LocalGrid:
    if not isinstance(value, LocalGrid):
        raise TypeError(
            f"local_grid must be a navkit.mapping.LocalGrid, got {type(value).__name__}"
        )
    return value
