"""World-coordinate path planning on an :class:`~navkit.mapping.OccupancyGrid`."""

from __future__ import annotations

import copy
import math
import re
from typing import TYPE_CHECKING, Any, Literal, NamedTuple, Protocol, cast

import numpy as np
from numpy.typing import ArrayLike

from navkit._shared.counts import counted
from navkit._shared.dunders import slot_state
from navkit._shared.frozen import restore_slots
from navkit._shared.metres import metres_text
from navkit._shared.moved import gone
from navkit._shared.text import as_text
from navkit._shared.types import FloatArray
from navkit._shared.validation import as_bool, as_float_array
from navkit.errors import NoPathError
from navkit.geometry import Pose2D, as_pose
from navkit.mapping import OccupancyGrid
from navkit.planning.grid._astar import AStarPlanner
from navkit.planning.grid._escape import nearest_escape
from navkit.planning.grid._field_dstar import FieldDStar
from navkit.planning.grid._limits import (
    COORDINATE_LIMIT,
    RADIUS_LIMIT,
    bounded_float,
    checked_costs,
)
from navkit.planning.grid._path import Path2D, grid_to_world, polyline_length

__all__ = ["CellPlanner", "MapPlanner", "plan_path"]


class CellPlanner(Protocol):
    """A planner on a cost grid, as :class:`MapPlanner` and :func:`plan_path` call it.

    ``planner(costs, start_cell, goal_cell) -> Path2D``, arguments positional:

    * ``costs``: the traversal costs, an already validated read-only C-contiguous
      float64 array (finite values in ``[1, 1e12]``, ``np.inf`` impassable). One
      :class:`MapPlanner` passes the same array object on every query, so a
      planner may prepare its own data once per array;
    * ``start_cell``, ``goal_cell``: ``(row, col)`` tuples of ints, inside the
      grid and on finite-cost cells;
    * returns a ``"grid"`` :class:`Path2D` from the centre of ``start_cell`` to
      the centre of ``goal_cell`` (continuous ``(row, col)``, integers at cell
      centres) with its cost in cost units × cells, or raises
      :class:`navkit.NoPathError`.

    :func:`navkit.planning.astar` follows it; give options with
    :func:`functools.partial`, e.g. ``partial(astar, corner_cutting=True)``.

    Examples
    --------
    >>> from functools import partial
    >>> from navkit.planning import astar
    >>> planner: CellPlanner = partial(astar, heuristic_weight=1.5)
    """

    def __call__(
        self, costs: FloatArray, start_cell: tuple[int, int], goal_cell: tuple[int, int], /
    ) -> Path2D:
        """Path from the centre of ``start_cell`` to the centre of ``goal_cell``."""
        ...


_BUILT_IN = ("astar", "field_dstar")

