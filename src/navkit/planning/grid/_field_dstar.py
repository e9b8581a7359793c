"""Field D*: interpolated any-angle planning on cell corners with D* Lite repair."""

from __future__ import annotations

import copy
import math
from _thread import get_ident
from collections.abc import Mapping
from types import MappingProxyType
from typing import TYPE_CHECKING, Any, Literal, cast, overload

import numpy as np
from numpy.typing import ArrayLike, NDArray

from navkit._shared.counts import counted
from navkit._shared.dunders import slot_state
from navkit._shared.frozen import restore_slots
from navkit._shared.grid_coords import as_pairs, one_or_many, round_half_up
from navkit._shared.locks import one_caller
from navkit._shared.moved import gone
from navkit._shared.types import CellLike, FloatArray, IntArray
from navkit._shared.validation import (
    as_array,
    as_bool,
    as_cell,
    as_float_array,
    as_point,
    is_ndarray,
)
from navkit.errors import NoPathError
from navkit.geometry import Pose2D, as_pose
from navkit.planning.grid._dstar_heap import RHS, G, clear_box, node_records
from navkit.planning.grid._dstar_lite_kernels import (
    FIELD_HSCALE,
    HALF_DIAGONAL,
    OCT,
    params,
    state,
)
from navkit.planning.grid._escape import nearest_escape
from navkit.planning.grid._field_path_kernels import (
    ABORTED,
    CANDIDATES,
    FULL,
    NO_PATH,
    OK,
    extract_path,
)
from navkit.planning.grid._limits import (
    COORDINATE_LIMIT,
    MAX_COST,
    PATH_COST_LIMIT,
    RESOLUTION_MAX,
    RESOLUTION_MIN,
    bounded_float,
    checked_costs,
)
from navkit.planning.grid._limits import check_range as _check_range
from navkit.planning.grid._path import Path2D, polyline_length
from navkit.planning.grid._polyline_kernels import polyline_cost, shortcut

__all__ = ["FieldDStar", "field_dstar"]

# Consecutive refusals after which the shortcut pass stops extending a segment.
_SHORTCUT_PATIENCE = 8
# How a planning method takes its ends (nodes, cells or world points), see FieldDStar._ends_text.
_Ends = Literal["node", "cell", "xy"]
_IDENTITY = Pose2D(0.0, 0.0, 0.0)
# The four corners of a cell, as node offsets from its (row, col).
_CORNERS = np.array([(0, 0), (0, 1), (1, 0), (1, 1)], dtype=np.int64)
# Node coordinates beyond this are refused: integers stay exact and their world
# points finite.
_NODE_LIMIT = float(2**53)
# Repair bounds. A repair's work counts expansions, a rising node RAISE_WORK; the
# bounds are fractions of the last fresh search's work (and at least
# _REPAIR_MIN_WORK). A repair that exceeds its bound is cut short and replaced by
# a fresh search on the planner's own arrays (the same path).
#
# After cost rises (the usual case: cells blocked), a repair sweeps the queue's
# keys from the lowest changed key `first` to the start's key `end`, and the
# region it has touched grows in two dimensions as the sweep advances, so its
# work grows about as the square of the key progress (measured on 1024² random
# and rooms maps and on maze512-32-9 at 40 change positions along the path:
# between linear and quadratic early, quadratic as the wave widens). The repair
# runs in stages of _REPAIR_PROBE, then twice as much work each time; after
# each stage the work so far, extrapolated quadratically over the key range,
# gives the projected total. A projection above _REPAIR_CAP (a repair that would
# cost more than a fresh search: a change near the goal raises nearly every
# node value, 2-4 fresh searches' work) falls back to the fresh search at once;
# the projection overestimates a repair that finishes, so a hopeless one is
# caught within a stage or two while most changes mid-path still repair. A
# repair work unit costs about 0.5-0.65 of a fresh expansion's time (measured),
# so a repair that finishes under the cap costs at most about 0.65 fresh
# searches, and one caught by the projection wastes one stage.
_REPAIR_CAP = 1.0
_REPAIR_PROBE = 0.005
_REPAIR_PROBE_MIN_WORK = 1024
# When some cell got cheaper (a falling wave, no key range to project over), the
# repair gets one bound: local changes near the robot need well under 1 % of a
# fresh search on large maps.
_REPAIR_FRACTION = 0.05
_REPAIR_MIN_WORK = 4096
_NO_LIMIT = np.iinfo(np.int64).max // 2
# The box of written records (first and last row, first and last column, see
# FieldDStar._blank) holding no node.
_EMPTY_BOX = (_NO_LIMIT, -1, _NO_LIMIT, -1)
# Initial room of the path buffer, points per node row and column; a longer walk
# is repeated with a buffer twice as large.
_POINTS_PER_SIDE = 4


def _on_node(point: tuple[float, float] | None, node: tuple[int, int] | None) -> bool:
    """Whether a kept end's point is its node itself: an end :meth:`FieldDStar.plan` gave."""
    return point is not None and node is not None and point == (float(node[0]), float(node[1]))


#: Slots :class:`FieldDStar` gained since a release, for pickles made before (see
#: navkit._shared.frozen.fill_added_fields), each as the planner of then worked:
#: changes applied at once (none pending), every end a node (plan_cells linked cell
#: centres to nodes), checked again as the method that gave it checks it (plan:
#: the point is the node itself).
_ADDED_SLOTS = MappingProxyType(
    {
        "_changed": lambda planner: np.zeros(64, dtype=np.int64),
        "_lowered": lambda planner: False,
        "_start_cell": lambda planner: False,
        "_goal_cell": lambda planner: False,
        "_start_on_node": lambda planner: _on_node(planner._start_point, planner._start),
        "_goal_on_node": lambda planner: _on_node(planner._goal_point, planner._goal),
    }
)


