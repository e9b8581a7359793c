"""A* (and weighted A*, Dijkstra) shortest paths on cost grids: one-shot and prepared."""

from __future__ import annotations

import threading
from types import MappingProxyType
from typing import TYPE_CHECKING, Any, Literal, cast

import numpy as np
from numpy.typing import ArrayLike, NDArray

from navkit._shared.counts import counted
from navkit._shared.dunders import slot_state
from navkit._shared.frozen import restore_slots
from navkit._shared.moved import gone
from navkit._shared.types import CellLike, FloatArray
from navkit._shared.validation import as_bool
from navkit.errors import NoPathError
from navkit.planning.grid._arguments import (
    check_connectivity,
    check_search_size,
    traversable_cell,
)
from navkit.planning.grid._astar_kernels import grid_search
from navkit.planning.grid._jps_cut_kernels import jps_cut_search
from navkit.planning.grid._jps_kernels import SQRT2, jps_search, jps_tables
from navkit.planning.grid._limits import (
    MAX_HEURISTIC_WEIGHT,
    bounded_float,
    checked_cost_range,
    compiled_cost_range,
    converted_costs,
    highest_finite,
    read_only,
)
from navkit.planning.grid._path import Path2D
from navkit.planning.grid._search_heap import F_BAND_COSTS
from navkit.planning.grid._workspace import grow_heap, scratch_text, used_meanwhile, workspace

__all__ = ["AStarPlanner", "astar"]

_METHODS = ("astar", "jps", "auto")


#: JPS bit tables (row bits, column bits).
_Tables = tuple[NDArray[np.uint64], NDArray[np.uint64]]


def _checked_grid(
    costs: ArrayLike,
    connectivity: Any,
    corner_cutting: Any,
    heuristic_weight: Any,
    method: Any,
) -> tuple[FloatArray, float, float, _Tables | None]:
    """The validated grid, its cost range and, when JPS may run, its bit tables.

    When the options ask for JPS (or allow it) the kernel that builds the
    tables also checks the values (one compiled kernel fewer on first use);
    otherwise :func:`checked_cost_range` checks them. Options of the wrong
    kind are reported later, by :meth:`AStarPlanner._setup`.
    """
    if (
        type(method) is str
        and (method == "jps" or method == "auto")
        and type(connectivity) is int
        and connectivity == 8
        and type(corner_cutting) is bool
        and type(heuristic_weight) in (int, float)
        and heuristic_weight == 1.0
    ):
        grid = converted_costs(costs)
        row_bits, col_bits, lowest, highest = jps_tables(grid)
        return grid, lowest, highest, (row_bits, col_bits)
    grid, lowest, highest = checked_cost_range(costs)
    return grid, lowest, highest, None


def _check_method(value: Any) -> str:
    """Return a valid search ``method`` name; reject anything else."""
    if not isinstance(value, str):
        raise TypeError(f"method must be 'astar', 'jps' or 'auto', got {type(value).__name__}")
    if value not in _METHODS:
        raise ValueError(f"method must be 'astar', 'jps' or 'auto', got {value!r}")
    return value


class _JpsScratch(threading.local):
    """One thread's scratch for jump point search, grown to the largest grid searched.

    ``records`` holds 16 bytes per cell (cost from the start and parent, see
    :func:`navkit.planning.grid._jps_kernels.jps_search`; both JPS kernels
    use it), ``meta`` is its int32 view, ``blocks`` the reached / closed bits
    with a stamp per 64 cells; each search takes the next stamp, so nothing
    is cleared between searches.
    """

    def __init__(self) -> None:
        self.records = np.zeros(0, dtype=np.float64)
        self.meta = self.records.view(np.int32)
        self.blocks = np.zeros(0, dtype=np.int64)
        self.heap = np.empty(2048, dtype=np.float64)
        self.stamp = 0


_jps_scratch = _JpsScratch()