class MapPlanner:
    """Plans paths between world points on one occupancy grid, many times.

    The constructor turns the map into traversal costs once
    (:func:`navkit.mapping.traversal_costs`): occupied cells and every cell whose
    centre lies within ``robot_radius`` of an occupied cell are impassable (the
    robot's centre may not go there), free cells cost 1, and cells near
    obstacles cost more (Nav2's exponential inflation decay) out to
    ``inflation_radius`` rounded up to whole cells, as Nav2 does: with the
    default ``inflation_radius = robot_radius`` such a band appears only when
    ``robot_radius`` is not a whole number of cells. Unknown space is
    impassable by default and, like an obstacle, keeps the robot
    ``robot_radius`` away (``inflate_unknown``):
    on a robot-built map whose walls are partly unknown cells the paths keep
    the same clearance from them. For the built-in planners it also prepares
    the planner on those costs (validation and conversion done once), so each
    :meth:`plan` only converts its two points and searches. A class with
    ``__slots__``: it owns the costs and the prepared planner.

    The costs are a snapshot: later changes to ``grid`` (e.g. ray casting) do
    not reach them; build a new planner for a changed map. The planner keeps a
    copy of the map as it was (4 bytes a cell), so that the errors of
    :meth:`plan` explain the costs it plans on.

    Parameters
    ----------
    grid : OccupancyGrid
        The map (cells ``(row, col)``, row 0 at the lowest y).
    robot_radius : float, default 0.0
        The robot's inscribed radius in m, in ``[0, 1e6]``: the obstacles'
        inflation.
    inflation_radius : float, optional
        Distance in m up to which costs decay (rounded up to whole cells), in
        ``[robot_radius, 1e6]``; default ``robot_radius``.
    unknown_cost : float, default inf
        Cost of unknown cells: ``inf`` (impassable) or a value in ``[1, 1e9]``
        (as :func:`navkit.mapping.traversal_costs`). In a simulator
        :class:`~navkit.sim.World` on the same map choose its
        ``unknown_blocks`` with it: ``inf`` with ``unknown_blocks=True`` (the
        defaults of both), a finite cost with ``unknown_blocks=False``. A
        finite cost in a World whose unknown cells block plans routes through
        cells the robot then hits; ``inf`` in one whose unknown cells are
        open only plans around space the robot could cross.
    inflate_unknown : bool or None, default None
        Whether unknown cells are inflated like obstacles: cells whose centre
        lies within ``robot_radius`` of an unknown cell's are impassable too
        (and the inflation cost decays from unknown cells as from occupied
        ones), so the robot's body, not only its centre, keeps clear of space
        it knows nothing about. ``True`` needs ``unknown_cost=inf``.
        ``None`` (the default) means ``True`` when ``unknown_cost`` is ``inf``
        and ``False`` otherwise (unknown space crossable at its cost). As
        :func:`navkit.mapping.traversal_costs` (Nav2's
        ``inflate_around_unknown``).
    planner : {"astar", "field_dstar"} or CellPlanner, default "astar"
        ``"astar"``: :class:`AStarPlanner` (8-connected, no corner cutting),
        a path through cell centres. ``"field_dstar"``: any-angle paths,
        :meth:`FieldDStar.plan_cells` (whose path costs, in cost units ×
        cells, must stay below ``2**52``: only a huge ``unknown_cost`` on a
        long route through unknown space comes near). Its paths may pass
        through a corner where two impassable cells touch diagonally, where
        ``"astar"`` finds no path; they are usually cheaper than ``"astar"``'s,
        not always (see :meth:`FieldDStar.plan_cells`). Or any callable following
        :class:`CellPlanner`, called on every query with the costs; use
        :func:`functools.partial` for options, e.g.
        ``partial(astar, corner_cutting=True)`` (a callable prepares nothing:
        ``astar`` validates the costs on each call).

    Raises
    ------
    TypeError
        ``grid`` is not an OccupancyGrid; ``planner`` is neither a name nor
        callable; a radius or ``unknown_cost`` that is not a real number (or a
        bool); ``inflate_unknown`` neither a bool nor None.
    ValueError
        Unknown planner name; radii or ``unknown_cost`` out of range;
        ``inflate_unknown=True`` with a finite ``unknown_cost``.

    Notes
    -----
    With ``"astar"`` or a thread-safe callable, :meth:`plan` may be called from
    several threads at once; ``"field_dstar"`` keeps search state and may not:
    give each thread its own :func:`copy.copy` of such a planner (the copies
    share the costs, not the search state).

    Memory: a planner keeps 12 bytes a cell, its snapshot of the map (4) and
    its costs (8), with ``"astar"`` (which borrows the costs) or a callable;
    with ``"field_dstar"`` about 68: the :class:`FieldDStar` adds 56 bytes a
    node (its padded copy of the costs, its search values and its queue; 68 MB
    for 1000 × 1000 cells against 12 MB allocated, of which the queue's 24
    bytes a node are pages that take memory only where a search writes: 45 MB
    resident after a plan across 1000 × 1000 free cells, measured with
    ``VmRSS``). :attr:`costs` stays an array of its
    own beside the padded copy: a read-only C-contiguous array that no search
    touches. Each :func:`copy.copy` of a ``"field_dstar"`` planner adds the 56
    bytes a node of its own search state.

    Examples
    --------
    >>> import numpy as np
    >>> from navkit.mapping import OccupancyGrid
    >>> occupied = np.zeros((20, 30), dtype=bool)
    >>> occupied[:15, 14:16] = True
    >>> grid = OccupancyGrid.from_occupancy(occupied, resolution=0.1)
    >>> planner = MapPlanner(grid, robot_radius=0.2)
    >>> path = planner.plan((0.55, 0.55), (2.55, 0.55))
    >>> path.frame, path.points[0].tolist(), path.points[-1].tolist()
    ('world', [0.55, 0.55], [2.55, 0.55])
    >>> bool(path.points[:, 1].max() > 1.7)
    True
    >>> back = planner.plan((2.55, 0.55, 3.14), (0.55, 0.55))  # a pose works too
    >>> round(back.cost, 9) == round(path.cost, 9)
    True
    """

    __slots__ = (
        "__weakref__",  # weakref.ref(obj) for callbacks and caches (review 36)
        "_costs",
        "_grid",
        "_inflate_unknown",
        "_inflation_radius",
        "_planner",
        "_prepared",
        "_robot_radius",
        "_snapshot",
        "_unknown_cost",
    )
    __getstate__ = slot_state  # pickle protocols 0 and 1 too

    def __init__(
        self,
        grid: OccupancyGrid,
        *,
        robot_radius: float = 0.0,
        inflation_radius: float | None = None,
        unknown_cost: float = math.inf,
        inflate_unknown: bool | None = None,
        planner: Literal["astar", "field_dstar"] | CellPlanner = "astar",
    ) -> None:
        if not isinstance(grid, OccupancyGrid):
            raise TypeError(f"grid must be an OccupancyGrid, got {type(grid).__name__}")
        if isinstance(planner, str):
            # Checked and kept as the plain str (an np.str_ printed as np.str_('astar'), a
            # case-blind subclass's own == let "ASTAR" through).
            planner = cast(Literal["astar", "field_dstar"], as_text(planner, "planner"))
            if planner not in _BUILT_IN:
                raise ValueError(
                    f"planner must be one of {list(_BUILT_IN)} or a CellPlanner callable, "
                    f"got {planner!r}"
                )
        elif not callable(planner):
            raise TypeError(
                f"planner must be a name or a CellPlanner callable, got {type(planner).__name__}"
            )
        radius = bounded_float(robot_radius, "robot_radius", 0.0, RADIUS_LIMIT, "m")
        inflate = None if inflate_unknown is None else as_bool(inflate_unknown, "inflate_unknown")
        # The map as the costs see it: ray casting may change ``grid`` later, and
        # the errors of plan() must explain the costs, not the map of the moment.
        snapshot = grid.copy()
        costs = snapshot.traversal_costs(
            robot_radius=radius,
            inflation_radius=inflation_radius,
            unknown_cost=unknown_cost,
            inflate_unknown=inflate,
        )
        # Finite costs are at most 1 + cost_weight (5) or unknown_cost (<= 1e9):
        # inside the planners' range, so this check never fails.
        costs, lowest = checked_costs(costs)
        costs.flags.writeable = False
        prepared: AStarPlanner | FieldDStar | None = None
        if isinstance(planner, str):
            if planner == "astar":
                # The costs are this planner's own array: no copy needed.
                prepared = AStarPlanner._borrowing(costs, lowest, 8, False, 1.0)
            else:
                prepared = FieldDStar(costs)
        self._grid = grid
        self._snapshot = snapshot
        self._costs = costs
        self._robot_radius = radius
        # As traversal_costs validated them; None kept (pickles of older planners hold it).
        self._inflation_radius = None if inflation_radius is None else float(inflation_radius)
        self._unknown_cost = float(unknown_cost)
        self._inflate_unknown = math.isinf(self._unknown_cost) if inflate is None else inflate
        self._planner = planner
        self._prepared = prepared

    def _closers(self) -> str:
        """What may have closed every way, for a :class:`navkit.NoPathError`'s message."""
        closers = []
        # Each remedy only with its cause: "a smaller robot_radius" at robot_radius=0, or
        # "a finite unknown_cost" on a map without unknown cells, could not open a way.
        remedies = []
        if self._robot_radius > 0.0:
            closers.append(f"obstacles grown by robot_radius={self._robot_radius:g} m")
            remedies.append("a smaller robot_radius")
        if math.isinf(self._unknown_cost) and bool(self._snapshot.unknown().any()):
            # A map built from scans keeps unknown specks inside driven corridors.
            grown = " (and grown)" if self._inflate_unknown and self._robot_radius > 0.0 else ""
            closers.append(f"unknown cells impassable{grown} with unknown_cost=inf")
            remedies.append("a finite unknown_cost")
        if not closers:
            return ""
        closed, opened = " and ".join(closers), " or ".join(remedies)
        return f": {closed} may close every way; {opened} may open one"

    def __copy__(self) -> MapPlanner:
        """A shallow copy with its own Field D* search state.

        The costs, the snapshot and the prepared A* planner are never written
        and stay shared, as does the caller's ``grid``. A prepared
        :class:`FieldDStar` rewrites its search state on every query: shared,
        the copy and the original planning in two threads read each other's
        half-finished searches (wrong paths, false :class:`navkit.NoPathError`).
        """
        # Python's default state of a slotted object, a subclass's __dict__ and slots
        # included (what copy.deepcopy copies), so subclasses copy whole.
        reduced = self.__reduce_ex__(4)
        assert isinstance(reduced, tuple)
        cls = type(self)
        twin = cls.__new__(cls)
        twin.__setstate__(reduced[2])
        if isinstance(self._prepared, FieldDStar):
            twin._prepared = copy.copy(self._prepared)
        return twin

    def __setstate__(self, state: Any) -> None:
        """Restore from a pickle or :func:`copy.deepcopy`, :attr:`costs` read-only again.

        The prepared A* planner borrows the same array, which stays shared.
        """
        restore_slots(self, state, read_only=("_costs",))

    @property
    def grid(self) -> OccupancyGrid:
        """The map the planner was built on."""
        return self._grid

    @property
    def costs(self) -> FloatArray:
        """The traversal costs, float64 (rows, cols), read-only; the same array every time."""
        return self._costs

    @property
    def robot_radius(self) -> float:
        """The robot's inscribed radius, m."""
        return self._robot_radius

    @property
    def inflation_radius(self) -> float:
        """Distance up to which costs decay, m (``None`` resolved to :attr:`robot_radius`).

        Examples
        --------
        >>> import numpy as np
        >>> from navkit.mapping import OccupancyGrid
        >>> grid = OccupancyGrid.from_occupancy(np.zeros((10, 10), dtype=bool), resolution=0.1)
        >>> MapPlanner(grid, robot_radius=0.2).inflation_radius
        0.2
        >>> MapPlanner(grid, robot_radius=0.2, inflation_radius=0.5).inflation_radius
        0.5
        """
        if self._inflation_radius is None:
            return self._robot_radius
        return self._inflation_radius

    @property
    def unknown_cost(self) -> float:
        """Cost of unknown cells: ``inf`` (impassable) or a value in ``[1, 1e9]``.

        Examples
        --------
        >>> import numpy as np
        >>> from navkit.mapping import OccupancyGrid
        >>> grid = OccupancyGrid.from_occupancy(np.zeros((10, 10), dtype=bool), resolution=0.1)
        >>> MapPlanner(grid).unknown_cost, MapPlanner(grid, unknown_cost=50).unknown_cost
        (inf, 50.0)
        """
        return self._unknown_cost

    @property
    def inflate_unknown(self) -> bool:
        """Whether unknown cells were inflated like obstacles (``None`` resolved)."""
        return self._inflate_unknown

    @property
    def planner(self) -> Literal["astar", "field_dstar"] | CellPlanner:
        """The planner name or callable given to the constructor."""
        return self._planner

    def __repr__(self) -> str:
        rows, cols = self._costs.shape
        return (
            f"{type(self).__name__}(<{rows}x{cols} map>, robot_radius={self._robot_radius}, "
            f"planner={self._planner!r})"
        )

    def plan(
        self,
        start: Pose2D | ArrayLike,
        goal: Pose2D | ArrayLike,
        *,
        start_tolerance: float = 0.0,
    ) -> Path2D:
        """Collision-free path between two world points.

        Parameters
        ----------
        start, goal : Pose2D or array_like, shape (2,) or (3,)
            World points ``(x, y)`` in m; a :class:`~navkit.geometry.Pose2D` or
            ``(x, y, theta)`` gives its position (the heading is ignored): a
            robot plans from its pose. Named without the ``_xy`` suffix for
            that: :meth:`FieldDStar.plan_world`'s ``start_xy`` and
            ``goal_xy``, as every ``_xy`` argument, refuse a pose with the
            hint to pass its ``[:2]``.
        start_tolerance : float, default 0.0
            Distance in m, in ``[0, 1e9]`` (keyword-only), within which the
            planner may escape from a start that is impassable only through
            the inflation, i.e. whose cell is neither occupied nor unknown
            space with ``unknown_cost=inf`` but lies within ``robot_radius``
            of such a cell: a robot whose state estimate drifted into the
            inflated band around a wall. Then the path begins at the ``start``
            point itself, goes straight to the centre of the nearest passable
            cell (the escape cell: least distance from ``start`` to its
            centre, at most ``start_tolerance``; ties, equal distances in the
            grid's float64 continuous coordinates, to the lowest
            ``(row, col)``) and follows the path planned from that cell. Only
            cells whose straight segment from ``start`` crosses no occupied
            cell and no impassable unknown cell qualify (a segment touching
            such a cell's square, a corner included, crosses it, as does one
            passing within ``1e-9`` cell sides of it, so that rounding never
            lets one through); it may cross the inflated band. ``0`` (the
            default) never escapes: such a start is refused, as are starts in
            an obstacle, in impassable unknown
            space or outside the map, whatever the tolerance. ROS's navfn and
            global_planner clear the robot's own cell before planning for the
            same reason; Nav2's planners have a goal ``tolerance`` only.

        Returns
        -------
        Path2D
            ``"world"`` path, points ``(x, y)`` in m of shape (K, 2), from
            ``start`` to ``goal``: its first and last points are the points
            given, exactly (as float64), as :meth:`FieldDStar.plan_world`'s.
            Each is linked by a straight segment inside its own (passable)
            cell to that cell's centre, where the planned path begins or ends
            (for ``"astar"`` through cell centres); a point within a millionth
            of a cell of its centre takes the centre's place instead. A start
            and goal in one cell are joined straight (one point when equal);
            in two neighbouring cells, however close, they are joined through
            both centres, as every planner's path joins cells (2 µm apart
            across a cell border: a path one cell long beside the links; the
            length jumps as a point crosses a border: a design choice, so
            that the cost is always the planner's plus the links').
            Cost in cost-weighted metres (the planner's cost × the resolution,
            plus each link's length × its cell's cost: equal to the length in
            free space), length in m (of the polyline, links included),
            expansions. After an escape, the points are
            ``start``, then the planned path from the escape cell's centre;
            ``length`` is the polyline's, escape segment included; ``cost`` is
            the planned path's plus the escape segment's, the integral of the
            cost along it: for each cell it crosses, the length inside the
            cell (m) × the cell's cost, an impassable (band) cell counting
            5 (``1 + cost_weight``, the band's cost next to the inscribed
            zone); ``expanded`` is the search's.

        Raises
        ------
        ValueError
            ``start`` or ``goal`` outside the map (cells are half-open, as in
            :meth:`~navkit.mapping.OccupancyGrid.world_to_cell`: a point on
            the far edges of an unrotated map, ``x = origin.x + width`` or
            ``y = origin.y + height``, is outside; the message gives the
            map's extent), or on an impassable cell
            (``start`` in the inflation only with no escape within
            ``start_tolerance``): the message says whether it is in an
            obstacle, within ``robot_radius`` of one, in unknown space (with
            ``unknown_cost=inf``) or within ``robot_radius`` of unknown space
            (with ``inflate_unknown``); ``start_tolerance`` negative, not
            finite or above 1e9; a :class:`CellPlanner` callable's path that
            does not begin in the start's cell and end in the goal's.
        TypeError
            ``start`` or ``goal`` is not a point or pose; ``start_tolerance``
            not a real number (or a bool). A :class:`CellPlanner` callable
            returning anything but a ``"grid"`` :class:`Path2D`.
        navkit.NoPathError
            No collision-free path exists (from the escape cell, after an
            escape). The message names the start and goal given, with their
            cells, and the search's expansions (``expanded``: cells for
            ``"astar"``, nodes for ``"field_dstar"`` and a
            :class:`CellPlanner` callable), as :func:`astar`'s does.

        Examples
        --------
        A wall from y = 0 to 0.6 m: the robot's centre passes its end at least
        ``robot_radius`` above it, and in free space the cost equals the length:

        >>> import numpy as np
        >>> from navkit.mapping import OccupancyGrid
        >>> occupied = np.zeros((10, 20), dtype=bool)
        >>> occupied[:6, 10] = True
        >>> grid = OccupancyGrid.from_occupancy(occupied, resolution=0.1)
        >>> planner = MapPlanner(grid, robot_radius=0.2)
        >>> path = planner.plan((0.55, 0.25), (1.55, 0.25))
        >>> path.points[[0, -1]].tolist(), bool(path.points[:, 1].max() >= 0.8)
        ([[0.55, 0.25], [1.55, 0.25]], True)
        >>> round(path.length, 3), round(path.cost, 3)
        (1.731, 1.731)

        Points off their cells' centres begin and end the path themselves,
        linked to those centres:

        >>> off = planner.plan((0.52, 0.21), (1.58, 0.29))
        >>> off.points[[0, 1, -2, -1]].round(6).tolist()
        [[0.52, 0.21], [0.55, 0.25], [1.55, 0.25], [1.58, 0.29]]

        A start that drifted into the inflated band is refused, unless it may
        escape to a passable cell within ``start_tolerance``:

        >>> planner.plan((0.85, 0.25), (1.55, 0.25))
        Traceback (most recent call last):
            ...
        ValueError: start (0.85, 0.25) (cell (2, 8)) is within robot_radius (0.2 m) of an ...
        >>> escaped = planner.plan((0.85, 0.25), (1.55, 0.25), start_tolerance=0.2)
        >>> escaped.points[:2].round(6).tolist()  # start, then the escape cell's centre
        [[0.85, 0.25], [0.75, 0.25]]
        """
        tolerance = bounded_float(start_tolerance, "start_tolerance", 0.0, COORDINATE_LIMIT, "m")
        escape: _Escape | None = None
        start_xy = _point_xy(start, "start")
        start_cell = self._point_cell(start_xy, "start")
        if not math.isfinite(self._costs[start_cell]):
            escape = self._escape(start_xy, start_cell, tolerance)
            start_cell = escape.cell
        goal_xy = _point_xy(goal, "goal")
        goal_cell = self._endpoint_cell(goal_xy, "goal")
        prepared = self._prepared
        try:
            if isinstance(prepared, AStarPlanner):
                path = prepared.plan(start_cell, goal_cell)
            elif isinstance(prepared, FieldDStar):
                path = prepared.plan_cells(start_cell, goal_cell)
            else:
                assert callable(self._planner)
                path = self._planner(self._costs, start_cell, goal_cell)
        except NoPathError as exc:
            # The cell planner names the cells it was given; the caller gave points.
            escaped = "" if escape is None else f", escaped to cell {start_cell},"
            # How far the search got (a handful: the start itself is boxed in), as
            # astar's own message says it.
            raise NoPathError(
                f"no collision-free path from {self._end_text(start, start_cell, 'start')}"
                f"{escaped} to {self._end_text(goal, goal_cell, 'goal')}"
                f" (expanded {_expansions(prepared, exc)}){self._closers()}",
                expanded=exc.expanded,
            ) from exc
        if not isinstance(path, Path2D) or path.frame != "grid":
            raise TypeError(
                f"the cell planner must return a 'grid' Path2D, got {path!r:.80}"
            )
        _check_ends(path.points, start_cell, goal_cell)
        grid = self._grid
        # As Path2D.to_world converts it: a plan between two cell centres is that path.
        points, cost = grid_to_world(path.points, path.cost, grid)
        if escape is None and start_cell == goal_cell and len(points) == 1:
            # One cell: straight from the start to the goal, inside the cell.
            same = bool(np.array_equal(start_xy, goal_xy))
            points = start_xy[None, :] if same else np.stack((start_xy, goal_xy))
            cost = float(np.hypot(*(goal_xy - start_xy))) * float(self._costs[goal_cell])
        else:
            if escape is not None:
                points = np.concatenate((escape.point[None, :], points))
                cost += escape.cost * grid.resolution
            else:
                points, cost = self._linked(points, cost, start_xy, start_cell, 0)
            points, cost = self._linked(points, cost, goal_xy, goal_cell, -1)
        length = polyline_length(points)
        return Path2D(
            points, "world", cost=cost, length=length,
            expanded=path.expanded,
        )

    def _linked(
        self, points: FloatArray, cost: float, point: FloatArray, cell: tuple[int, int], end: int
    ) -> tuple[FloatArray, float]:
        """``points`` (world) beginning (``end=0``) or ending (``end=-1``) at ``point`` exactly.

        The planned path ends at the centre of ``cell``, the passable cell
        holding ``point``; the straight link between them stays inside that
        cell (a square holds the segment between two of its points), so the
        path stays collision-free, and costs its length × the cell's cost. The
        planned path itself is kept as planned (A*'s through cell centres). A
        point within a millionth of a cell of the centre takes the centre's
        place instead: a link that short is the rounding of ``cell_to_world``
        (0.55 back as 0.5500000000000002), not a step.
        """
        centre = points[end]
        step = float(np.hypot(*(point - centre)))
        if step <= _SAME_POINT * self._grid.resolution:
            points = points.copy()
            points[end] = point
            return points, cost
        pair = (point[None, :], points) if end == 0 else (points, point[None, :])
        return np.concatenate(pair), cost + step * float(self._costs[cell])

    def _escape(self, point: FloatArray, start: tuple[int, int], tolerance: float) -> _Escape:
        """The escape from the impassable start cell ``start``, or the refusal.

        The hard cells, which no escape segment may touch, are the occupied
        ones and, with ``unknown_cost=inf``, the unknown ones; the search is
        :func:`~navkit.planning.grid._escape.nearest_escape`, shared with
        :class:`FieldDStar`. The reason of a refusal is worked out only then
        (:meth:`_blocked_reason` may rebuild the costs).
        """
        where = f"start {tuple(point.tolist())} (cell {start})"
        if tolerance == 0.0:
            reason = self._blocked_reason(*start)
            hint = (
                "; pass start_tolerance > 0 to escape to the nearest passable cell"
                if reason.startswith("is within robot_radius")
                else ""
            )
            raise ValueError(f"{where} {reason}{hint}")
        q_row, q_col = (
            float(v)
            for v in np.asarray(
                self._grid.world_to_cell(point, continuous=True), dtype=np.float64
            ).reshape(2)
        )
        snapshot = self._snapshot
        hard = snapshot.occupied()
        if math.isinf(self._unknown_cost):
            hard |= snapshot.unknown()
        if hard[start]:
            # In an obstacle or in impassable unknown space: never escaped.
            raise ValueError(f"{where} {self._blocked_reason(*start)}")
        found = nearest_escape(
            self._costs, hard, start, (q_row, q_col), tolerance, self._grid.resolution
        )
        if found is not None:
            return _Escape(found[0], point, found[1])
        raise ValueError(
            f"{where} {self._blocked_reason(*start)}, and no passable cell centre within "
            f"start_tolerance ({tolerance} m) can be reached in a straight line without "
            "crossing an obstacle" + (" or unknown space" if math.isinf(self._unknown_cost) else "")
        )

    def _endpoint_cell(self, point: FloatArray, name: str) -> tuple[int, int]:
        row, col = self._point_cell(point, name)
        if not math.isfinite(self._costs[row, col]):
            where = f"{name} {tuple(point.tolist())}"
            raise ValueError(f"{where} (cell {(row, col)}) {self._blocked_reason(row, col)}")
        return row, col

    def _point_cell(self, point: FloatArray, name: str) -> tuple[int, int]:
        """The cell of a world point, refused outside the map."""
        row, col = (int(v) for v in np.asarray(self._grid.world_to_cell(point)).reshape(2))
        rows, cols = self._costs.shape
        if not (0 <= row < rows and 0 <= col < cols):
            raise ValueError(
                f"{name} {tuple(point.tolist())} is outside the map{self._extent_text(point)}"
            )
        return row, col

    def _extent_text(self, point: FloatArray) -> str:
        """Where the map lies, in world metres (only on an error path).

        A map ``origin`` given as the map's centre, or cells given for metres,
        are the usual causes of an endpoint outside it; the extent shows both.
        A refused ``point`` inside the printed ranges gets the reason: it is
        on the map's far edges (cells are half-open) or, on a rotated map,
        outside the map but inside the box around it.
        """
        rows, cols = self._costs.shape
        size = np.array([[0, 0], [cols, 0], [0, rows], [cols, rows]]) * self._grid.resolution
        corners = self._grid.origin.transform_points(size)
        # To the nanometre (a rotated origin leaves 1e-16 m where 0 is meant), not to
        # :g's 6 digits: a map at UTM-size coordinates would read [4.51235e+06,
        # 4.51235e+06], hiding the point's distance from it.
        lo, hi = corners.min(axis=0), corners.max(axis=0)
        lo0, lo1, hi0, hi1 = (metres_text(v) for v in (*lo.tolist(), *hi.tolist()))
        why = ""
        if bool(np.all((lo <= point) & (point <= hi))):
            why = (
                f"; its far edges x = {hi0} m and y = {hi1} m belong to no cell"
                if self._grid.origin.theta == 0.0
                else "; the map is rotated by its origin's theta and these ranges are "
                "the box around it"
            )
        return (
            f": the map covers x in [{lo0}, {hi0}] m and y in [{lo1}, {hi1}] m{why} "
            "(its origin is the lower-left corner of cell (0, 0), not the map's centre; "
            "start and goal are world points in metres, not cells)"
        )

    @staticmethod
    def _end_text(value: Pose2D | ArrayLike, cell: tuple[int, int], name: str) -> str:
        """``name`` and the point the caller gave, with its cell (only on an error path)."""
        return f"{name} {tuple(_point_xy(value, name).tolist())} (cell {cell})"

    def _blocked_reason(self, row: int, col: int) -> str:
        """Why cell (row, col) is impassable (only on the error path: reads the map's views).

        From the snapshot the costs were built on: the map itself may have
        changed since (the costs have not).
        """
        grid = self._snapshot
        if grid.occupied()[row, col]:
            return "is in an obstacle"
        if grid.unknown()[row, col] and math.isinf(self._unknown_cost):
            return "is in unknown space (unknown_cost is inf)"
        if self._inflate_unknown:
            # Blocked only by the inflation of unknown space if it is free without it.
            plain = grid.traversal_costs(
                robot_radius=self._robot_radius,
                inflation_radius=self._inflation_radius,
                unknown_cost=self._unknown_cost,
                inflate_unknown=False,
            )
            if math.isfinite(plain[row, col]):
                return (
                    f"is within robot_radius ({self._robot_radius} m) of unknown space "
                    "(inflate_unknown is True)"
                )
        return f"is within robot_radius ({self._robot_radius} m) of an obstacle"