class FieldDStar:
    """Field D* planner (Ferguson & Stentz) with incremental D* Lite repair.

    Nodes are the cell corners: a grid of ``rows × cols`` cells has a
    ``(rows + 1) × (cols + 1)`` node grid, and node ``(i, j)`` is the corner
    between cells ``(i-1, j-1)`` and ``(i, j)``, at continuous grid coordinates
    ``(row, col) = (i - 0.5, j - 0.5)`` (integers are cell centres). A path may
    cross a cell edge at any point; the cost-to-goal there is interpolated
    linearly between the edge's two nodes, so headings are not restricted to
    multiples of 45°. Crossing a cell costs its value per unit length; running
    along an edge costs the cheaper of the two cells beside it.

    The search is D* Lite (Koenig & Likhachev) backwards from the goal, so after
    :meth:`update_costs` the next :meth:`replan` repairs only the part of the
    cost field the change affects, also when the robot has moved (new start,
    same goal). A repair that would cost more than a fresh search (a change
    near the goal raises nearly every node's value) is detected early, from
    how its work grows while it sweeps the affected values, and replaced by a
    fresh search on the planner's own arrays: a replan costs about as much as
    a fresh plan at worst, and a small fraction of one after most changes
    between the robot and the goal. A class with ``__slots__``: it keeps and
    updates the search state between calls.

    Three ways to give the ends, each returning a :class:`Path2D`:

    * nodes: :meth:`plan` / :meth:`replan` (``"grid"`` path from node to node);
    * cells: :meth:`plan_cells` (``"grid"`` path from cell centre to cell centre);
    * world points: :meth:`plan_world` / :meth:`replan_world` (``"world"`` path
      from point to point), with the grid placed in the world by ``resolution``
      and ``origin`` as an :class:`~navkit.mapping.OccupancyGrid` is.

    Parameters
    ----------
    costs : (rows, cols) array_like
        Per-cell traversal cost per unit length: finite values in ``[1, 1e12]``,
        ``np.inf`` impassable (the A* convention), at most ``2**31 - 1`` nodes
        ``(rows + 1) × (cols + 1)``. Copied; the caller's array is never
        modified. The least cost from a start to the goal must moreover be below
        ``2**52`` (about 4.5e15 cost units × cells), see Notes. Paths run
        through nodes, so they pass between two impassable cells that touch
        only at a corner (a gap of zero width), which A* without corner
        cutting refuses.
    interpolate : bool, default True
        ``False`` gives classic 8-connected D* Lite on the same nodes (an axis
        move pays the cheaper cell beside the edge, a diagonal ``sqrt(2)`` times
        the cell it crosses) and returns the optimal node path.
    lookahead : bool, default True
        One-step lookahead in the path extraction: a candidate crossing point
        inside an edge is scored by the best step onwards from it instead of by
        the linearly interpolated cost-to-goal there. Without it the path is
        occasionally costlier than the 8-connected one: in random tests
        (grids up to 12 × 12, a quarter impassable) by up to about 15 % on
        maps of free and blocked cells (4 % after smoothing), and up to about
        35 % (14 % after smoothing) on grids of costs uniform in [1, 10].
    smooth : bool, default True
        After extraction, replace runs of the polyline by straight segments
        whenever the segment's exact cost is not higher (up to a relative
        ``1e-12``, so that rounding in the sums does not block a straight
        segment). It never raises the path cost by more than that allowance
        and makes paths in uniform regions exactly straight. Used with
        ``interpolate=True`` by :meth:`plan` / :meth:`replan`, and always on the
        linked paths of :meth:`plan_cells` and the world methods.
    resolution : float, optional
        Cell side in m, in ``[1e-6, 1e6]``, for the world methods (the node and
        cell methods do not use it). Default (``None``): 1 m, which suits a bare
        cost array; for costs of an :class:`~navkit.mapping.OccupancyGrid` pass
        its ``resolution`` and ``origin``, which :class:`MapPlanner` reads from
        its grid itself.
    origin : Pose2D or (x, y, theta), default Pose2D(0, 0, 0)
        World pose of node ``(0, 0)``, the outer corner of cell ``(0, 0)``
        (rows along the origin's y axis, columns along its x axis), for the
        world methods: the convention of :class:`~navkit.mapping.OccupancyGrid`.
        ``|x|, |y| <= 1e9`` m. Only with ``resolution``: a grid's origin given
        alone would place the nodes 1 m apart, so it raises ``ValueError``.
    obstacles : (rows, cols) array_like of bool, optional
        Which impassable cells are obstacles (occupied, or unknown space not
        to be crossed) rather than the inflation drawn around them; every
        ``True`` cell must cost ``inf``. For costs from
        ``grid.traversal_costs(robot_radius=...)`` pass ``grid.occupied() |
        grid.unknown()`` (``grid.occupied()`` with a finite
        ``unknown_cost``). Read only by the world methods' ``start_tolerance``
        (:meth:`plan_world`): a start in the inflation may escape to a
        passable cell, never through an obstacle. Copied (1 byte a cell);
        :meth:`update_costs` keeps it current: a cell it makes impassable
        counts as an obstacle (the planner cannot tell a new obstacle from
        the inflation drawn around it) unless its ``obstacles=`` says
        otherwise, one it opens does not. ``None`` (the default): every
        impassable cell counts as an obstacle, so no start escapes (until
        :meth:`update_costs` marks inflation with ``obstacles=False``).

    Raises
    ------
    ValueError
        Invalid ``costs`` (see :func:`navkit.planning.distance_field`), too
        many nodes, ``resolution`` or ``origin`` out of range, ``origin``
        without ``resolution``; ``obstacles`` of another shape than ``costs``
        or marking a cell of finite cost.
    TypeError
        Non-bool flags (``interpolate``, ``lookahead``, ``smooth``: only
        ``True``/``False``), a bad ``origin``, ``obstacles`` not boolean.
    MemoryError
        No memory for the planner's arrays (about 56 bytes a node), naming
        the grid's size.

    Notes
    -----
    The interpolated node cost is the minimum over every option of the paper's
    formula (see ``corner_cost`` in ``_dstar_lite_kernels``) rather than the one
    option the paper's tests select; the value is never higher and identical
    whenever the paper's choice is the cheapest. The heuristic is the octile
    distance divided by ``sqrt(2)`` (the plain octile distance without
    interpolation): weak enough that an interpolated node is never expanded
    before the neighbours its cost depends on, so each node is expanded once
    per search. It assumes a minimum cell cost of 1, so it stays admissible
    after any cost update.

    Optimality and symmetry. The node values interpolate the continuous
    cost-to-goal, and the extracted polyline is not always the cheapest one.
    In random tests with the defaults its cost was at most 1 % above that of
    the 8-connected path (``interpolate=False``, an exact search), and
    usually below it; not a bound: on tiny grids where the way runs through
    one-cell gaps it can be more (above 1 % for about 1 in 10^4 random
    grids of up to 8 × 8 cells, at most 4.5 %: costs ``[[2, 1, inf], [2,
    inf, 1], [3.5, 1, inf]]`` from node ``(2, 0)`` to ``(1, 2)``, 4 against
    3.83, where the start node's interpolated value, 3.73, is below any
    path's cost). The values are computed from the goal, so swapping the
    start and the goal can change the path's cost (by up to about 4 % in those
    tests), whereas A* and ``interpolate=False`` give the same cost both ways.
    Mirroring the grid or turning it by quarter turns (the nodes with it)
    leaves the settled node values unchanged, bit for bit (every site of the
    search evaluates a pair of neighbours with the same arguments, as a
    mirrored grid does; review 41), but not always the path.
    Where two candidate points of the walk tie in value (the crossing points
    of two far edges of a cell whose other corners have equal values), it
    takes the first it scans, and the two continuations can differ in cost.
    In random tests (grids up to 10 × 10, 20 % impassable) the unsmoothed
    path's cost differed between drawings for about 3 in 10^4 pairs of nodes
    without the lookahead (at most 24 %; 29 % with integer costs 1 to 5,
    where ties are commoner) and 2.4 in 10^4 with it (at most 1.5 %). For
    example, costs ``[[3, 4, 3, 5], [2, 2, 1, 4], [3, 5, 1, 3], [1, 1, 1, 5],
    [2, 5, inf, inf], [inf, 5, 1, 3], [inf, 4, 1, 3], [1, 5, 2, 3]]`` from
    node ``(8, 0)`` to ``(2, 1)`` without the lookahead give 16.71 on four
    drawings and 16.29 on the other four. The shortcut pass is greedy along
    the path, so it may also straighten a mirrored path differently (about
    1 % in tests).

    Limits of float64. Path extraction (below) walks downhill on the
    cost-to-goal, so it needs every node to be strictly dearer than the
    neighbour its value comes from. In exact arithmetic the difference is at
    least ``1/sqrt(2)`` (costs are >= 1); in float64 it survives rounding while
    the values are below ``2**52`` (about 4.5e15), where one unit in the last
    place is at most 0.5, but not far beyond: at 1e20, ``1e20 + 1.41 == 1e20``
    and the walk would find no lower neighbour. Every search therefore
    requires the start's cost-to-goal (the path cost in cost units × cells)
    to be below ``2**52`` and raises ``ValueError`` otherwise; with cells up to
    the maximum 1e12 that allows paths of 4,500 cells at the maximum cost.

    Path extraction walks from the start: at each point (a node or a point on
    a grid line) it takes the cheapest of the optimal crossing points of the far
    edges of the cells touching it, the ends of the grid lines through it and,
    from a node, the point where the paper's "along the edge, then cut" option
    leaves the edge. A step must lower the estimated cost-to-goal; if none does,
    a straight step to a corner of lower exact cost-to-goal is taken instead.
    A crossing point a hair from an edge's end can have its interpolated value
    rounded to exactly that end's value (costs of very different magnitude);
    from such a point the walk may step to a corner cheaper than the last
    node it passed. Node values met along the walk strictly decrease, so it
    always ends exactly at the goal. Every node value the walk reads
    is settled first (the D* Lite loop runs until that node's key is reached),
    so a repaired plan reads exactly the values a fresh plan reads and both
    return the same path.

    Memory: a planner keeps 56 bytes a node ((rows + 1) × (cols + 1) nodes)
    between queries: its values ``g`` and ``rhs`` and the padded costs, 8 bytes
    each, and a priority queue able to hold every node, 32 (about 900 MB for a
    4000 × 4000 grid). Of the queue, 24 bytes a node (past 1 MiB) are pages
    mapped on their own, which take memory only where a search writes (the
    first few thousand slots). Returned paths hold only their own points.

    A planner keeps its search state between queries, so it is not
    thread-safe: one thread at a time may call its methods (queries included);
    different planners may run in different threads at once. A plan, replan or
    cost update called while another is under way (another thread's, or a
    signal handler's interrupting one in the same thread) raises
    ``RuntimeError`` and changes nothing; the call under way goes on as alone.
    A copy or pickle made while a call is under way keeps the costs but not
    the search, which the call is writing: its :meth:`replan` asks for a
    :meth:`plan` first. Taking a copy is a call too: a plan, replan or cost
    update that another thread starts while ``copy`` or ``pickle`` reads the
    planner raises ``RuntimeError`` (a thread saving snapshots of a planner
    that another thread plans with needs the same lock as the calls). Copies
    that several threads take at once each keep the search.

    Examples
    --------
    >>> import numpy as np
    >>> from navkit.planning import FieldDStar
    >>> planner = FieldDStar(np.ones((20, 20)))
    >>> path = planner.plan((0, 0), (20, 10))
    >>> path.frame, path.points.tolist()
    ('grid', [[-0.5, -0.5], [19.5, 9.5]])
    >>> round(path.cost, 9) == round(float(np.hypot(20, 10)), 9)
    True
    >>> planner.update_costs([(3, 1), (3, 2)], np.inf)
    >>> again = planner.replan()
    >>> again.cost > path.cost
    True

    In world coordinates (0.1 m cells, the grid's corner at (1, 2)):

    >>> world = FieldDStar(np.ones((20, 20)), resolution=0.1, origin=(1.0, 2.0, 0.0))
    >>> path = world.plan_world((1.05, 2.05), (2.55, 3.05))
    >>> path.frame, path.points.round(6).tolist()
    ('world', [[1.05, 2.05], [2.55, 3.05]])
    >>> world.replan_world((1.25, 2.05)).points.round(6).tolist()
    [[1.25, 2.05], [2.55, 3.05]]
    """

    __slots__ = (
        "__weakref__",
        "_cached",
        "_callers",
        "_changed",
        "_clean",
        "_cols",
        "_escape",
        "_fresh",
        "_fresh_work",
        "_g",
        "_goal",
        "_goal_cell",
        "_goal_on_node",
        "_goal_point",
        "_goal_xy",
        "_heap",
        "_hscale",
        "_interp",
        "_km",
        "_lookahead",
        "_lowered",
        "_ncols",
        "_nrows",
        "_obstacles",
        "_origin",
        "_pad",
        "_resolution",
        "_rhs",
        "_rows",
        "_smooth",
        "_start",
        "_start_cell",
        "_start_on_node",
        "_start_point",
        "_start_xy",
        "_vals",
        "_width",
        "_work",
    )

    _added_fields = _ADDED_SLOTS

    def __init__(
        self,
        costs: ArrayLike,
        *,
        interpolate: bool = True,
        lookahead: bool = True,
        smooth: bool = True,
        resolution: float | None = None,
        origin: Pose2D | ArrayLike = _IDENTITY,
        obstacles: ArrayLike | None = None,
    ) -> None:
        # The calls under way (one at most: see one_caller; not copied or pickled).
        self._callers: list[tuple[int, str, object]] = []
        arr, _ = checked_costs(costs, corner_nodes=True)
        self._interp = as_bool(interpolate, "interpolate")
        self._lookahead = as_bool(lookahead, "lookahead")
        self._smooth = as_bool(smooth, "smooth")
        self._resolution = 1.0 if resolution is None else bounded_float(
            resolution, "resolution", RESOLUTION_MIN, RESOLUTION_MAX, "m"
        )  # fmt: skip
        self._origin = as_pose(origin, "origin")
        if not max(abs(self._origin.x), abs(self._origin.y)) <= COORDINATE_LIMIT:
            raise ValueError(
                f"origin must lie within ±{COORDINATE_LIMIT:g} m in x and y, got {self._origin!r}"
            )
        if resolution is None and origin is not _IDENTITY:
            # A grid's origin without its resolution planned on 1 m cells, silently.
            raise ValueError(
                "origin needs resolution, the cell side of the same grid: pass both "
                "(resolution=grid.resolution, origin=grid.origin); alone, the origin "
                "would place the nodes 1 m apart (the default for a bare cost array)"
            )
        self._rows, self._cols = (int(v) for v in arr.shape)
        self._obstacles = None if obstacles is None else _obstacle_mask(obstacles, arr)
        if self._obstacles is not None:
            # Only a planner told its obstacles escapes (start_tolerance): scipy.ndimage
            # (0.05-0.5 s to import) here, not in the first escape of a control loop.
            import scipy.ndimage  # noqa: F401
        # After an escape from the inflation (start_tolerance): the start point the
        # caller gave (node coordinates) and the escape segment's cost (cost units ×
        # cells); _start_point is then the escape cell's centre.
        self._escape: tuple[tuple[float, float], float] | None = None
        self._width = self._cols + 2
        # The border inf, then the costs: one pass over the memory (a fill with inf
        # first wrote every line twice).
        try:
            pad = np.empty((self._rows + 2, self._cols + 2))
        except MemoryError as exc:
            raise MemoryError(_memory_text(self._rows, self._cols)) from exc
        pad[0] = pad[-1] = np.inf
        pad[1:-1, 0] = pad[1:-1, -1] = np.inf
        pad[1:-1, 1:-1] = arr
        self._pad = pad.ravel()
        self._hscale = FIELD_HSCALE if self._interp else 1.0
        self._nrows = self._rows + 1
        self._ncols = self._cols + 1
        # g, rhs and the heap slot of each node side by side (one cache line per node
        # read, see node_records); _g and _rhs are views of their columns.
        self._vals, self._heap = _search_state(self._rows, self._cols)
        self._g, self._rhs = self._vals[:, G], self._vals[:, RHS]
        # g, rhs and the heap as allocated: the first search need not clear them.
        self._clean = True
        self._km = 0.0
        # (work done, work limit) of the current search, see settle(), then the box of
        # the records written since they were last blanked (see _blank).
        self._work = np.array([0, 0, *_EMPTY_BOX], dtype=np.int64)
        # Cells changed since the last search (count, then padded flat indices), see
        # update_costs(), and whether any of them became cheaper.
        self._changed = np.zeros(64, dtype=np.int64)
        self._lowered = False
        # Whether the next search starts from scratch, and the work of the last one that did.
        self._fresh = True
        self._fresh_work = 0
        # The last node path found and the start node it runs from: valid while
        # no cell cost changes and the goal stays, so a replan from the same
        # start returns it without walking the cost field again.
        self._cached: tuple[tuple[int, int], FloatArray, float, float] | None = None
        self._start: tuple[int, int] | None = None
        self._goal: tuple[int, int] | None = None
        # The path's end points in node coordinates (the nodes themselves, cell
        # centres after plan_cells, world points after the world methods).
        self._start_point: tuple[float, float] | None = None
        self._goal_point: tuple[float, float] | None = None
        # The world points given for the ends (the world methods; after an escape
        # the point given, not the escape cell's centre), or None for a node or a
        # cell: world paths begin and end at them exactly, not at their node
        # coordinates turned back into world points (a rounding step off).
        self._start_xy: tuple[float, ...] | None = None
        self._goal_xy: tuple[float, ...] | None = None
        # Whether each end was given as a node (plan(), replan()) rather than as a
        # point in a cell (plan_cells(), the world methods): a replan checks a kept
        # end again the way the method that gave it checked it.
        self._start_on_node = False
        self._goal_on_node = False
        # Whether each end is a cell (plan_cells): the search's goal is then the
        # goal cell's centre, linked to its four corners (each a source of the
        # search), and the walk starts at the start cell's corner of least
        # cost-to-goal; _start / _goal hold the cells' lower-left corners (lowest row, col).
        self._start_cell = False
        self._goal_cell = False

    def __getstate__(self) -> object:
        """The state pickles and copies take: Python's default, without what is derived.

        Taken as a short call of the planner (calls of other threads starting
        meanwhile are refused), with its arrays copied under that guard, so
        that a call starting once this returns, while pickle or ``copy`` reads
        the state, cannot change them. A copy made while another call is under
        way (another thread's, or a signal handler's copy inside the main
        thread's call; not another copy, which only reads) keeps the costs but
        no search: the searches write the
        search state in place with the GIL released, and such a copy held it
        half-written (29 of 168 copies taken while another thread planned
        replanned for ever, holding no GIL; review 52, LONGRUN). Its
        :meth:`replan` asks for a :meth:`plan` first, as a new planner's does.

        Pickle stores each view as an array of its own: ``_g``, ``_rhs`` and the
        heap's slots (columns of the node records) were pickled beside the
        records, and the heap whole although only the slots a search has
        reached hold anything but zeros (a fresh 1000² planner pickled to
        80 MB). Left out: the views, the heap's trailing zero slots (those
        past the deepest a search reached: the copy is bit for bit the
        original, slots a search left behind included), and the records of a
        planner that has not searched yet (``_clean``: as :func:`node_records`
        makes them), and the calls under way (a copy is not in use).
        :meth:`__setstate__` makes them again. Also pickle protocols 0 and 1
        need a ``__getstate__`` (see :func:`slot_state`).
        """
        # one_caller's guard, written out (its message names a copy).
        callers = self._callers
        token = (get_ident(), "__getstate__", object())
        try:
            callers.append(token)
            # Whether a call that writes the search is under way, decided as the token
            # goes in: such a call runs only as the first token and stays first until
            # it returns, and none starts behind this token. Another copy first only
            # reads, so this copy keeps the search (review 54: the second of two
            # threads' copies taken at once had none). Decided after the snapshot, as
            # it was, a call that ended during it left this token first, and the copy
            # kept what the call had half written.
            busy = callers[0][1] != "__getstate__"
            instance, kept = self._snapshot()
            if busy:
                # A call under way: its search may be half-written. The costs stay (a
                # cost update writes them holding the GIL); the search goes, as if
                # the copy had never searched (see _reset and __init__).
                kept.pop("_vals", None)
                nodes, keys, _ = kept["_heap"]
                kept["_heap"] = (nodes[:0], keys[:0], 0)
                kept.update(_clean=True, _km=0.0, _fresh=True, _start=None, _goal=None)
                kept.update(_cached=None, _lowered=False)
                kept["_work"] = np.array([0, 0, *_EMPTY_BOX], dtype=np.int64)
                kept["_changed"] = np.zeros_like(self._changed)
            return instance, kept
        finally:
            callers.remove(token)

    def _snapshot(self) -> tuple[Any, dict[str, Any]]:
        """:meth:`__getstate__` inside its guard: the state, every array copied."""
        instance, slots = cast("tuple[Any, dict[str, Any]]", slot_state(self))
        kept = {
            name: value.copy() if isinstance(value, np.ndarray) else value
            for name, value in slots.items()
            if name not in ("_g", "_rhs", "_heap", "_vals", "_callers")
        }
        nodes, keys, _, size = self._heap
        # Bits, not values: a key of -0.0 is kept.
        written = np.flatnonzero((nodes != 0) | (keys.view(np.int64) != 0).any(axis=1))
        used = int(written[-1]) + 1 if written.size else 0
        # (nodes, keys, size): three items, where pickles of earlier versions hold
        # (nodes, keys, pos, size) whole.
        kept["_heap"] = (nodes[:used].copy(), keys[:used].copy(), int(size[0]))
        if not self._clean:
            kept["_vals"] = self._vals.copy()
        return instance, kept

    def __setstate__(self, state: Any) -> None:
        # Copies (copy.deepcopy, pickle) hand back what __getstate__ kept: the node
        # records and the heap are made again (node_records: the keys cache-line
        # aligned, as a fresh planner's) and filled from the copies, so that g, rhs
        # and the heap's slots are views of the records again. A subclass's own
        # attributes (the state's instance __dict__) are restored too. Pickles made
        # before the records hold g, rhs and the slots as arrays of their own; those
        # made before __getstate__ the records, g, rhs and the heap whole.
        instance, slots = state if isinstance(state, tuple) else (None, state)
        slots = dict(slots)
        if "_work" not in slots:
            # Made before the search's work records (6de62f3, the project's first day):
            # a different search state, not carried over (review 51: it raised
            # KeyError here).
            raise ValueError(
                f"{type(self).__name__}: a pickle made by navkit before its search kept "
                "work records (6de62f3, 30 November 2026) cannot be restored; build the "
                "planner again from its costs"
            )
        old_vals = slots.pop("_vals", None)
        old_g, old_rhs = slots.pop("_g", None), slots.pop("_rhs", None)
        old_heap = slots.pop("_heap")
        vals, heap = _search_state(int(slots["_nrows"]) - 1, int(slots["_ncols"]) - 1)
        if len(old_heap) == 3:
            nodes, keys, size = old_heap
            heap[0][: len(nodes)] = nodes
            heap[1][: len(nodes)] = keys
            heap[3][0] = size
            if old_vals is not None:
                vals[:] = old_vals
        else:
            nodes, keys, pos, size = old_heap
            if old_vals is None:
                vals[:, G] = old_g
                vals[:, RHS] = old_rhs
                heap[2][:] = pos
            else:
                vals[:] = old_vals
            heap[0][:] = nodes
            heap[1][:] = keys
            heap[3][:] = size
        # Pickles made before start_tolerance: no obstacle mask, no escape; before
        # exact world ends: no world points (paths end at the round-tripped nodes).
        slots.setdefault("_obstacles", None)
        slots.setdefault("_escape", None)
        # Not in use, whatever the original was doing as it was copied (another thread's call).
        slots["_callers"] = []
        slots.setdefault("_start_xy", None)
        slots.setdefault("_goal_xy", None)
        work = np.asarray(slots["_work"], dtype=np.int64)
        if work.shape[0] == 2:
            # Pickles made before the box of written records (see _blank): the whole
            # grid, unless the planner never searched.
            every = (0, int(slots["_nrows"]) - 1, 0, int(slots["_ncols"]) - 1)
            box = _EMPTY_BOX if slots.get("_clean", False) else every
            slots["_work"] = np.array([*work, *box], dtype=np.int64)
        restore_slots(self, (instance, slots))
        self._vals, self._heap = vals, heap
        self._g, self._rhs = vals[:, G], vals[:, RHS]
        if self._obstacles is not None:
            # As in __init__: a planner unpickled in a fresh process (a sweep's worker)
            # paid the import of scipy.ndimage at its first escape, in the control loop.
            import scipy.ndimage  # noqa: F401

    def __copy__(self) -> FieldDStar:
        # update_costs() and every search write the costs and the search state in
        # place: a shallow copy sharing them would change this planner's costs
        # without queueing the change here, and its replans would no longer match
        # fresh plans. copy.copy copies them too, as OccupancyGrid's does.
        return copy.deepcopy(self)

    # ------------------------------------------------------------ properties
    @property
    def shape(self) -> tuple[int, int]:
        """Cell grid shape ``(rows, cols)``; the node grid is one larger in each axis."""
        return self._rows, self._cols

    @property
    def costs(self) -> FloatArray:
        """Copy of the current cell costs, shape ``(rows, cols)``."""
        out: FloatArray = self._pad.reshape(self._rows + 2, self._cols + 2)[1:-1, 1:-1].copy()
        return out

    @property
    def interpolate(self) -> bool:
        """Whether the planner is Field D* (True) or 8-connected D* Lite (False)."""
        return self._interp

    @property
    def lookahead(self) -> bool:
        """Whether the path extraction looks one step ahead."""
        return self._lookahead

    @property
    def smooth(self) -> bool:
        """Whether paths get the cost-never-increasing shortcut pass."""
        return self._smooth

    @property
    def resolution(self) -> float:
        """Cell side, m."""
        return self._resolution

    @property
    def origin(self) -> Pose2D:
        """World pose of node ``(0, 0)``."""
        return self._origin

    def __repr__(self) -> str:
        return (
            f"{type(self).__name__}(<{self._rows}x{self._cols} costs>, interpolate={self._interp}, "
            f"lookahead={self._lookahead}, smooth={self._smooth}, "
            f"resolution={self._resolution}, origin={self._origin!r})"
        )

    # ------------------------------------------------------------ conversions
    @overload
    def world_to_node(
        self, points_xy: ArrayLike, *, continuous: Literal[False] = False
    ) -> IntArray: ...

    @overload
    def world_to_node(self, points_xy: ArrayLike, *, continuous: Literal[True]) -> FloatArray: ...

    @overload
    def world_to_node(self, points_xy: ArrayLike, *, continuous: bool) -> IntArray | FloatArray: ...

    def world_to_node(
        self, points_xy: ArrayLike, *, continuous: bool = False
    ) -> IntArray | FloatArray:
        """Nodes nearest to world points ``(x, y)``, or their node coordinates.

        Parameters
        ----------
        points_xy : array_like, shape (2,) or (N, 2)
            World points in m, finite, ``|x|, |y| <= 1e9``.
        continuous : bool, default False
            Return float node coordinates ``(i, j)`` (node ``(i, j)`` at integer
            values) instead of the nearest node.

        Returns
        -------
        ndarray, shape (2,) or (N, 2)
            int64 nodes (each coordinate rounded half up) or float64 node
            coordinates; same leading shape as ``points_xy``. Not clipped to the
            node grid.

        Raises
        ------
        ValueError
            Bad shape, non-finite points or points beyond ±1e9 m.
        TypeError
            Non-numeric points or a non-bool ``continuous``.

        Examples
        --------
        >>> planner = FieldDStar(np.ones((4, 4)), resolution=0.5, origin=(1.0, 0.0, 0.0))
        >>> planner.world_to_node((1.6, 1.2)).tolist()
        [2, 1]
        >>> planner.world_to_node([[1.6, 1.2]], continuous=True).tolist()
        [[2.4, 1.2]]
        """
        pts, single = as_pairs(points_xy, "points_xy")
        _check_range(pts, COORDINATE_LIMIT, "points_xy", "m")
        o = self._origin
        c = math.cos(o.theta)
        s = math.sin(o.theta)
        inv_res = 1.0 / self._resolution
        dx = pts[:, 0] - o.x
        dy = pts[:, 1] - o.y
        # Local frame of the grid: x along columns, y along rows. The operations of
        # OccupancyGrid.world_to_cell (times 1 / resolution, not divided by it), so a
        # point on a cell edge falls in the same cell as in the map the costs come
        # from (0.3 / 0.1 < 3 but 0.3 * (1 / 0.1) > 3).
        nodes = np.empty_like(pts)
        # Products of a tiny offset and a tiny sine underflow to 0, as under NumPy's
        # defaults, whatever the caller's np.seterr.
        with np.errstate(under="ignore"):
            nodes[:, 0] = (-s * dx + c * dy) * inv_res
            nodes[:, 1] = (c * dx + s * dy) * inv_res
        out: FloatArray | IntArray = (
            nodes if as_bool(continuous, "continuous") else round_half_up(nodes)
        )
        return one_or_many(out, single)

    def node_to_world(self, nodes: ArrayLike) -> FloatArray:
        """World points ``(x, y)`` of nodes ``(i, j)`` (float node coordinates accepted).

        Parameters
        ----------
        nodes : array_like, shape (2,) or (N, 2)
            Nodes or node coordinates (not checked against the node grid),
            finite and within ``±2**53``.

        Returns
        -------
        ndarray of float64, shape (2,) or (N, 2)
            World points in m; same leading shape as ``nodes``.

        Raises
        ------
        TypeError
            Non-numeric ``nodes``.
        ValueError
            ``nodes`` of another shape, with NaN or inf, or beyond ``±2**53``.

        Examples
        --------
        >>> planner = FieldDStar(np.ones((4, 4)), resolution=0.5, origin=(1.0, 0.0, 0.0))
        >>> planner.node_to_world((2, 1)).tolist()
        [1.5, 1.0]
        """
        pts, single = as_pairs(nodes, "nodes")
        _check_range(pts, _NODE_LIMIT, "nodes", "(2**53)")
        out = self._origin.transform_points(pts[:, ::-1] * self._resolution)
        return one_or_many(out, single)

    # ------------------------------------------------------------ planning
    @one_caller
    def plan(self, start_node: ArrayLike, goal_node: ArrayLike) -> Path2D:
        """Search from scratch and return the path from ``start_node`` to ``goal_node``.

        Parameters
        ----------
        start_node, goal_node : (2,) int
            Nodes ``(i, j)`` with ``0 <= i <= rows`` and ``0 <= j <= cols``, each a
            corner of at least one passable cell.

        Returns
        -------
        Path2D
            ``"grid"`` path: its points, shape (K, 2), are node − 0.5 (continuous
            cell coordinates), from ``start_node`` to ``goal_node``; its cost
            (cost units × cells) is that of the polyline itself (the integral of
            the cell cost along it, a stretch along a grid line paying the
            cheaper cell beside it), not the search's interpolated estimate; its
            length is in cells; ``expanded`` counts node expansions.

        Raises
        ------
        ValueError
            A node off the node grid or surrounded by impassable cells; a path
            cost of ``2**52`` or more (see the class Notes).
        TypeError
            Nodes that are not pairs of integers.
        navkit.NoPathError
            The goal cannot be reached from the start.
        KeyboardInterrupt
            Or any other exception from outside the planner raised part-way
            (a signal handler's): the planner then holds these ends, whose
            search the next :meth:`replan` completes, or no plan (a replan
            raises ``RuntimeError`` until the next plan); never a mix of the
            two plans.
        RuntimeError
            Another call of this planner is under way (another thread's, or a
            signal handler's in the same thread): one call at a time, see the
            class notes; nothing is changed.

        Examples
        --------
        On uniform costs the path is the straight line between the corners,
        at any angle:

        >>> planner = FieldDStar(np.ones((10, 10)))
        >>> path = planner.plan((0, 0), (10, 5))
        >>> path.points.tolist()
        [[-0.5, -0.5], [9.5, 4.5]]
        >>> round(path.cost, 6), round(float(np.hypot(10, 5)), 6)
        (11.18034, 11.18034)
        """
        s = self._node(start_node, "start_node")
        gl = self._node(goal_node, "goal_node")
        self._reset(s, gl, s, gl, start_on_node=True, goal_on_node=True)
        points, cost, length, expanded = self._search("node")
        return Path2D(points - 0.5, "grid", cost=cost, length=length, expanded=expanded)

    @one_caller
    def replan(self, start_node: ArrayLike | None = None) -> Path2D:
        """Repair the previous search after cost updates and return the new path.

        Parameters
        ----------
        start_node : (2,) int, optional
            New start node (the robot moved); the goal stays. Defaults to the
            previous start node.

        Returns
        -------
        Path2D
            As :meth:`plan`: the same path a fresh :meth:`plan` on the current
            costs returns, found with far fewer expansions after a local change.
            After :meth:`plan_cells` (and no ``start_node``) the node part of
            the path a fresh plan_cells returns: from the start cell's chosen
            corner to where it meets the goal cell's boundary.

        Raises
        ------
        RuntimeError
            No plan was made yet, or another call of this planner is under way
            (another thread's, or a signal handler's in the same thread: one
            call at a time, see the class notes; nothing is changed).
        ValueError
            A ``start_node`` not of length 2, off the node grid or a corner of
            impassable cells only; the kept start node (without
            ``start_node``) or the kept goal node is now such a corner (the
            start checked first, as a fresh :meth:`plan` refuses them), or a
            cell kept from :meth:`plan_cells` is impassable; a path cost of
            ``2**52`` or more.
        TypeError
            A ``start_node`` that is not a pair of integers.
        navkit.NoPathError
            The goal cannot be reached any more.
        KeyboardInterrupt
            Or any other exception from outside the planner raised part-way
            (a signal handler's): the planner keeps its plan and the next
            replan completes the repair, unless a hopeless repair was being
            replaced by a fresh search: then it holds no plan (a replan raises
            ``RuntimeError`` until the next plan).

        Examples
        --------
        >>> planner = FieldDStar(np.ones((10, 10)))
        >>> first = planner.plan((0, 0), (10, 5))
        >>> planner.update_costs([(4, 1), (4, 2), (4, 3)], np.inf)  # a wall appears
        >>> again = planner.replan()
        >>> again.points.tolist()
        [[-0.5, -0.5], [4.5, 0.5], [9.5, 4.5]]

        The path of a fresh search, found with fewer expansions:

        >>> fresh = FieldDStar(planner.costs).plan((0, 0), (10, 5))
        >>> round(again.cost, 9) == round(fresh.cost, 9), again.expanded < fresh.expanded
        (True, True)
        >>> planner.replan((2, 0)).points.tolist()  # the robot moved 2 rows
        [[1.5, -0.5], [4.5, 0.5], [9.5, 4.5]]
        """
        self._require_plan("replan")
        assert self._start is not None and self._goal is not None
        # Every check before any state changes, in the order of plan(): a refused
        # replan leaves the planner as it was.
        if start_node is not None:
            s = self._node(start_node, "start_node")
        else:
            s = self._start
            self._check_kept_node(s, "start_node", None, self._start_cell)
        self._check_kept_node(self._goal, "goal_node", None, self._goal_cell)
        if start_node is not None:
            # The point before the move, so that no call (where Python delivers a
            # KeyboardInterrupt) separates the new start from its point: a start
            # moved without it would make a later replan_world() link the old
            # point to the new start node, a path of neither plan.
            point = (float(s[0]), float(s[1]))
            self._move_start(s)
            self._start_point = point
            self._start_xy = None
            self._start_on_node = True
            self._escape = None
        points, cost, length, expanded = self._search("node")
        return Path2D(points - 0.5, "grid", cost=cost, length=length, expanded=expanded)

    @one_caller
    def plan_cells(self, start_cell: CellLike, goal_cell: CellLike) -> Path2D:
        """Path from the centre of ``start_cell`` to the centre of ``goal_cell``.

        Field D* plans between cell corners; the segment from a cell's centre
        to any of its four corners lies inside the cell and costs half a
        diagonal times the cell's cost. The link corners are chosen by cost:
        the search starts from all four corners of the goal cell at once, each
        valued at its segment's cost (a virtual goal at the centre), and the
        path runs from the start cell's centre to its corner of least
        cost-to-goal, down the cost field until it meets the goal cell's
        boundary (at a corner or inside an edge), and straight on to the goal
        cell's centre. Start corners whose cost-to-goal ties the least (to a
        relative 1e-9) are all walked and the cheapest linked path kept (ties:
        the first of the corners ``(0, 0), (0, 1), (1, 0), (1, 1)`` from the
        cell). The whole polyline then gets the cost-never-increasing shortcut
        pass (when ``smooth``). A search from scratch, like :meth:`plan`; a
        later :meth:`replan_world` or :meth:`replan` keeps the two cells (the
        start corner is chosen again on the repaired values) until a new start
        is given.

        So the linked cost-to-goal is the least over all 16 corner pairs, and
        mirroring the grid or turning it by quarter turns gives the same node
        values and link corners up to rounding. The extracted path's cost
        carries the caveats of the class Notes (the walk is not exact, the
        shortcut pass is greedy): in random tests on small cost grids (holes,
        inflated cost bands) its cost was above that of the cheapest of the
        16 corner pairs forced through :meth:`plan` plus the two end segments
        in 27 of 22,853 queries, by at most 2 % (the start corner is chosen
        by its interpolated value, which can rank two corners otherwise than
        the paths walked from them), and without smoothing (with
        ``lookahead``) it was up to 4 % above in about 1 % of the queries
        (grids up to 9 × 9; an earlier sample of 5,479 had shown 3 queries
        above, by 0.6 %). Without both smoothing and ``lookahead`` the walk
        can be much dearer where costs differ by large factors (43 % in one
        test with costs of 1 and 1000).
        The position rule used before (the corner nearest the other centre)
        cost up to 20 % more in such tests.

        Parameters
        ----------
        start_cell, goal_cell : (int, int)
            Passable cells ``(row, col)``.

        Returns
        -------
        Path2D
            ``"grid"`` path from centre to centre (integers at cell centres) with
            the exact cost of the polyline (cost units × cells), its length in
            cells and the node expansions. Equal cells give the one-point path of
            cost 0 (no search).

        Raises
        ------
        ValueError
            A cell outside the grid or impassable; a path cost of ``2**52`` or
            more.
        TypeError
            Non-integer cells.
        navkit.NoPathError
            The goal cell cannot be reached.
        KeyboardInterrupt
            Part-way: as for :meth:`plan`.
        RuntimeError
            Another call of this planner is under way (another thread's, or a
            signal handler's in the same thread): one call at a time, see the
            class notes; nothing is changed.

        Examples
        --------
        >>> costs = np.ones((10, 10))
        >>> costs[2:8, 4] = np.inf
        >>> path = FieldDStar(costs).plan_cells((5, 0), (5, 9))
        >>> path.points[[0, -1]].tolist()
        [[5.0, 0.0], [5.0, 9.0]]
        >>> path.cells[[0, -1]].tolist()
        [[5, 0], [5, 9]]
        """
        s = self._passable_cell(start_cell, "start_cell")
        gl = self._passable_cell(goal_cell, "goal_cell")
        # The cells' lower-left corner nodes are (row, col) themselves; the ends are the centres.
        self._reset(s, gl, (s[0] + 0.5, s[1] + 0.5), (gl[0] + 0.5, gl[1] + 0.5),
                    start_cell=True, goal_cell=True)
        if s == gl:  # no search, but the goal is recorded for replan_world
            return Path2D(np.array([s], dtype=np.float64), "grid", cost=0.0, length=0.0, expanded=0)
        points, _, _, expanded = self._search("cell")
        points, cost, length = self._linked(points)
        return Path2D(points - 0.5, "grid", cost=cost, length=length, expanded=expanded)

    @one_caller
    def plan_world(
        self, start_xy: ArrayLike, goal_xy: ArrayLike, *, start_tolerance: float = 0.0
    ) -> Path2D:
        """Path between two world points, from scratch.

        Each point is linked to its nearest node (:meth:`world_to_node`), a
        corner of the cell that contains it, by a straight segment inside that
        cell; Field D* plans between the two nodes; the linked polyline gets the
        shortcut pass when ``smooth``. A later :meth:`replan_world` repairs this
        search.

        Parameters
        ----------
        start_xy, goal_xy : array_like, shape (2,)
            World points ``(x, y)`` in m, each inside a passable cell (the
            start, with ``start_tolerance``, possibly in the inflation). A
            pose ``(x, y, theta)`` is refused with the hint to pass its
            ``[:2]``, as by every ``_xy`` argument (the README's conventions);
            :meth:`MapPlanner.plan`, whose ``start`` and ``goal`` have no
            suffix, takes a robot's pose too.
        start_tolerance : float, default 0.0
            Distance in m, in ``[0, 1e9]`` (keyword-only), within which a
            start in an impassable cell that is not an obstacle (see
            ``obstacles`` of :class:`FieldDStar`: a robot whose state
            estimate drifted into the inflated band around a wall) may escape,
            as :meth:`MapPlanner.plan`'s: the path begins at ``start_xy``
            itself, goes straight to the centre of the nearest passable cell
            (the escape cell: least distance from ``start_xy`` to its centre,
            at most ``start_tolerance``; ties, equal distances in the grid's
            float64 continuous coordinates, to the lowest ``(row, col)``)
            and follows the path :meth:`plan_world` plans from that centre
            (linked to its nearest node). Only cells whose straight segment
            from ``start_xy`` touches no obstacle cell's square (a corner
            included) qualify; a segment passing within ``1e-9`` cell sides
            of such a square (its corner, say) counts as touching it, so that
            rounding never lets one through. It may cross the inflation.
            ``0`` (the default) never escapes: such a start is refused, as
            are starts in an obstacle (every impassable cell without ``obstacles``) or
            outside the grid, whatever the tolerance. The goal never escapes.

        Returns
        -------
        Path2D
            ``"world"`` path from ``start_xy`` to ``goal_xy``: its first and last
            points are the points given, exactly (as float64); cost in cost
            units × metres: the exact cost of the polyline in node coordinates
            (whose ends, mapped back to world points, can differ from the
            points given by a rounding step) times the resolution; length in
            m, that of the points returned (as every world path's:
            :meth:`MapPlanner.plan`'s, :meth:`Path2D.to_world`'s), which can
            differ from the node polyline's times the resolution in the last
            bits. Equal points give a one-point path of cost 0.
            After an escape the points are ``start_xy``, then the path from
            the escape cell's centre; ``length`` includes the escape segment
            and ``cost`` its cost: for each cell it crosses, the length inside
            the cell × the cell's cost, an impassable (inflation) cell
            counting 5 (``1 + cost_weight`` of
            :func:`~navkit.mapping.traversal_costs`, as :class:`MapPlanner`).

        Raises
        ------
        ValueError
            A point outside the grid or in an impassable cell (the start in
            the inflation only with no escape within ``start_tolerance``; the
            message says whether it is in an obstacle or in the inflation,
            when ``obstacles`` tells), not finite or beyond ±1e9 m; a path
            cost of ``2**52`` or more; ``start_tolerance`` negative, not
            finite or above 1e9.
        TypeError
            Non-numeric points; ``start_tolerance`` not a real number (or a
            bool).
        navkit.NoPathError
            The goal cannot be reached.
        KeyboardInterrupt
            Part-way: as for :meth:`plan`.
        RuntimeError
            Another call of this planner is under way (another thread's, or a
            signal handler's in the same thread): one call at a time, see the
            class notes; nothing is changed.

        Examples
        --------
        Cells of 0.5 m, node ``(0, 0)`` at (1, 2); on uniform costs the path is
        straight and its cost equals its length:

        >>> planner = FieldDStar(np.ones((10, 10)), resolution=0.5, origin=(1.0, 2.0, 0.0))
        >>> path = planner.plan_world((1.25, 2.25), (5.75, 4.25))
        >>> path.frame, path.points.round(6).tolist()
        ('world', [[1.25, 2.25], [5.75, 4.25]])
        >>> round(path.length, 6), round(path.cost, 6), round(float(np.hypot(4.5, 2.0)), 6)
        (4.924429, 4.924429, 4.924429)

        On a map's costs, with its obstacles: a start that drifted into the
        inflated band around a wall is refused, unless it may escape to a
        passable cell within ``start_tolerance``:

        >>> from navkit.mapping import OccupancyGrid
        >>> occupied = np.zeros((10, 20), dtype=bool)
        >>> occupied[:6, 10] = True
        >>> grid = OccupancyGrid.from_occupancy(occupied, resolution=0.1)
        >>> planner = FieldDStar(grid.traversal_costs(robot_radius=0.2), resolution=0.1,
        ...                      obstacles=grid.occupied())
        >>> planner.plan_world((0.85, 0.25), (1.55, 0.25))
        Traceback (most recent call last):
            ...
        ValueError: start_xy (0.85, 0.25) is in an impassable cell (2, 8) (cost inf), within ...
        >>> escaped = planner.plan_world((0.85, 0.25), (1.55, 0.25), start_tolerance=0.2)
        >>> escaped.points[:2].round(6).tolist()  # the start, then the escape cell's centre
        [[0.85, 0.25], [0.75, 0.25]]
        """
        tolerance = bounded_float(start_tolerance, "start_tolerance", 0.0, COORDINATE_LIMIT, "m")
        given, _, where = self._world_point(start_xy, "start_xy")
        p_s, s, escape = self._start_end(given, where, tolerance, "")
        p_g, gl, goal_at = self._world_end(goal_xy, "goal_xy")
        self._reset(s, gl, p_s, p_g, escape=escape, start_xy=where, goal_xy=goal_at)
        points, _, _, expanded = self._search("xy")
        return self._world_path(points, expanded)

    @one_caller
    def replan_world(
        self, start_xy: ArrayLike | None = None, *, start_tolerance: float = 0.0
    ) -> Path2D:
        """Repair the previous search after cost updates; world-point form of :meth:`replan`.

        Parameters
        ----------
        start_xy : array_like, shape (2,), optional
            The robot's new position ``(x, y)`` in m (linked to its nearest node
            as in :meth:`plan_world`); the goal stays. Defaults to the previous
            start point (after an escape, the point given, not the escape
            cell: escaped again, or not, on the current costs).
        start_tolerance : float, default 0.0
            As in :meth:`plan_world` (keyword-only), for ``start_xy`` or a
            kept start point that escaped or whose cell :meth:`update_costs`
            closed with ``obstacles=False``: a robot tracking a path along the
            edge of the inflated band a few centimetres off replans from where
            it is. Any other kept start is checked as before: a world point
            whose cell :meth:`update_costs` closed as an obstacle (its
            default), a node (:meth:`plan`, :meth:`replan`) or a cell
            (:meth:`plan_cells`) never escapes. The search moves its
            start to the escape cell's node, as for any new start, and its
            repair stays equal to a fresh :meth:`plan_world` from
            ``start_xy`` with this tolerance.

        Returns
        -------
        Path2D
            ``"world"`` path from the start point to the goal point of the last
            plan (the goal node itself after :meth:`plan`, the goal cell's
            centre after :meth:`plan_cells`), linked to the same goal node.
            World points given (``start_xy``, the kept start and goal of
            :meth:`plan_world` or this method, an escaped start) are its first
            and last points exactly, cost and length as in :meth:`plan_world`.
            Equal to a fresh search between the same nodes on the current
            costs: after :meth:`plan_world`, to what a fresh
            :meth:`plan_world` returns. After :meth:`plan_cells` the goal
            stays the goal cell's centre linked to its four corners (and,
            without ``start_xy``, the start the start cell's centre): the
            path a fresh :meth:`plan_cells` returns, or with ``start_xy`` a
            fresh plan_cells followed by this start move; a fresh
            plan_world, linking the centre to its nearest node, may differ.

        Raises
        ------
        RuntimeError
            No plan was made yet, or another call of this planner is under way
            (another thread's, or a signal handler's in the same thread: one
            call at a time, see the class notes; nothing is changed).
        ValueError
            ``start_xy`` outside the grid or in an impassable cell (the
            inflation with no escape within ``start_tolerance``); the kept
            start point (without ``start_xy``) or the kept goal point is no
            longer valid (the start checked first): a point given to
            :meth:`plan_world` or :meth:`plan_cells` whose cell is now
            impassable (as a fresh :meth:`plan_world` refuses it, a point
            exactly on a node too), a node given to :meth:`plan` or
            :meth:`replan` that is now a corner of impassable cells only (as a
            fresh :meth:`plan` refuses it); a path cost of ``2**52`` or more;
            a bad ``start_tolerance`` (as :meth:`plan_world`).
        TypeError
            Non-numeric ``start_xy``; ``start_tolerance`` not a real number.
        navkit.NoPathError
            The goal cannot be reached any more.
        KeyboardInterrupt
            Part-way: as for :meth:`replan`.

        Examples
        --------
        >>> planner = FieldDStar(np.ones((10, 10)), resolution=0.5)
        >>> first = planner.plan_world((0.25, 0.25), (4.75, 0.25))
        >>> planner.update_costs([(0, 5), (1, 5)], np.inf)
        >>> first.length
        4.5
        >>> detour = planner.replan_world((0.75, 0.25))  # the robot moved 0.5 m
        >>> detour.points[0].tolist(), round(detour.length, 3)  # straight: 4.0 m
        ([0.75, 0.25], 4.308)

        A robot that drifted into the inflated band replans from where it is:

        >>> from navkit.mapping import OccupancyGrid
        >>> occupied = np.zeros((10, 20), dtype=bool)
        >>> occupied[:6, 10] = True
        >>> grid = OccupancyGrid.from_occupancy(occupied, resolution=0.1)
        >>> planner = FieldDStar(grid.traversal_costs(robot_radius=0.2), resolution=0.1,
        ...                      obstacles=grid.occupied())
        >>> first = planner.plan_world((0.25, 0.25), (1.55, 0.25))
        >>> drifted = planner.replan_world((0.85, 0.45), start_tolerance=0.1)
        >>> drifted.points[:2].round(6).tolist()
        [[0.85, 0.45], [0.75, 0.45]]
        """
        self._require_plan("replan_world")
        assert self._start is not None and self._goal is not None
        assert self._start_point is not None and self._goal_point is not None
        tolerance = bounded_float(start_tolerance, "start_tolerance", 0.0, COORDINATE_LIMIT, "m")
        # Every check before any state changes: a refused replan leaves the planner as it was.
        kept = start_xy is None
        if start_xy is not None:
            given, _, where = self._world_point(start_xy, "start_xy")
            p_s, s, escape = self._start_end(given, where, tolerance, "")
        elif self._escape is not None:
            # The point given last, not the escape cell: escaped again (or not) on
            # the current costs with this call's tolerance.
            given = self._escape[0]
            where = self._world_of(given, self._start_xy)
            p_s, s, escape = self._start_end(given, where, tolerance, " (kept from the last plan)")
        elif self._kept_in_inflation():
            # A world point whose cell update_costs() closed as inflation
            # (obstacles=False): it escapes as the same point given would.
            given = self._start_point
            where = self._world_of(given, self._start_xy)
            p_s, s, escape = self._start_end(given, where, tolerance, " (kept from the last plan)")
        else:
            # A kept start that did not escape: its cell was passable, so one closed
            # since is a cell update_costs() closed, an obstacle to the escape (unless
            # closed as inflation, above).
            self._check_kept_end(
                self._start_point, self._start, self._start_on_node, "start_xy", self._start_xy
            )
            kept = False
        self._check_kept_end(
            self._goal_point, self._goal, self._goal_on_node, "goal_xy", self._goal_xy
        )
        if start_xy is not None or kept:
            # Plain assignments after the move: no call (where Python delivers a
            # KeyboardInterrupt) separates the new start from its point and escape.
            self._move_start(s)
            self._start_point = p_s
            self._start_xy = where
            self._start_on_node = False
            self._escape = escape
        points, _, _, expanded = self._search("xy")
        return self._world_path(points, expanded)

    @one_caller
    def update_costs(
        self, cells: ArrayLike, new_costs: ArrayLike, *, obstacles: ArrayLike | None = None
    ) -> None:
        """Change the cost of some cells; the next :meth:`replan` repairs the plan.

        Parameters
        ----------
        cells : (M, 2) or (2,) int array_like
            Cells ``(row, col)`` to change (integers; integral floats such as
            ``2.0`` are accepted). With repeats, the last value wins.
        new_costs : float or (M,) array_like
            New costs per unit length (as ``costs``), in ``[1, 1e12]`` or
            ``np.inf`` (impassable); a float sets every cell listed.
        obstacles : bool or (M,) array_like of bool, optional
            Keyword-only: which of the cells are obstacles (``True``) or only
            the inflation drawn around them (``False``), for the world
            methods' ``start_tolerance`` (see ``obstacles`` of
            :class:`FieldDStar`); a bool sets every cell listed, and only an
            impassable cell may be an obstacle. ``None`` (the default): a cell
            closed here counts as an obstacle, a cell opened does not, a cell
            impassable before and after keeps its kind. Block a new
            obstacle's cells and the ring around them in two calls, the ring
            with ``obstacles=False``, so that a robot that drifts into the
            ring may escape it. On a planner built without ``obstacles``,
            every other impassable cell counts as an obstacle.

        Raises
        ------
        ValueError
            Cells outside the grid or not integral, mismatched lengths, or costs
            that are NaN, ``-inf``, below 1 or finite above 1e12; ``obstacles``
            of another length or marking a cell whose new cost is finite.
        TypeError
            Cells or costs that are not real numbers (booleans, strings,
            complex numbers, mappings); ``obstacles`` not boolean.
        RuntimeError
            Another call of this planner is under way (another thread's, or a
            signal handler's in the same thread): one call at a time, see the
            class notes; nothing is changed.

        Examples
        --------
        >>> planner = FieldDStar(np.ones((3, 4)))
        >>> before = planner.plan((0, 0), (3, 4))
        >>> planner.update_costs([(1, 1), (1, 2)], [5.0, np.inf])
        >>> planner.costs[1].tolist()
        [1.0, 5.0, inf, 1.0]
        >>> planner.update_costs([(1, 1), (1, 1)], [3.0, 2.0])  # repeated: the last wins
        >>> planner.costs[1].tolist()
        [1.0, 2.0, inf, 1.0]
        >>> before.cost, bool(planner.replan().cost > before.cost)  # straight line blocked
        (5.0, True)

        A new obstacle and the ring grown around it: a start in the ring may
        escape it (``start_tolerance``), one in the obstacle's cell never:

        >>> planner = FieldDStar(np.ones((5, 5)), obstacles=np.zeros((5, 5), dtype=bool))
        >>> ring = [(r, c) for r in range(1, 4) for c in range(1, 4) if (r, c) != (2, 2)]
        >>> planner.update_costs(ring, np.inf, obstacles=False)
        >>> planner.update_costs([(2, 2)], np.inf)  # an obstacle: closed here
        >>> planner.plan_world((1.5, 1.2), (4.5, 4.5), start_tolerance=1.0).points[:2].tolist()
        [[1.5, 1.2], [1.5, 0.5]]
        """
        idx = self._update_cells(cells)
        vals = as_float_array(new_costs, "new_costs", finite=False)
        if vals.ndim == 0:
            vals = np.full(idx.shape[0], float(vals))
        if vals.shape != (idx.shape[0],):
            raise ValueError(
                f"new_costs must be a scalar or have shape ({idx.shape[0]},), got {vals.shape}"
            )
        bad = ~((vals >= 1.0) & ((vals <= MAX_COST) | (vals == np.inf)))
        if bad.any():
            raise ValueError(
                f"new_costs must be >= 1 and <= {MAX_COST:g}, or np.inf (no NaN, no -inf); "
                f"got {float(vals[bad][0])}"
            )
        flags = None if obstacles is None else _obstacle_flags(obstacles, idx, vals)
        if idx.shape[0] == 0:
            return
        # With repeats the last value wins: each cell's final value.
        flat = (idx[:, 0] + 1) * self._width + idx[:, 1] + 1
        cells_u, last = np.unique(flat[::-1], return_index=True)
        final = vals[::-1][last]
        mask = self._obstacles
        created = mask is None and flags is not None
        if created:
            # Built without obstacles: every impassable cell counted as one so far.
            mask = ~np.isfinite(self._pad.reshape(self._rows + 2, self._cols + 2)[1:-1, 1:-1])
            import scipy.ndimage  # noqa: F401  # it may escape from now on: see __init__
        kinds = None
        if mask is not None:
            rows = cells_u // self._width - 1
            cols = cells_u - (rows + 1) * self._width - 1
            if flags is None:
                # A cell closed here counts as an obstacle: the planner cannot tell a new
                # obstacle from the inflation drawn around it, and an escape must never
                # cross one. A cell opened is no obstacle; one closed before keeps its kind.
                closed = np.isfinite(self._pad[cells_u]) | mask[rows, cols]
                kinds = np.isinf(final) & closed
            else:
                kinds = flags[::-1][last]
            if not created and np.array_equal(mask[rows, cols], kinds):
                kinds = None
        # Only start_tolerance reads the kinds: the search state does not change. They
        # are written with the costs, so that an interrupted update (a MemoryError or a
        # KeyboardInterrupt below) marks no cell of finite cost as an obstacle.
        if np.array_equal(self._pad[cells_u], final):
            # No cost changes: the search state and the cached path stay valid.
            if kinds is not None:
                assert mask is not None
                mask[rows, cols] = kinds
                self._obstacles = mask
            return
        self._cached = None
        self._lowered = self._lowered or bool(np.any(final < self._pad[cells_u]))
        listed = int(self._changed[0])
        if listed > 2 * self._rows * self._cols:
            # Updated far more often than searched: cells listed again and again.
            # Keep each once, so the list (and the next repair's requeue) stays
            # bounded by the grid, not by the number of updates.
            kept = np.unique(self._changed[1 : listed + 1])
            self._changed[1 : kept.shape[0] + 1] = kept
            self._changed[0] = listed = kept.shape[0]
        added = cells_u.shape[0]
        if listed + added >= self._changed.shape[0]:
            grown = np.zeros(2 * (listed + added + 1), dtype=np.int64)
            grown[: listed + 1] = self._changed[: listed + 1]
            self._changed = grown
        # The costs are written now and the cells listed; the next search requeues
        # their corners (settle). NumPy, not a kernel: one compiled function fewer
        # on first use, and a few cells take microseconds either way.
        self._pad[cells_u] = final
        if kinds is not None:  # no call since the costs: no interrupt between them
            assert mask is not None
            mask[rows, cols] = kinds
            self._obstacles = mask
        self._changed[listed + 1 : listed + 1 + added] = cells_u
        self._changed[0] = listed + added

    # ------------------------------------------------------------ internals
    def _update_cells(self, cells: Any) -> IntArray:
        """``cells`` of :meth:`update_costs` as an (M, 2) int64 array inside the grid."""
        if isinstance(cells, (str, bytes, Mapping, set, frozenset)):
            raise TypeError(f"cells must be (row, col) pairs, got {type(cells).__name__}")
        raw = as_float_array(cells, "cells", finite=False)
        if is_ndarray(cells) and cells.dtype.kind in "iu":
            exact = np.asarray(cells, dtype=np.int64)  # no round trip through float64
        else:
            exact = None
        if raw.ndim == 1 and raw.shape[0] == 2:
            raw = raw.reshape(1, 2)
        if raw.size == 0:
            raw = raw.reshape(0, 2)
        if raw.ndim != 2 or raw.shape[1] != 2:
            raise ValueError(f"cells must have shape (M, 2) or (2,), got {raw.shape}")
        if not np.all(np.isfinite(raw)) or not np.all(raw == np.floor(raw)):
            raise ValueError("cells must hold integer (row, col) indices")
        inside = (
            (raw[:, 0] >= 0)
            & (raw[:, 0] < self._rows)
            & (raw[:, 1] >= 0)
            & (raw[:, 1] < self._cols)
        )
        if not inside.all():
            bad = raw[~inside][0]
            raise ValueError(
                f"cells {[int(v) for v in bad]} is outside the grid of shape {self.shape}"
            )
        if exact is not None:
            return exact.reshape(raw.shape)
        return raw.astype(np.int64)

    def _node(self, value: Any, name: str) -> tuple[int, int]:
        node = as_cell(value, name, (self._nrows, self._ncols))
        if self._enclosed(node):
            raise ValueError(
                f"{name} {node} is a corner of impassable cells only (node grid is "
                f"(rows + 1, cols + 1) = {(self._nrows, self._ncols)})"
            )
        return node

    def _enclosed(self, node: tuple[int, int]) -> bool:
        """Whether every cell around ``node`` is impassable (or off the grid)."""
        i, j = node
        around = self._pad.reshape(self._rows + 2, self._cols + 2)[i : i + 2, j : j + 2]
        return not bool(np.isfinite(around).any())

    def _check_kept_node(
        self,
        node: tuple[int, int],
        name: str,
        where: tuple[float, ...] | None,
        cell: bool = False,
    ) -> None:
        """Refuse an end node kept from the last plan that :meth:`_node` would refuse now.

        After :meth:`update_costs` closed every cell around it, a search to or
        from it finds no path; a fresh :meth:`plan` refuses such a node with
        ``ValueError``, and a replan, equal to that fresh plan, does the same.
        ``where`` is the kept world point to name instead of the node
        (:meth:`replan_world`), or None. With ``cell`` the end is the cell
        ``node`` of :meth:`plan_cells`, refused once it is impassable (as a
        fresh :meth:`plan_cells` refuses it).
        """
        if cell:
            if not math.isfinite(self._cell_cost(*node)):
                raise ValueError(
                    f"{name}: the cell {node} kept from plan_cells() is impassable "
                    "since update_costs()"
                )
            return
        if self._enclosed(node):
            text = str(node) if where is None else str(where)
            raise ValueError(
                f"{name} {text} (kept from the last plan) is a corner of impassable cells "
                f"only since update_costs() (node grid is (rows + 1, cols + 1) = "
                f"{(self._nrows, self._ncols)})"
            )

    def _cell_cost(self, row: int, col: int) -> float:
        return float(self._pad[(row + 1) * self._width + col + 1])

    def _passable_cell(self, value: Any, name: str) -> tuple[int, int]:
        row, col = as_cell(value, name, (self._rows, self._cols))
        if not math.isfinite(self._cell_cost(row, col)):
            raise ValueError(f"{name} {(row, col)} is on an impassable cell (cost inf)")
        return row, col

    def _world_end(
        self, value: ArrayLike, name: str
    ) -> tuple[tuple[float, float], tuple[int, int], tuple[float, ...]]:
        """Node coordinates of a world point, its nearest node and the point given, checked."""
        p, (row, col), where = self._world_point(value, name)
        if not math.isfinite(self._cell_cost(row, col)):
            raise ValueError(f"{name} {where} is in an impassable cell {(row, col)} (cost inf)")
        return p, _nearest_node(p), where

    def _world_of(
        self, point: tuple[float, float], given: tuple[float, ...] | None
    ) -> tuple[float, ...]:
        """The world point of an end: the point given, else ``point`` (node coordinates) mapped."""
        if given is not None:
            return given
        return tuple(self.node_to_world(point).tolist())

    def _world_point(
        self, value: ArrayLike, name: str
    ) -> tuple[tuple[float, float], tuple[int, int], tuple[float, ...]]:
        """Node coordinates of a world point inside the grid, its cell and the point given."""
        point = as_point(value, name)
        _check_range(point, COORDINATE_LIMIT, name, "m")
        p = self.world_to_node(point, continuous=True)
        row, col = math.floor(p[0]), math.floor(p[1])
        where = tuple(point.tolist())
        if not (0 <= row < self._rows and 0 <= col < self._cols):
            raise ValueError(f"{name} {where} is outside the grid")
        return (float(p[0]), float(p[1])), (row, col), where

    def _start_end(
        self, p: tuple[float, float], where: tuple[float, ...], tolerance: float, kept: str
    ) -> tuple[tuple[float, float], tuple[int, int], tuple[tuple[float, float], float] | None]:
        """The start of a world search from point ``p`` (node coordinates, inside the grid).

        Returns the point the path is linked from, its nearest node and the
        escape (``p`` and the escape segment's cost) or None. ``p`` in a
        passable cell is its own start. In an impassable cell it may escape
        (``start_tolerance``, see :meth:`plan_world`) when that cell is not an
        obstacle: to the escape cell's centre, linked to its nearest node as
        :meth:`plan_world` links a point there. ``where``: the world point,
        and ``kept`` the words after it, for the refusals ("" for a point
        given, " (kept from the last plan)" for one kept).
        """
        cell = (math.floor(p[0]), math.floor(p[1]))
        if math.isfinite(self._cell_cost(*cell)):
            return p, _nearest_node(p), None
        text = f"start_xy {where}{kept} is in an impassable cell {cell} (cost inf)"
        hard = self._obstacles
        if hard is None:
            hint = (
                "; start_tolerance escapes only a FieldDStar given obstacles= (which "
                "impassable cells are obstacles, not the inflation around them)"
                if tolerance > 0.0
                else ""
            )
            raise ValueError(text + hint)
        if hard[cell]:
            raise ValueError(f"{text}, an obstacle")
        text += ", within the inflation around an obstacle"
        if tolerance == 0.0:
            raise ValueError(
                f"{text}; pass start_tolerance > 0 to escape to the nearest passable cell"
            )
        costs = self._pad.reshape(self._rows + 2, self._cols + 2)[1:-1, 1:-1]
        # Continuous cell coordinates (integers at cell centres), as MapPlanner's.
        found = nearest_escape(
            costs, hard, cell, (p[0] - 0.5, p[1] - 0.5), tolerance, self._resolution
        )
        if found is None:
            raise ValueError(
                f"{text}, and no passable cell centre within start_tolerance ({tolerance} m) "
                "can be reached in a straight line without crossing an obstacle"
            )
        (row, col), cost = found
        centre = (row + 0.5, col + 0.5)
        return centre, _nearest_node(centre), (p, cost)

    def _check_kept_end(
        self,
        point: tuple[float, float],
        node: tuple[int, int],
        on_node: bool,
        name: str,
        given: tuple[float, ...] | None,
    ) -> None:
        """Refuse an end kept from the last plan that a fresh plan would refuse now.

        An end given as a node (:meth:`plan`, :meth:`replan`) is checked as
        :meth:`_node` checks it. An end given as a point (:meth:`plan_world`,
        :meth:`plan_cells`) is linked to its node by a segment inside its cell
        (the cell :meth:`_world_end` checked), so after :meth:`update_costs`
        made that cell impassable the linked path would cost inf and a fresh
        :meth:`plan_world` refuses the point; this holds for a point exactly
        on a node too, whose cell is the one :meth:`_world_end` picks.
        ``given``: the world point given for the end (named in the refusal), or None.
        """
        if on_node:
            self._check_kept_node(node, name, self._world_of(point, given))
            return
        row, col = math.floor(point[0]), math.floor(point[1])
        if not math.isfinite(self._cell_cost(row, col)):
            where = self._world_of(point, given)
            raise ValueError(
                f"{name} {where} (kept from the last plan) is in an impassable cell "
                f"{(row, col)} (cost inf) since update_costs()"
            )

    def _kept_in_inflation(self) -> bool:
        """Whether the kept start is a world point in a cell the obstacle mask calls inflation.

        Such a start (given to :meth:`plan_world` or :meth:`replan_world`, not
        a node or a cell of :meth:`plan_cells`) whose cell :meth:`update_costs`
        closed with ``obstacles=False`` may escape, as the point given anew may.
        """
        if self._start_on_node or self._start_cell or self._obstacles is None:
            return False
        assert self._start_point is not None
        row, col = math.floor(self._start_point[0]), math.floor(self._start_point[1])
        return not math.isfinite(self._cell_cost(row, col)) and not self._obstacles[row, col]

    def _require_plan(self, method: str) -> None:
        if self._start is None or self._goal is None:
            raise RuntimeError(
                f"{method}() repairs a previous search: call plan(), plan_cells() or "
                "plan_world() first"
            )

    def _move_start(self, s: tuple[int, int]) -> None:
        assert self._start is not None
        # D* Lite: keys already queued stay lower bounds if km grows by h(old, new).
        self._km += _heuristic(self._start, s, self._hscale)
        self._start = s
        if self._start_cell:
            # The cached path ran from the start cell's best corner, not from node s.
            self._cached = None
            self._start_cell = False

    def _reset(
        self,
        s: tuple[int, int],
        gl: tuple[int, int],
        start_point: tuple[float, float],
        goal_point: tuple[float, float],
        *,
        start_cell: bool = False,
        goal_cell: bool = False,
        start_on_node: bool = False,
        goal_on_node: bool = False,
        escape: tuple[tuple[float, float], float] | None = None,
        start_xy: tuple[float, ...] | None = None,
        goal_xy: tuple[float, ...] | None = None,
    ) -> None:
        """Start a new search from node ``s`` to node ``gl`` (the path's end points given).

        With ``start_cell`` ``s`` is the start cell (its top-left corner): the
        walk starts at its corner of least cost-to-goal. With ``goal_cell``
        ``gl`` is the goal cell: its four corners are the sources, each valued
        at the cost of its segment from the centre. ``start_on_node`` and
        ``goal_on_node``: whether each end was given as a node (see
        :meth:`_check_kept_end`). ``escape``: the start point given and the
        escape segment's cost, when ``start_point`` is an escape cell's centre
        (see :meth:`_start_end`). ``start_xy`` and ``goal_xy``: the world
        points given for the ends (the world methods), or None.

        The planner holds no plan until the sources are queued: an exception on
        the way (a ``KeyboardInterrupt``, which Python delivers as soon as the
        clearing of a large grid's arrays returns) leaves it without one
        (:meth:`replan` raises ``RuntimeError``), not with the last plan's ends
        over cleared values and a stale queue, which a repair would turn into a
        wrong path or an out-of-bounds read in the kernels.
        """
        self._start = self._goal = None
        self._cached = None
        self._blank()
        self._clean = False
        self._changed[0] = 0  # a fresh search reads the costs as they are
        self._lowered = False
        self._km = 0.0
        self._fresh = True
        self._start_point = (float(start_point[0]), float(start_point[1]))
        self._goal_point = (float(goal_point[0]), float(goal_point[1]))
        self._start_cell = start_cell
        self._goal_cell = goal_cell
        self._start_on_node = start_on_node
        self._goal_on_node = goal_on_node
        self._escape = escape
        self._start_xy = start_xy
        self._goal_xy = goal_xy
        if goal_cell:
            seed = self._cell_cost(*gl) * HALF_DIAGONAL
            sources = [((gl[0] + di, gl[1] + dj), seed) for di, dj in _CORNERS.tolist()]
        else:
            sources = [(gl, 0.0)]
        # Queue the sources with keys (value + h(start, source), value) in the empty
        # heap: in ascending order, which is a valid heap.
        queued = sorted((v + _heuristic(s, node, self._hscale), v, node) for node, v in sources)
        nodes, keys, pos, size = self._heap
        rows = [node[0] for _, _, node in queued]
        cols = [node[1] for _, _, node in queued]
        self._work[2:6] = (min(rows), max(rows), min(cols), max(cols))  # the box, emptied above
        for slot, (k0, k1, node) in enumerate(queued):
            node_id = node[0] * self._ncols + node[1]
            self._rhs[node_id] = k1
            nodes[slot] = node_id
            keys[slot, 0] = k0
            keys[slot, 1] = k1
            pos[node_id] = slot
        size[0] = len(queued)
        # The ends last: from here on the planner holds this search.
        self._start = s
        self._goal = gl

    def _blank(self) -> int:
        """Blank the records written since the last time (and empty the queue); how many.

        Every search keeps the box of the nodes whose value fell in
        ``_work[2:6]`` (first and last row, first and last column), and
        :meth:`_reset` puts the sources it queues in it: every record written
        since lies in that box widened by one node (see ``settle``), so only
        that is blanked, and a short plan after a long one, on a large map, or
        after a replan, costs time in proportion to the searches since, not to
        the map (a short plan on a 4096² map took 25-50 ms, nearly all of it
        blanking every record; until review 28 a repair's box was the whole
        grid). Blanked in place, not allocated again: memory already paged in
        makes a search on a used planner (a replan's fallback) faster than on a
        new one.
        """
        top, bottom, left, right = (int(v) for v in self._work[2:6])
        rows = (max(top - 1, 0), min(bottom + 1, self._nrows - 1))
        cols = (max(left - 1, 0), min(right + 1, self._ncols - 1))
        blanked = clear_box(self._vals, self._ncols, rows, cols)
        self._heap[3][0] = 0  # size: no node queued (their slots were in the box)
        # Emptied last: an exception on the way (see _reset) leaves the box to blank again.
        self._work[2:6] = _EMPTY_BOX
        return blanked

    def _state(self) -> tuple[np.ndarray, ...]:
        return state(self._pad, self._vals, self._heap, self._work, self._changed)

    def _params(self, walk: int | None = None, fresh: bool = False) -> tuple[Any, ...]:
        """The kernels' scalars; ``walk``: the node the walk starts at, if not the usual one.

        ``fresh``: the search starts from scratch (see ``settle``).
        """
        start = self._start if self._start is not None else (0, 0)
        goal_id = -1 if self._goal is None else self._goal[0] * self._ncols + self._goal[1]
        if walk is None:
            walk = -1 if self._start_cell else start[0] * self._ncols + start[1]
        goal_cell = goal_id if self._goal_cell else -1
        return params(self._width, self._nrows, self._ncols, start,
                      -1 if self._goal_cell else goal_id, self._km, self._interp, self._hscale,
                      walk, goal_cell, fresh)

    def _search(self, ends: _Ends) -> tuple[FloatArray, float, float, int]:
        """Node path (node coordinates), its exact cost and length, expansions.

        ``ends``: how the calling method takes its ends, for its errors to name
        them as its caller gave them (see :meth:`_ends_text`).

        A repair is bounded (see ``_REPAIR_CAP`` and :meth:`_repair`): cut short,
        it is replaced by a fresh search from the current start on the planner's
        own arrays, which returns the same path (the repair's expansions are
        counted too). With no cost changed since the last search from the same
        start, that search's path is returned.
        """
        assert self._start is not None and self._goal is not None
        cached = self._cached
        if cached is not None and cached[0] == self._start:
            return cached[1].copy(), cached[2], cached[3], 0
        fresh = self._fresh
        self._work[0] = 0
        if fresh:
            self._work[1] = _NO_LIMIT
            pts, k, expanded, status = self._walk(fresh=True)
        else:
            pts, k, expanded, status = self._repair()
        if status == ABORTED:
            assert self._start_point is not None and self._goal_point is not None
            self._reset(self._start, self._goal, self._start_point, self._goal_point,
                        start_cell=self._start_cell, goal_cell=self._goal_cell,
                        start_on_node=self._start_on_node, goal_on_node=self._goal_on_node,
                        escape=self._escape, start_xy=self._start_xy,
                        goal_xy=self._goal_xy)
            self._work[0] = 0
            self._work[1] = _NO_LIMIT
            pts, k, more, status = self._walk(fresh=True)
            expanded += more
            fresh = True
        if fresh:
            self._fresh_work = int(self._work[0])
        self._fresh = False
        if status == NO_PATH:
            start, goal = self._ends_text(ends)
            # The words of astar's message (the ends as this method's caller gave them).
            raise NoPathError(
                f"no path from {start} to {goal} (expanded {counted(expanded, 'node')})",
                expanded=expanded,
            )
        # The walk's start: the start node, or the start cell's corner it picked.
        to_goal = float(self._g[int(pts[0, 0]) * self._ncols + int(pts[0, 1])]) if k else np.inf
        if not to_goal < PATH_COST_LIMIT:
            start, goal = self._ends_text(ends)
            raise ValueError(
                f"costs: the least cost from {start} to {goal} is {to_goal!r} (cost units "
                "× cells); Field D* needs it below 2**52 = 4503599627370496, beyond which "
                "float64 cannot tell its node values apart (lower the largest costs)"
            )
        if status != OK:  # pragma: no cover - guarded by the strictly decreasing walk
            raise RuntimeError("Field D* path extraction failed to reach the goal")
        points = self._node_path(pts, k)
        if self._start_cell:
            points, more = self._best_start_corner(points, fresh)
            expanded += more
        cost, length = polyline_cost(self._pad, self._width, points, points.shape[0])
        self._cached = (self._start, points.copy(), float(cost), float(length))
        return points, float(cost), float(length), int(expanded)

    def _node_path(self, pts: FloatArray, k: int) -> FloatArray:
        """The walk's first ``k`` points, smoothed when the options ask for it."""
        if self._interp and self._smooth and k > 2:
            smoothed: FloatArray = shortcut(self._pad, self._width, pts, k, _SHORTCUT_PATIENCE)
            return smoothed
        head: FloatArray = pts[:k].copy()
        return head

    def _best_start_corner(self, points: FloatArray, fresh: bool) -> tuple[FloatArray, int]:
        """Among start-cell corners tied at the least cost-to-goal, the cheapest linked path.

        The walk started at the first corner of least value (the four were
        settled). Corners whose value equals it to a relative 1e-9 (a tie up to
        rounding, which a mirrored grid may break the other way) are walked too,
        and the one whose path, linked to the end points, costs least is kept
        (ties: the first corner). Returns the node path and the expansions.
        ``fresh``: whether the search was fresh (see :meth:`_walk`).
        """
        assert self._start is not None
        first = (int(points[0, 0]), int(points[0, 1]))
        corners = [(self._start[0] + di, self._start[1] + dj) for di, dj in _CORNERS.tolist()]
        values = [float(self._g[i * self._ncols + j]) for i, j in corners]
        least = values[corners.index(first)]
        tied = [c for c, v in zip(corners, values, strict=True)
                if c != first and v <= least + 1e-9 * least]
        if not tied:
            return points, 0
        best = points
        best_cost = self._linked(points)[1]
        expanded = 0
        self._work[1] = _NO_LIMIT  # the tied corners are settled: a short walk each
        for corner in tied:
            pts, k, more, status = self._walk(corner[0] * self._ncols + corner[1], fresh)
            expanded += more
            if status != OK:  # pragma: no cover - every value is settled, none is far
                continue
            other = self._node_path(pts, k)
            cost = self._linked(other)[1]
            if cost < best_cost or (cost == best_cost and corner < first):
                best, best_cost, first = other, cost, corner
        return best, expanded

    def _ends_text(self, ends: _Ends) -> tuple[str, str]:
        """The start and the goal of the search as the calling method's caller gave them.

        ``"node"`` (:meth:`plan`, :meth:`replan`): the nodes; ``"cell"``
        (:meth:`plan_cells`): the cells; ``"xy"`` (the world methods): the world
        points, also an end kept from a plan of another form (a node or a cell
        centre as the world point it is).
        """
        assert self._start is not None and self._goal is not None
        assert self._start_point is not None and self._goal_point is not None
        if ends == "node":
            return f"start_node {self._start}", f"goal_node {self._goal}"
        if ends == "cell":
            start = tuple(math.floor(v) for v in self._start_point)
            goal = tuple(math.floor(v) for v in self._goal_point)
            return f"start_cell {start}", f"goal_cell {goal}"
        goal_xy = self._world_of(self._goal_point, self._goal_xy)
        if self._escape is not None:
            given = self._world_of(self._escape[0], self._start_xy)
            cell = tuple(math.floor(v) for v in self._start_point)
            return f"start_xy {given} (escaped to cell {cell})", f"goal_xy {goal_xy}"
        start_xy = self._world_of(self._start_point, self._start_xy)
        return f"start_xy {start_xy}", f"goal_xy {goal_xy}"

    def _repair(self) -> tuple[FloatArray, int, int, int]:
        """:meth:`_walk` on the repaired state, bounded (``ABORTED`` when hopeless).

        See the notes on ``_REPAIR_CAP`` for the staged, projected bound.
        """
        assert self._start is not None
        fresh = self._fresh_work
        lowered = self._lowered
        _, keys, _, size = self._heap
        start_id = self._start[0] * self._ncols + self._start[1]
        # Key range of the repair: from the lowest key queued or about to be (a changed
        # cell's corner, whose value does not fall when no cell got cheaper) to the
        # start's (old) key.
        first = min(float(keys[0, 0]) if size[0] > 0 else np.inf, self._changed_key())
        end = min(float(self._g[start_id]), float(self._rhs[start_id])) + self._km
        self._lowered = False
        if lowered or not first < end < np.inf:
            self._work[1] = max(int(_REPAIR_FRACTION * fresh), _REPAIR_MIN_WORK)
            return self._walk()
        cap = max(int(_REPAIR_CAP * fresh), _REPAIR_MIN_WORK)
        stage = max(int(_REPAIR_PROBE * fresh), _REPAIR_PROBE_MIN_WORK)
        span = end - first
        expanded = 0
        while True:
            self._work[1] = min(stage, cap)
            pts, k, more, status = self._walk()
            expanded += more
            done = float(self._work[0])
            if status != ABORTED or done >= cap:
                return pts, k, expanded, status
            progress = (float(keys[0, 0]) if size[0] > 0 else end) - first
            # Hopeless when the projected total done * (span / progress)^2 exceeds the cap.
            if not progress > 0.0 or done * span * span > cap * progress * progress:
                return pts, k, expanded, status
            stage *= 2

    def _changed_key(self) -> float:
        """Least key ``min(g, rhs) + h + km`` of the changed cells' corners (before requeueing)."""
        n = int(self._changed[0])
        if n == 0:
            return np.inf
        assert self._start is not None
        cells = self._changed[1 : n + 1]
        rows = cells // self._width - 1
        cols = cells - (rows + 1) * self._width - 1
        i = (rows[:, None] + _CORNERS[:, 0]).ravel()
        j = (cols[:, None] + _CORNERS[:, 1]).ravel()
        ids = i * self._ncols + j
        m = np.minimum(self._g[ids], self._rhs[ids])
        dr = np.abs(i - self._start[0])
        dc = np.abs(j - self._start[1])
        h = self._hscale * (np.maximum(dr, dc) + OCT * np.minimum(dr, dc))
        return float((m + h).min()) + self._km

    def _walk(
        self, walk: int | None = None, fresh: bool = False
    ) -> tuple[FloatArray, int, int, int]:
        """Run :func:`extract_path`: (points buffer (n, 2), K, expansions, status).

        The kernel's buffers are flat (see ``_field_path_kernels``); the points'
        is returned as (n, 2) rows, a view.

        ``walk``: the node id to walk from instead of the start (see :meth:`_params`);
        ``fresh``: a search from scratch, not a repair (see :meth:`_params`). Fresh
        searches and repairs alike widen the box of the records written (see
        ``settle``), which the next fresh search blanks.
        """
        pts = np.empty(2 * max(_POINTS_PER_SIDE * (self._nrows + self._ncols), 1))
        cand = np.empty(4 * CANDIDATES)
        cand2 = np.empty(4 * CANDIDATES)
        corner_g = np.empty(4)
        counter = np.zeros(1, dtype=np.int64)
        need = np.zeros(1, dtype=np.int64)
        while True:
            k, status = extract_path(self._state(), self._params(walk, fresh), self._lookahead,
                                     pts, cand, cand2, corner_g, counter, need)
            if status != FULL:
                return pts.reshape(-1, 2), int(k), int(counter[0]), int(status)
            # Out of room: walk again with twice the buffer (the values stay settled).
            pts = np.empty(2 * pts.shape[0])

    def _linked(self, points: FloatArray) -> tuple[FloatArray, float, float]:
        """The node path with the stored end points attached, smoothed, and its cost/length."""
        assert self._start_point is not None and self._goal_point is not None
        if self._start_point == self._goal_point:
            # Start and goal at one point (off a node too): the path is that point,
            # not a trip to the nearest node and back.
            return np.array([self._start_point], dtype=np.float64), 0.0, 0.0
        linked = np.vstack([self._start_point, points, self._goal_point])
        # An end point on its node adds a zero-length step: drop repeated vertices.
        keep = np.ones(linked.shape[0], dtype=bool)
        keep[1:] = np.any(linked[1:] != linked[:-1], axis=1)
        linked = np.ascontiguousarray(linked[keep])
        if self._smooth:
            linked = shortcut(self._pad, self._width, linked, linked.shape[0], _SHORTCUT_PATIENCE)
        cost, length = polyline_cost(self._pad, self._width, linked, linked.shape[0])
        return linked, float(cost), float(length)

    def _world_path(self, points: FloatArray, expanded: int) -> Path2D:
        linked, cost, _ = self._linked(points)
        if self._escape is not None:
            # As MapPlanner: the start point given, then the path from the escape
            # cell's centre; the escape segment priced by nearest_escape.
            given, escape_cost = self._escape
            linked = np.vstack([given, linked])
            cost += escape_cost
        res = self._resolution
        points = self.node_to_world(linked)
        # The ends exactly as given (node coordinates turned back into world points
        # are a rounding step off); the cost stays that of the node polyline.
        if self._start_xy is not None:
            points[0] = self._start_xy
        if self._goal_xy is not None:
            if points.shape[0] == 1 and self._start_xy not in (None, self._goal_xy):
                # Start and goal at one node point, given as two world points.
                points = np.vstack([points, [self._goal_xy]])
            else:
                points[-1] = self._goal_xy
        # The length of the points returned, as every world path's (MapPlanner.plan's,
        # Path2D.to_world's), not the node polyline's times the resolution, which
        # differed from it in the last bits (review 54, FOUND7).
        return Path2D(
            points,
            "world",
            cost=cost * res,
            length=polyline_length(points),
            expanded=expanded,
        )