def _jps_workspace(
    n: int, own: bool = False
) -> tuple[FloatArray, NDArray[np.int32], NDArray[np.int64], NDArray[np.float64], int]:
    """This thread's JPS scratch for ``n`` cells, its queue and a fresh stamp.

    ``own``: new arrays, not this thread's (see :func:`_jps_used_meanwhile`).
    """
    scratch = _jps_scratch
    if own or scratch.records.size < 2 * n:
        # Both arrays first, then the swap: a MemoryError from the second must
        # not leave large records with the old, smaller blocks, which the
        # kernels (no bounds checks) would then index past their end.
        try:
            records = np.empty(2 * n, dtype=np.float64)
            blocks = np.zeros(3 * ((n + 63) // 64), dtype=np.int64)
        except MemoryError as exc:
            raise MemoryError(scratch_text(n, 16.375)) from exc
        if own:
            heap = np.empty(scratch.heap.size, dtype=np.float64)
            return records, records.view(np.int32), blocks, heap, 1
        scratch.records = records
        scratch.meta = records.view(np.int32)
        scratch.blocks = blocks
        scratch.stamp = 0
    scratch.stamp += 1
    return scratch.records, scratch.meta, scratch.blocks, scratch.heap, scratch.stamp


def _jps_used_meanwhile(records: FloatArray, heap: NDArray[np.float64], stamp: int) -> bool:
    """Whether another search took this thread's JPS scratch since the one given these.

    As :func:`~navkit.planning.grid._workspace.used_meanwhile`: a signal
    handler's search in this thread, which may have overwritten the answer
    (the path in ``heap``) before it was read.
    """
    scratch = _jps_scratch
    return scratch.records is not records or scratch.heap is not heap or scratch.stamp != stamp


def _lowest_cost(planner: Any) -> float:
    """``_lowest`` of an :class:`AStarPlanner` pickled before it existed: its costs' smallest."""
    return compiled_cost_range(planner._costs)[0]


def _not_yet(planner: Any) -> None:
    """``_highest`` (found at its first need) and ``_jps`` (A*, as it ran then) of a
    planner pickled before they existed."""
    return None


class AStarPlanner:
    """A* on one cost grid, validated once, answering many queries.

    The constructor does every O(cells) step once: it validates the grid,
    converts it to C-contiguous float64 (integer and float32 grids included),
    and finds its smallest cost for the heuristic. :meth:`plan` and
    :meth:`distance_field` then only check their cells and run the search
    kernel, so a short query costs microseconds however large the grid (as
    tcod's ``Pathfinder`` does). A class with ``__slots__`` rather than a
    frozen dataclass because it owns a private working copy of the grid.

    The grid model and the search are those of :func:`astar`: a move between
    neighbouring traversable cells u, v costs ``step * (c_u + c_v) / 2``
    (``step`` 1 orthogonal, sqrt(2) diagonal); the heuristic is the octile
    distance (Manhattan for ``connectivity=4``) times the smallest cell cost,
    so the paths are optimal for ``heuristic_weight <= 1`` (to the tie band's
    bound: where routes' costs differ by less than 2**-40 of f, not at all,
    within about ``m * 2**-40`` relative and ``m * 2**-21`` of the smallest
    cost; see :func:`astar`).

    Parameters
    ----------
    costs : array_like, shape (rows, cols)
        Per-cell traversal cost (per cell length): finite values in
        ``[1, 1e12]`` are traversable, ``np.inf`` is impassable; at most
        ``2**31 - 1`` cells. Copied: later changes to the caller's array do not
        reach the planner.
    connectivity : {8, 4}, default 8
        8 allows diagonal moves, 4 only orthogonal ones.
    corner_cutting : bool, default False
        With False a diagonal move also needs both cells it passes beside to be
        traversable (MovingAI convention, no squeezing past obstacle corners).
        With True only its two end cells matter (scikit-image ``MCP_Geometric``).
        Ignored when ``connectivity=4``.
    heuristic_weight : float, default 1.0
        Multiplies the heuristic, in ``[0, 1e6]``. 1 (or anything in [0, 1])
        gives optimal paths (to the tie band's bound, above); 0 is Dijkstra's
        algorithm. A weight w > 1 is
        weighted A*: it usually expands far fewer cells and returns a path
        costing at most w times the optimum (the heuristic is consistent and no
        cell is expanded twice; Likhachev, Gordon & Thrun, "ARA*", NIPS 2003,
        Theorem 1), to the tie band's bound as for w = 1.
    method : {"astar", "jps", "auto"}, default "astar"
        ``"astar"`` expands cells one by one. ``"jps"`` is jump point search
        (Harabor & Grastien: with ``corner_cutting=True`` the pruning rules of
        their AAAI 2011 paper, without it those of their ICAPS 2014 paper,
        with its 64-cell block scans either way): it expands only the cells
        where an optimal path may turn, often 10-100 times fewer, and returns
        a path of the same optimal cost through every cell (consecutive cells
        are 8-neighbours), possibly another of the equally short paths. It
        needs every traversable cell to cost the same, ``connectivity=8``
        and ``heuristic_weight=1``. ``"auto"`` uses JPS when those hold and
        A* otherwise. With ``"jps"`` and ``"auto"`` the constructor also
        builds bit tables of the grid (a quarter of a byte per cell).
        ``expanded`` of a JPS path counts jump points.

    Raises
    ------
    ValueError
        Invalid ``costs`` (see :func:`navkit.planning.distance_field`), bad
        ``connectivity``, ``heuristic_weight`` outside ``[0, 1e6]``, an
        unknown ``method`` or ``method="jps"`` on a grid or options JPS does
        not support.
    TypeError
        Non-integer connectivity, non-bool ``corner_cutting``, non-real
        ``heuristic_weight``, non-string ``method``.

    Notes
    -----
    Queries are thread-safe: the planner is not modified by them and the
    search's scratch arrays (16 bytes per cell and the queue, see :func:`astar`;
    JPS: 16.4 bytes per cell and its queue) are kept per thread.
    :meth:`distance_field` runs Dijkstra on a bucket queue (as
    :func:`navkit.planning.distance_field`), on the heap when the cost range is
    too wide for buckets.

    Examples
    --------
    >>> import numpy as np
    >>> costs = np.ones((3, 4))
    >>> costs[1, 1:3] = np.inf
    >>> planner = AStarPlanner(costs)
    >>> planner.plan((2, 0), (0, 3)).cells.tolist()
    [[2, 0], [2, 1], [2, 2], [2, 3], [1, 3], [0, 3]]
    >>> planner.plan((0, 0), (2, 3)).cost
    5.0
    >>> planner.distance_field((0, 0))[2].tolist()
    [2.0, 3.0, 4.0, 5.0]
    >>> jps = AStarPlanner(costs, method="jps")  # another path of the same cost
    >>> path = jps.plan((2, 0), (0, 3))
    >>> path.cells.tolist(), path.cost
    ([[2, 0], [1, 0], [0, 0], [0, 1], [0, 2], [0, 3]], 5.0)
    """

    __slots__ = (
        "__weakref__",
        "_costs",
        "_cutting",
        "_eight",
        "_flat",
        "_highest",
        "_jps",
        "_lowest",
        "_scale",
        "_weight",
    )

    _costs: FloatArray
    _flat: FloatArray
    _eight: bool
    _cutting: bool
    _weight: float
    _scale: float
    _lowest: float
    _highest: float | None
    # JPS tables (row bits, column bits) and the uniform cell cost,
    # or None when this planner runs A*.
    _jps: tuple[NDArray[np.uint64], NDArray[np.uint64], float] | None

    # Slots added since a release, for pickles made before (see
    # navkit._shared.frozen.fill_added_fields): such a planner ran A* (the JPS tables
    # came later) and found its costs' range when needed. Not annotated: it would
    # read as a slot's type.
    _added_fields = MappingProxyType(
        {"_lowest": _lowest_cost, "_highest": _not_yet, "_jps": _not_yet}
    )

    def __init__(
        self,
        costs: ArrayLike,
        *,
        connectivity: int = 8,
        corner_cutting: bool = False,
        heuristic_weight: float = 1.0,
        method: Literal["astar", "jps", "auto"] = "astar",
    ) -> None:
        grid, lowest, highest, tables = _checked_grid(
            costs, connectivity, corner_cutting, heuristic_weight, method
        )
        # Validation converts only when needed: copy unless the result is surely a
        # new array. Nested lists always convert; an ndarray converts when its
        # dtype or layout differs (the bounds test is O(1)); any other array-like
        # may hand over its own memory (an ``__array__`` returning the object's
        # array unchanged, which has no base).
        if not (
            isinstance(costs, (list, tuple))
            or (isinstance(costs, np.ndarray) and not np.may_share_memory(grid, costs))
        ):
            grid = grid.copy()
        self._setup(
            grid, lowest, connectivity, corner_cutting, heuristic_weight, method, highest, tables
        )

    @classmethod
    def _borrowing(
        cls,
        grid: FloatArray,
        lowest: float,
        connectivity: Any,
        corner_cutting: Any,
        heuristic_weight: Any,
        method: Any = "astar",
        highest: float | None = None,
        tables: _Tables | None = None,
    ) -> AStarPlanner:
        """A planner on an already validated grid, without copying it.

        For the one-shot functions, whose planner lives for one query while the
        caller's array cannot change, and for owners of a private grid.
        ``highest``: the grid's largest finite cost when known (found when needed);
        ``tables``: its JPS bit tables when already built.
        """
        planner = cls.__new__(cls)
        planner._setup(
            grid, lowest, connectivity, corner_cutting, heuristic_weight, method, highest, tables
        )
        return planner

    def _setup(
        self,
        grid: FloatArray,
        lowest: float,
        connectivity: Any,
        corner_cutting: Any,
        heuristic_weight: Any,
        method: Any,
        highest: float | None,
        tables: _Tables | None = None,
    ) -> None:
        check_search_size(grid)
        self._eight = check_connectivity(connectivity)
        self._cutting = as_bool(corner_cutting, "corner_cutting")
        self._weight = bounded_float(
            heuristic_weight, "heuristic_weight", 0.0, MAX_HEURISTIC_WEIGHT
        )
        # The smallest cost is finite whenever a query can run (its start is
        # traversable), so the scale is finite then.
        self._scale = self._weight * lowest
        self._lowest = lowest
        self._highest = highest
        self._costs = grid
        # Read-only: the kernels are compiled for read-only grids only.
        self._flat = read_only(grid.reshape(-1))
        self._jps = None
        how = _check_method(method)
        if how == "astar":
            return
        options_fit = self._eight and self._weight == 1.0
        if how == "jps" and not options_fit:
            raise ValueError(
                "method='jps' needs connectivity=8 and heuristic_weight=1.0, got "
                f"connectivity={8 if self._eight else 4}, heuristic_weight={self._weight}"
            )
        if not options_fit:
            return
        if tables is None:
            row_bits, col_bits, _, _ = jps_tables(grid)
        else:
            row_bits, col_bits = tables
        # The common cost of the traversable cells (inf when there are none).
        uniform = lowest if lowest == np.inf or lowest == self._highest_cost() else -1.0
        if uniform < 0.0:
            if how == "jps":
                raise ValueError(
                    "method='jps' needs every traversable cell of costs to cost the same; "
                    "use method='astar' (or 'auto') on grids of varying cost"
                )
            return
        self._jps = (row_bits, col_bits, uniform)

    def __getstate__(self) -> object:
        """The state pickles and copies take: Python's default, without the flat view.

        Pickle stores a view as an array of its own, so the grid was pickled
        twice (16 MB for a 1000² grid instead of 8); :meth:`__setstate__` makes
        the view again. Also pickle protocols 0 and 1 need a ``__getstate__``
        (see :func:`slot_state`).
        """
        instance, slots = cast("tuple[Any, dict[str, Any]]", slot_state(self))
        return instance, {name: value for name, value in slots.items() if name != "_flat"}

    def __setstate__(self, state: Any) -> None:
        """Restore from a pickle or :func:`copy.deepcopy`.

        The flat grid is made again as a read-only view of the grid (pickles
        made before it was left out hand it back as a writable array of its
        own: the search kernels would compile a second time for it, see
        :func:`read_only`, and the grid would be held twice).
        """
        restore_slots(self, state)
        self._flat = read_only(self._costs.reshape(-1))

    def _highest_cost(self) -> float:
        """The largest finite cost of the grid (-inf if none), found once."""
        if self._highest is None:
            self._highest = highest_finite(self._costs)
        return self._highest

    @property
    def costs(self) -> FloatArray:
        """The validated float64 cost grid, shape (rows, cols); a read-only view."""
        view: FloatArray = self._costs.view()
        view.flags.writeable = False
        return view

    @property
    def shape(self) -> tuple[int, int]:
        """Grid shape ``(rows, cols)``."""
        rows, cols = self._costs.shape
        return int(rows), int(cols)

    @property
    def connectivity(self) -> int:
        """8 or 4."""
        return 8 if self._eight else 4

    @property
    def corner_cutting(self) -> bool:
        """Whether diagonal moves may pass beside impassable cells."""
        return self._cutting

    @property
    def heuristic_weight(self) -> float:
        """Weight of the heuristic (1 is A*, 0 Dijkstra, > 1 weighted A*)."""
        return self._weight

    @property
    def method(self) -> Literal["astar", "jps"]:
        """The search :meth:`plan` runs: ``"jps"`` or ``"astar"`` (``"auto"`` resolved)."""
        return "astar" if self._jps is None else "jps"

    def __repr__(self) -> str:
        rows, cols = self.shape
        jps = "" if self._jps is None else ", method='jps'"
        return (
            f"{type(self).__name__}(<{rows}x{cols} costs>, connectivity={self.connectivity}, "
            f"corner_cutting={self._cutting}, heuristic_weight={self._weight}{jps})"
        )

    def plan(self, start_cell: CellLike, goal_cell: CellLike) -> Path2D:
        """Least-cost path between two cells.

        Parameters
        ----------
        start_cell, goal_cell : (int, int)
            Cells ``(row, col)``; both inside the grid and traversable.

        Returns
        -------
        Path2D
            ``"grid"`` path through the cell centres from ``start_cell`` to
            ``goal_cell``, points of shape (K, 2) in cells (:attr:`Path2D.cells`
            gives them as integers), its cost (sum of the move costs, in cost
            units × cells), length in cells (orthogonal steps 1, diagonal
            sqrt(2)) and the number of cells expanded (jump points with JPS).

        Raises
        ------
        ValueError
            A cell outside the grid or on an impassable cell.
        TypeError
            Non-integer cells.
        navkit.NoPathError
            ``goal_cell`` is unreachable from ``start_cell``; ``expanded`` holds
            the number of cells expanded.

        Examples
        --------
        >>> import numpy as np
        >>> costs = np.ones((3, 5))
        >>> costs[:2, 2] = np.inf  # a wall with a gap in the bottom row
        >>> planner = AStarPlanner(costs)
        >>> path = planner.plan((0, 0), (0, 4))
        >>> path.cells.tolist()
        [[0, 0], [1, 1], [2, 1], [2, 2], [2, 3], [1, 4], [0, 4]]
        >>> round(path.cost, 6), round(path.length, 6)  # 4 + 2 sqrt(2)
        (6.828427, 6.828427)
        >>> costs[2, 2] = np.inf  # the gap closed (the planner kept its own copy)
        >>> AStarPlanner(costs).plan((0, 0), (0, 4))
        Traceback (most recent call last):
            ...
        navkit.errors.NoPathError: no path from start_cell (0, 0) to goal_cell (0, 4) ...
        """
        grid = self._costs
        s = traversable_cell(grid, start_cell, "start_cell")
        t = traversable_cell(grid, goal_cell, "goal_cell")
        if self._jps is not None:
            return self._plan_jps(s, t)
        rows, cols = grid.shape
        goal_index = t[0] * cols + t[1]
        own = False
        while True:
            rec, meta, heap, stamp = workspace(rows * cols, own=own)
            expanded, found, k, diagonal = grid_search(
                self._flat,
                rows,
                cols,
                s[0] * cols + s[1],
                goal_index,
                self._eight,
                self._cutting,
                self._scale,
                F_BAND_COSTS * self._lowest,
                rec,
                meta,
                heap,
                stamp,
            )
            if found < 0:
                # Rare: the queue filled up or the path did not fit in it; search
                # again with a larger one.
                grow_heap(k)
                continue
            # The search wrote the path's cells into its queue's scratch (uint64).
            cells = heap[: 2 * k].reshape(k, 2).astype(np.float64) if found else rec[:0]
            cost = float(rec[2 * goal_index])
            if own or not used_meanwhile(rec, stamp):
                break
            # A signal handler searched in this thread meanwhile: again, alone.
            own = True
        if not found:
            raise NoPathError(
                f"no path from start_cell {s} to goal_cell {t} "
                f"(expanded {counted(expanded, 'cell')})",
                expanded=expanded,
            )
        length = (k - 1 - diagonal) + SQRT2 * diagonal
        return Path2D._owned(cells, "grid", cost, length, expanded)

    def _plan_jps(self, s: tuple[int, int], t: tuple[int, int]) -> Path2D:
        """:meth:`plan` by jump point search (tables built, cells checked)."""
        assert self._jps is not None
        row_bits, col_bits, uniform = self._jps
        rows, cols = self._costs.shape
        goal_index = t[0] * cols + t[1]
        search = jps_cut_search if self._cutting else jps_search
        own = False
        while True:
            records, meta, blocks, heap, stamp = _jps_workspace(rows * cols, own)
            expanded, found, k, diagonal = search(
                row_bits,
                col_bits,
                rows,
                cols,
                s[0] * cols + s[1],
                goal_index,
                records,
                meta,
                blocks,
                heap,
                stamp,
            )
            if found < 0:
                # The queue filled up (rare: it holds the open jump points) or the
                # path did not fit in it: grow it and search again.
                _jps_scratch.heap = np.empty(max(2 * heap.size, 2 * k), dtype=np.float64)
                continue
            # The search wrote the path's cells into its queue's scratch.
            cells = heap[: 2 * k].reshape(k, 2).copy() if found else heap[:0]
            if own or not _jps_used_meanwhile(records, heap, stamp):
                break
            # A signal handler searched in this thread meanwhile: again, alone.
            own = True
        if not found:
            raise NoPathError(
                f"no path from start_cell {s} to goal_cell {t} "
                f"(expanded {counted(expanded, 'jump point')})",
                expanded=expanded,
            )
        length = (k - 1 - diagonal) + SQRT2 * diagonal
        return Path2D._owned(cells, "grid", uniform * length, length, expanded)

    def distance_field(self, goal_cell: CellLike) -> FloatArray:
        """Least cost from every cell to ``goal_cell`` (Dijkstra to exhaustion).

        Ignores ``heuristic_weight`` and ``method`` (always Dijkstra); see
        :func:`navkit.planning.distance_field`.

        Parameters
        ----------
        goal_cell : (int, int)
            Goal cell ``(row, col)``; inside the grid and traversable.

        Returns
        -------
        ndarray of float64, shape (rows, cols)
            Cost-to-go of each cell (cost units × cells, as :meth:`plan`'s
            path costs); 0 at the goal and ``np.inf`` where the goal is
            unreachable (including impassable cells).

        Raises
        ------
        TypeError
            ``goal_cell`` not a pair of integers (a world point in metres
            included: the message names ``world_to_cell``).
        ValueError
            ``goal_cell`` outside the grid or on an impassable cell.

        Examples
        --------
        >>> import numpy as np
        >>> costs = np.ones((3, 5))
        >>> costs[:2, 2] = np.inf  # a wall with a gap in the bottom row
        >>> planner = AStarPlanner(costs)
        >>> field = planner.distance_field((0, 4))
        >>> field.round(3)
        array([[6.828, 6.414,   inf, 1.   , 0.   ],
               [5.828, 5.414,   inf, 1.414, 1.   ],
               [5.414, 4.414, 3.414, 2.414, 2.   ]])
        >>> bool(np.isclose(field[0, 0], planner.plan((0, 0), (0, 4)).cost))  # A*'s optimum
        True
        """
        # Imported here: the distance-field module builds on this one.
        from navkit.planning.grid._distance_field import _bucket_field

        grid = self._costs
        t = traversable_cell(grid, goal_cell, "goal_cell")
        field = _bucket_field(
            grid, self._lowest, self._highest_cost(), t, self._eight, self._cutting
        )
        if field is not None:
            return field
        # Cost ranges too wide for the bucket queue: Dijkstra on the heap.
        rows, cols = grid.shape
        n = rows * cols
        own = False
        while True:
            rec, meta, heap, stamp = workspace(n, own=own)
            _, status, _, _ = grid_search(
                self._flat,
                rows,
                cols,
                t[0] * cols + t[1],
                -1,
                self._eight,
                self._cutting,
                0.0,
                0.0,
                rec,
                meta,
                heap,
                stamp,
            )
            if status < 0:
                grow_heap()
                continue
            # Exhaustion closes every reachable cell; costs are stale everywhere else.
            closed = (meta[2 : 4 * n : 4] >> 4) == stamp + 1
            out: FloatArray = np.where(closed, rec[0 : 2 * n : 2], np.inf).reshape(rows, cols)
            if own or not used_meanwhile(rec, stamp):
                return out
            # A signal handler searched in this thread meanwhile: again, alone.
            own = True


def astar(
    costs: ArrayLike,
    start_cell: CellLike,
    goal_cell: CellLike,
    *,
    connectivity: int = 8,
    corner_cutting: bool = False,
    heuristic_weight: float = 1.0,
    method: Literal["astar", "jps", "auto"] = "astar",
) -> Path2D:
    """Least-cost path between two cells of a cost grid (A*), one-shot.

    The grid is a graph whose nodes are the traversable cells. A move between
    neighbouring cells u, v costs ``step * (c_u + c_v) / 2``, where ``step`` is 1
    for an orthogonal and sqrt(2) for a diagonal move, so an all-ones grid gives
    octile distances (the MovingAI benchmark model).

    The heuristic is the octile distance (Manhattan for ``connectivity=4``) times
    the smallest cell cost in the grid, which is admissible and consistent: each
    move changes it by at most ``step * min(costs)`` while costing at least that.
    Queue ties in f = g + h are broken towards smaller h (nearer the goal).

    Every call validates the whole grid (O(cells)); for many queries on one
    grid build an :class:`AStarPlanner` once, which gives the same answers.

    Parameters
    ----------
    costs : array_like, shape (rows, cols)
        Per-cell traversal cost (per cell length): finite values in
        ``[1, 1e12]`` are traversable, ``np.inf`` is impassable; at most
        ``2**31 - 1`` cells. Not modified.
    start_cell, goal_cell : (int, int)
        Cells ``(row, col)``; both must be inside the grid and traversable.
    connectivity : {8, 4}, default 8
        8 allows diagonal moves, 4 only orthogonal ones.
    corner_cutting : bool, default False
        As in :class:`AStarPlanner`.
    heuristic_weight : float, default 1.0
        As in :class:`AStarPlanner`, in ``[0, 1e6]``: 1 is A*, 0 Dijkstra,
        w > 1 weighted A* (path cost at most w times the optimum, to the tie
        band's bound).
    method : {"astar", "jps", "auto"}, default "astar"
        As in :class:`AStarPlanner`: ``"jps"`` runs jump point search (grids
        whose traversable cells all cost the same, 8-connected, with or
        without corner cutting, weight 1; the same optimal cost, often far
        fewer expansions), ``"auto"`` uses it whenever it applies.

    Returns
    -------
    Path2D
        ``"grid"`` path through the cell centres from ``start_cell`` to
        ``goal_cell`` (:attr:`Path2D.cells` gives them as integers) with cost,
        length in cells and expansion count.

    Notes
    -----
    The search runs in a numba kernel over flat arrays with an indexed 4-ary
    heap (:mod:`navkit.planning.grid._search_heap`); memory is O(cells). Its
    scratch (a packed 16-byte record per cell: cost, mark, parent and heap
    slot, so a cell's search state is one cache line away, and the queue) is
    kept per thread and reused by later calls on grids of the same or smaller
    size, so repeated queries pay no allocation. It stays allocated while the
    thread lives: after one search on a 4000 × 4000 grid the thread holds
    about 256 MB (A*) or more with JPS and :func:`distance_field`; search
    huge grids in a worker thread that ends to give the memory back.
    Grids may have at most 2**31 - 1 cells. Ties among equal f are broken by the
    heuristic (to 1/16 cell at any distance from the goal on grids with rows +
    cols below 2**27, or 2**17 with JPS; on longer ones to the finest power of
    two that fits), then by cell index, so results are deterministic. A*
    counts f equal within 2**-40 of f (its lowest 12 bits ignored): sums of
    1 and sqrt(2) in different orders round differently, so the cells of one
    plateau differ in f by an ulp or a few, and comparing f exactly made A*
    expand many cells off the path (an empty 512 x 512 grid from (0, 0) to
    (511, 250): 63,760 cells for a path of 512, now 512; JPS 3). The cost
    stays within about ``m * 2**-40`` of the optimum, relative, m the number
    of nested near ties (costs less than 2**-40 apart, not equal) on the
    path, none on grids of one cost whose optimum is below 700,000 times it
    (see ``F_TIE_BITS`` in :mod:`navkit.planning.grid._search_heap`). Only f
    below 2**19 times the smallest cell cost is banded, so a near tie costs
    at most 2**-21 of the cheapest move (behind cells of cost 1e12, f is
    compared exactly).

    Raises
    ------
    ValueError
        Invalid ``costs`` (see :func:`navkit.planning.distance_field`), ``start_cell`` or
        ``goal_cell`` outside the grid or on an impassable cell, bad
        ``connectivity``, ``heuristic_weight`` outside ``[0, 1e6]``, an unknown
        ``method`` or ``method="jps"`` where it does not apply.
    TypeError
        Cells that are not pairs of integers (booleans, mappings and strings
        included); non-integer connectivity; non-bool ``corner_cutting``;
        non-string ``method``.
    navkit.NoPathError
        ``goal_cell`` is unreachable from ``start_cell``; ``expanded`` holds the
        number of cells expanded.

    Examples
    --------
    >>> import numpy as np
    >>> costs = np.ones((3, 4))
    >>> costs[1, 1:3] = np.inf
    >>> path = astar(costs, (2, 0), (0, 3))
    >>> path.cells.tolist()
    [[2, 0], [2, 1], [2, 2], [2, 3], [1, 3], [0, 3]]
    >>> path.frame, path.cost, path.length
    ('grid', 5.0, 5.0)
    >>> round(astar(costs, (2, 0), (0, 3), corner_cutting=True).cost, 6)
    4.414214
    >>> astar(costs, (2, 0), (0, 3), method="jps").cost
    5.0
    >>> round(astar(costs, (2, 0), (0, 3), method="jps", corner_cutting=True).cost, 6)
    4.414214
    """
    grid, lowest, highest, tables = _checked_grid(
        costs, connectivity, corner_cutting, heuristic_weight, method
    )
    planner = AStarPlanner._borrowing(
        grid, lowest, connectivity, corner_cutting, heuristic_weight, method, highest, tables
    )
    return planner.plan(start_cell, goal_cell)


if not TYPE_CHECKING:  # mypy would take any name of this module
    # A pickle made at 5e5f83f (30 November 2026) names this module's GridPath, which
    # 0123de4 replaced by Path2D: refused clearly, not pickle's AttributeError.
    __getattr__ = gone(__name__, ("GridPath",), "0123de4")