#: A start or goal within this many cells of its cell's centre takes the centre's place.
_SAME_POINT = 1e-6


#: The count at the end of navkit's cell planners' NoPathError ("... (expanded 3 cells)").
_EXPANDED = re.compile(r" \(expanded (\d+ [a-z]+(?: [a-z]+)?)\)$")


def _expansions(prepared: AStarPlanner | FieldDStar | None, exc: NoPathError) -> str:
    """``"200 cells"``: how far the cell planner's search got, named as it names it."""
    if isinstance(prepared, AStarPlanner):
        return counted(exc.expanded, "jump point" if prepared.method == "jps" else "cell")
    if isinstance(prepared, FieldDStar):
        return counted(exc.expanded, "node")
    # A cell planner of the caller's: its count in its own words (navkit's astar
    # and Field D* end their message with it), or the bare number.
    found = _EXPANDED.search(str(exc))
    if found is not None and found.group(1).split(" ", 1)[0] == str(exc.expanded):
        return found.group(1)
    return str(exc.expanded)


def _check_ends(cells: FloatArray, start: tuple[int, int], goal: tuple[int, int]) -> None:
    """Refuse a cell planner's path that does not begin in ``start`` and end in ``goal``.

    The points given are linked straight to the path's ends, a link that is
    collision-free only inside the end's own (passable) cell: a callable
    breaking the :class:`CellPlanner` contract (a path from elsewhere, or
    reversed) would otherwise get a segment across the map, through walls.
    """
    first, last = cells[0], cells[-1]
    # Half a cell: the ends may be off the centres (as floats), not out of the cells.
    if np.abs(first - start).max() <= 0.5 and np.abs(last - goal).max() <= 0.5:
        return
    raise ValueError(
        f"the cell planner must return a path from start_cell {start} to goal_cell {goal}, "
        f"got one from {tuple(first.tolist())} to {tuple(last.tolist())}"
    )