def _nearest_node(p: tuple[float, float]) -> tuple[int, int]:
    """The node nearest node coordinates ``p`` (as :meth:`FieldDStar.world_to_node` rounds)."""
    # round_half_up, not floor(p + 0.5): that sum rounds first (0.5 - 2**-54 -> 1).
    near = round_half_up(np.array(p, dtype=np.float64))
    return int(near[0]), int(near[1])


def _obstacle_mask(value: ArrayLike, costs: FloatArray) -> NDArray[np.bool_]:
    """``obstacles`` of :class:`FieldDStar` checked against the costs, as an owned copy."""
    arr = as_array(value, "obstacles")
    if arr.dtype != np.bool_:
        raise TypeError(f"obstacles must be a boolean array, got dtype {arr.dtype}")
    if arr.shape != costs.shape:
        raise ValueError(f"obstacles must have the shape of costs {costs.shape}, got {arr.shape}")
    passable = arr & np.isfinite(costs)
    if passable.any():
        row, col = (int(v) for v in np.argwhere(passable)[0])
        cost = float(costs[row, col])
        raise ValueError(
            f"obstacles marks cell {(row, col)}, whose cost is finite ({cost!r}): "
            "an obstacle is impassable (with a finite unknown_cost, unknown cells are no obstacles)"
        )
    return np.array(arr, dtype=np.bool_, order="C")