class _Escape(NamedTuple):
    """The escape cell, the start point (world) and the segment's cost in cost units × cells."""

    cell: tuple[int, int]
    point: FloatArray
    cost: float


def _point_xy(value: Pose2D | ArrayLike, name: str) -> FloatArray:
    """``(x, y)`` of a point, a Pose2D or an ``(x, y, theta)`` sequence."""
    if isinstance(value, Pose2D):
        return np.array([value.x, value.y])
    if not isinstance(value, (str, bytes)) and np.shape(value) == (3,):
        pose = as_pose(value, name)
        return np.array([pose.x, pose.y])
    return as_float_array(value, name, shape=(2,))


def plan_path(
    grid: OccupancyGrid,
    start: Pose2D | ArrayLike,
    goal: Pose2D | ArrayLike,
    *,
    robot_radius: float = 0.0,
    inflation_radius: float | None = None,
    unknown_cost: float = math.inf,
    inflate_unknown: bool | None = None,
    planner: Literal["astar", "field_dstar"] | CellPlanner = "astar",
    start_tolerance: float = 0.0,
) -> Path2D:
    """Plan a collision-free path between two world points on an occupancy grid, one-shot.

    ``MapPlanner(grid, ...).plan(start, goal, start_tolerance=...)``: builds the traversal costs for
    this one query. For many queries on the same map keep a :class:`MapPlanner`,
    which builds them once.

    Parameters
    ----------
    grid : OccupancyGrid
        The map.
    start, goal : Pose2D or array_like, shape (2,) or (3,)
        World points ``(x, y)`` in m, or poses (their position).
    robot_radius, inflation_radius, unknown_cost, inflate_unknown, planner
        As in :class:`MapPlanner`: ``robot_radius`` in ``[0, 1e6]`` m;
        ``inflate_unknown=None`` keeps the robot ``robot_radius`` clear of
        unknown space whenever ``unknown_cost`` is ``inf``; ``planner`` is
        ``"astar"``, ``"field_dstar"`` or a :class:`CellPlanner` callable
        (options by :func:`functools.partial`).
    start_tolerance : float, default 0.0
        As in :meth:`MapPlanner.plan`: how far, in m, a start inside the
        inflation may escape to the nearest passable cell (0: refused).

    Returns
    -------
    Path2D
        ``"world"`` path, see :meth:`MapPlanner.plan`.

    Raises
    ------
    ValueError, TypeError, navkit.NoPathError
        As :class:`MapPlanner` and :meth:`MapPlanner.plan`.

    Examples
    --------
    >>> from functools import partial
    >>> import numpy as np
    >>> from navkit.mapping import OccupancyGrid
    >>> from navkit.planning import astar
    >>> occupied = np.zeros((20, 30), dtype=bool)
    >>> occupied[:15, 14:16] = True
    >>> grid = OccupancyGrid.from_occupancy(occupied, resolution=0.1)
    >>> path = plan_path(grid, (0.55, 0.55), (2.55, 0.55), robot_radius=0.2)
    >>> path.points[0].tolist(), path.points[-1].tolist()
    ([0.55, 0.55], [2.55, 0.55])
    >>> cut = plan_path(grid, (0.55, 0.55), (2.55, 0.55), robot_radius=0.2,
    ...                 planner=partial(astar, corner_cutting=True))
    >>> bool(cut.cost <= path.cost)
    True
    """
    return MapPlanner(
        grid,
        robot_radius=robot_radius,
        inflation_radius=inflation_radius,
        unknown_cost=unknown_cost,
        inflate_unknown=inflate_unknown,
        planner=planner,
    ).plan(start, goal, start_tolerance=start_tolerance)


if not TYPE_CHECKING:  # mypy would take any name of this module
    # A pickle made at 5e5f83f (30 November 2026) names this module's WorldPath, which
    # 0123de4 replaced by Path2D: refused clearly, not pickle's AttributeError.
    __getattr__ = gone(__name__, ("WorldPath",), "0123de4")