def _obstacle_flags(value: ArrayLike, cells: IntArray, costs: FloatArray) -> NDArray[np.bool_]:
    """``obstacles`` of :meth:`FieldDStar.update_costs`, one flag a cell listed."""
    arr = as_array(value, "obstacles")
    if arr.size == 0 and arr.ndim == 1:
        # No flags for no cells: NumPy types an empty list float64, as cells and new_costs.
        arr = arr.astype(np.bool_)
    if arr.dtype != np.bool_:
        raise TypeError(f"obstacles must be a bool or a boolean array, got dtype {arr.dtype}")
    m = cells.shape[0]
    if arr.ndim == 0:
        arr = np.full(m, bool(arr))
    if arr.shape != (m,):
        raise ValueError(f"obstacles must be a bool or have shape ({m},), got {arr.shape}")
    passable = arr & np.isfinite(costs)
    if passable.any():
        k = int(np.argmax(passable))
        cell = (int(cells[k, 0]), int(cells[k, 1]))
        raise ValueError(
            f"obstacles marks cell {cell}, whose new cost is finite ({float(costs[k])!r}): "
            "an obstacle is impassable"
        )
    return np.array(arr, dtype=np.bool_)


def _heuristic(a: tuple[int, int], b: tuple[int, int], hscale: float) -> float:
    """``heuristic`` of the search kernels (the same float operations) between nodes a, b."""
    dr = abs(b[0] - a[0])
    dc = abs(b[1] - a[1])
    if dr < dc:
        return hscale * (dc + OCT * dr)
    return hscale * (dr + OCT * dc)


def field_dstar(
    costs: ArrayLike,
    start_node: ArrayLike,
    goal_node: ArrayLike,
    *,
    interpolate: bool = True,
    lookahead: bool = True,
    smooth: bool = True,
) -> Path2D:
    """One-shot Field D* path between two nodes of a cost grid.

    Equivalent to ``FieldDStar(costs, ...).plan(start_node, goal_node)``; see
    :class:`FieldDStar` for the conventions (node ``(i, j)`` is a cell corner, at
    continuous grid coordinates ``(i - 0.5, j - 0.5)``).

    Parameters
    ----------
    costs : array_like, shape (rows, cols)
        Per-cell traversal cost per unit length: finite values in ``[1, 1e12]``,
        ``np.inf`` impassable. Never modified.
    start_node, goal_node : array_like of int, shape (2,)
        Nodes ``(i, j)`` with ``0 <= i <= rows`` and ``0 <= j <= cols``, each a
        corner of at least one passable cell.
    interpolate : bool, default True
        Field D*'s interpolated edge costs; False gives 8-connected D* Lite.
    lookahead : bool, default True
        One-step lookahead in the path extraction.
    smooth : bool, default True
        Straighten runs of the path where that does not raise its cost.

    Returns
    -------
    Path2D
        ``"grid"`` path whose points are node − 0.5.

    Raises
    ------
    ValueError, TypeError, navkit.NoPathError
        As :class:`FieldDStar` (costs in ``[1, 1e12]`` or ``inf``; the flags
        only ``True`` or ``False``) and :meth:`FieldDStar.plan`.

    Examples
    --------
    >>> import numpy as np
    >>> from navkit.planning import field_dstar
    >>> costs = np.ones((10, 10))
    >>> costs[2:8, 4] = np.inf
    >>> path = field_dstar(costs, (5, 0), (5, 10))
    >>> path.points[0].tolist(), path.points[-1].tolist()
    ([4.5, -0.5], [4.5, 9.5])
    >>> bool(path.cost > 10.0)
    True
    """
    planner = FieldDStar(costs, interpolate=interpolate, lookahead=lookahead, smooth=smooth)
    return planner.plan(start_node, goal_node)


#: Bytes a node of a planner's search state takes: its record (g, rhs, heap slot: 24),
#: its heap entry (key 16, node id 8) and about its padded cell cost (8).
_BYTES_PER_NODE = 56


def _memory_text(rows: int, cols: int) -> str:
    """The message of a MemoryError from a planner's arrays, naming the grid."""
    nodes = (rows + 1) * (cols + 1)
    size = nodes * _BYTES_PER_NODE / 2**20
    return (
        f"a FieldDStar planner of {rows} x {cols} cells ({nodes} nodes) needs about "
        f"{size:.4g} MiB for its costs and search state ({_BYTES_PER_NODE} bytes a node), "
        "which could not be allocated"
    )


def _search_state(rows: int, cols: int) -> tuple[FloatArray, tuple[np.ndarray, ...]]:
    """:func:`node_records` of the nodes of a ``rows`` x ``cols`` grid; MemoryError naming it.

    The heap's large arrays are anonymous pages of their own, or ``np.zeros`` where
    the mapping fails (``_dstar_heap._lazy_zeros``): NumPy's MemoryError then named
    an array's shape only.
    """
    try:
        return node_records((rows + 1) * (cols + 1))
    except MemoryError as exc:
        raise MemoryError(_memory_text(rows, cols)) from exc


if not TYPE_CHECKING:  # mypy would take any name of this module
    # A pickle made at 5e5f83f (30 November 2026) names this module's FieldPath, which
    # 0123de4 replaced by Path2D: refused clearly, not pickle's AttributeError.
    __getattr__ = gone(__name__, ("FieldPath",), "0123de4")
