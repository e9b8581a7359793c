"""Field D*: interpolated any-angle planning on cell corners with D* Lite repair."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from navkit._shared.costs import validate_costs
from navkit._shared.validation import as_cell
from navkit.errors import NoPathError
from navkit.planning.grid import _field_dstar_kernels as _k
from navkit.planning.grid._dstar_heap import heap_new, heap_push

__all__ = ["FieldDStar", "FieldPath", "field_dstar", "field_dstar_cells"]

FloatArray = NDArray[np.float64]

# Consecutive refusals after which the shortcut pass stops extending a segment.
_SHORTCUT_PATIENCE = 8


@dataclass(frozen=True, eq=False)
class FieldPath:
    """A path through continuous grid coordinates.

    Attributes
    ----------
    points : (K, 2) float64 ndarray
        Vertices ``(row, col)`` in continuous grid coordinates (cell ``(r, c)``
        covers ``[r, r+1] × [c, c+1]``), from the start node to the goal node.
    cost : float
        Cost of the polyline itself: the integral of the cell cost along it
        (a stretch along a grid line pays the cheaper cell beside it). This is
        the true cost of ``points``, not the search's interpolated estimate.
    length : float
        Geometric length of the polyline, in cells.
    expanded : int
        Node expansions the call that produced the path performed.
    """

    points: FloatArray
    cost: float
    length: float
    expanded: int


class FieldDStar:
    """Field D* planner (Ferguson & Stentz) with incremental D* Lite repair.

    Nodes are the cell corners: a grid of ``rows × cols`` cells has a
    ``(rows + 1) × (cols + 1)`` node grid and node ``(i, j)`` sits at the
    continuous point ``(row, col) = (i, j)``. A path may cross a cell edge at any
    point; the cost-to-goal there is interpolated linearly between the edge's
    two nodes, so headings are not restricted to multiples of 45°. Crossing a
    cell costs its value per unit length; running along an edge costs the
    cheaper of the two cells beside it.

    The search is D* Lite (Koenig & Likhachev) backwards from the goal, so after
    :meth:`update_costs` the next :meth:`replan` repairs only the part of the
    cost field the change affects, also when the robot has moved (new start,
    same goal).

    Parameters
    ----------
    costs : (rows, cols) array_like
        Per-cell traversal cost per unit length: finite values >= 1, ``np.inf``
        impassable (the A* convention). Copied; the caller's array is never
        modified.
    interpolate : bool, default True
        ``False`` gives classic 8-connected D* Lite on the same nodes (an axis
        move pays the cheaper cell beside the edge, a diagonal ``sqrt(2)`` times
        the cell it crosses) and returns the optimal node path.
    lookahead : bool, default True
        One-step lookahead in the path extraction: a candidate crossing point
        inside an edge is scored by the best step onwards from it instead of by
        the linearly interpolated cost-to-goal there. Without it the raw path
        is occasionally a few per cent costlier than the 8-connected one.
    smooth : bool, default True
        After extraction, replace runs of the polyline by straight segments
        whenever the segment's exact cost is not higher. It never raises the
        path cost and makes paths in uniform regions exactly straight. Only
        used with ``interpolate=True``.

    Notes
    -----
    The interpolated node cost is the minimum over every option of the paper's
    formula (see ``corner_cost`` in ``_fdstar_kernels``) rather than the one
    option the paper's tests select; the value is never higher and identical
    whenever the paper's choice is the cheapest. The heuristic is the octile
    distance divided by ``sqrt(2)`` (the plain octile distance without
    interpolation): weak enough that an interpolated node is never expanded
    before the neighbours its cost depends on, so each node is expanded once
    per search. It assumes a minimum cell cost of 1, so it stays admissible
    after any cost update.

    Path extraction walks from the start: at each point (a node or a point on
    a grid line) it takes the cheapest of the optimal crossing points of the far
    edges of the cells touching it, the ends of the grid lines through it and,
    from a node, the point where the paper's "along the edge, then cut" option
    leaves the edge. A step must lower the estimated cost-to-goal; if none does,
    a straight step to a corner of lower exact cost-to-goal is taken instead,
    so the walk always ends exactly at the goal. Every node value the walk reads
    is settled first (the D* Lite loop runs until that node's key is reached),
    so a repaired plan reads exactly the values a fresh plan reads and both
    return the same path.

    Examples
    --------
    >>> import numpy as np
    >>> from navkit.planning import FieldDStar
    >>> planner = FieldDStar(np.ones((20, 20)))
    >>> path = planner.plan((0, 0), (20, 10))
    >>> round(path.cost, 9) == round(float(np.hypot(20, 10)), 9)
    True
    >>> planner.update_costs([(3, 1), (3, 2)], np.inf)
    >>> again = planner.replan()
    >>> again.cost > path.cost
    True
    """

    def __init__(
        self,
        costs: ArrayLike,
        *,
        interpolate: bool = True,
        lookahead: bool = True,
        smooth: bool = True,
    ) -> None:
        arr = validate_costs(costs)
        self._rows, self._cols = arr.shape
        self._width = self._cols + 2
        pad = np.full((self._rows + 2, self._cols + 2), np.inf)
        pad[1:-1, 1:-1] = arr
        self._pad = pad.ravel()
        self._interp = bool(interpolate)
        self._lookahead = bool(lookahead)
        self._smooth = bool(smooth)
        self._hscale = _k.FIELD_HSCALE if self._interp else 1.0
        self._nrows = self._rows + 1
        self._ncols = self._cols + 1
        n = self._nrows * self._ncols
        self._g = np.full(n, np.inf)
        self._rhs = np.full(n, np.inf)
        self._heap = heap_new(n)
        self._km = 0.0
        self._start: tuple[int, int] | None = None
        self._goal: tuple[int, int] | None = None

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

    def _node(self, value: Any, name: str) -> tuple[int, int]:
        node = as_cell(value, name, (self._nrows, self._ncols))
        i, j = node
        around = self._pad.reshape(self._rows + 2, self._cols + 2)[i : i + 2, j : j + 2]
        if not np.isfinite(around).any():
            raise ValueError(
                f"{name} {node} is a corner of impassable cells only (node grid is "
                f"(rows + 1, cols + 1) = {(self._nrows, self._ncols)})"
            )
        return node

    def plan(self, start: ArrayLike, goal: ArrayLike) -> FieldPath:
        """Search from scratch and return the path from ``start`` to ``goal``.

        Parameters
        ----------
        start, goal : (2,) int
            Nodes ``(row, col)`` with ``0 <= row <= rows`` and ``0 <= col <= cols``,
            each a corner of at least one passable cell.

        Raises
        ------
        ValueError
            ``start`` or ``goal`` off the node grid or surrounded by impassable cells.
        NoPathError
            The goal cannot be reached from the start.
        """
        s = self._node(start, "start")
        gl = self._node(goal, "goal")
        self._g.fill(np.inf)
        self._rhs.fill(np.inf)
        self._heap = heap_new(self._g.shape[0])
        self._km = 0.0
        self._start = s
        self._goal = gl
        goal_id = gl[0] * self._ncols + gl[1]
        self._rhs[goal_id] = 0.0
        nodes, keys, pos, size = self._heap
        h = _k._h(s[0], s[1], gl[0], gl[1], self._hscale)
        heap_push(nodes, keys, pos, size, goal_id, h, 0.0)
        return self._search()

    def replan(self, start: ArrayLike | None = None) -> FieldPath:
        """Repair the previous search after cost updates and return the new path.

        Parameters
        ----------
        start : (2,) int, optional
            New start node (the robot moved); the goal stays. Defaults to the
            previous start.

        Raises
        ------
        RuntimeError
            :meth:`plan` was never called.
        ValueError
            Bad ``start``.
        NoPathError
            The goal cannot be reached any more.
        """
        if self._start is None or self._goal is None:
            raise RuntimeError("replan() repairs a previous search: call plan() first")
        if start is not None:
            s = self._node(start, "start")
            # D* Lite: keys already queued stay lower bounds if km grows by h(old, new).
            self._km += _k._h(self._start[0], self._start[1], s[0], s[1], self._hscale)
            self._start = s
        return self._search()

    def update_costs(self, cells: ArrayLike, new_costs: ArrayLike) -> None:
        """Change the cost of some cells; the next :meth:`replan` repairs the plan.

        Parameters
        ----------
        cells : (M, 2) or (2,) int array_like
            Cells ``(row, col)`` to change. With repeats, the last value wins.
        new_costs : float or (M,) array_like
            New costs, >= 1 or ``np.inf`` (impassable).

        Raises
        ------
        ValueError
            Cells outside the grid or not integers, mismatched lengths, or costs
            that are NaN, ``-inf`` or below 1.
        """
        idx = np.asarray(cells)
        if idx.ndim == 1 and idx.shape[0] == 2:
            idx = idx.reshape(1, 2)
        if idx.size == 0:
            idx = idx.reshape(0, 2)
        if idx.ndim != 2 or idx.shape[1] != 2:
            raise ValueError(f"cells must have shape (M, 2) or (2,), got {idx.shape}")
        if idx.dtype.kind == "f":
            if not np.all(np.isfinite(idx)) or not np.all(idx == np.round(idx)):
                raise ValueError("cells must hold integer (row, col) indices")
        elif idx.dtype.kind not in "iu" or idx.dtype == np.bool_:
            raise ValueError(f"cells must hold integer (row, col) indices, got dtype {idx.dtype}")
        idx = idx.astype(np.int64)
        bad = (idx[:, 0] < 0) | (idx[:, 0] >= self._rows) | (idx[:, 1] < 0) | (
            idx[:, 1] >= self._cols
        )
        if bad.any():
            raise ValueError(
                f"cells {idx[bad][0].tolist()} is outside the grid of shape {self.shape}"
            )
        try:
            vals = np.asarray(new_costs, dtype=np.float64)
        except (TypeError, ValueError):
            raise ValueError("new_costs must be numeric") from None
        if vals.ndim == 0:
            vals = np.full(idx.shape[0], float(vals))
        if vals.shape != (idx.shape[0],):
            raise ValueError(
                f"new_costs must be a scalar or have shape ({idx.shape[0]},), got {vals.shape}"
            )
        if np.isnan(vals).any() or (vals < 1.0).any():
            raise ValueError("new_costs must be >= 1 or np.inf (no NaN, no -inf)")
        if idx.shape[0] == 0:
            return
        _k.update_cells(
            self._state(),
            self._params(),
            np.ascontiguousarray(idx[:, 0]),
            np.ascontiguousarray(idx[:, 1]),
            np.ascontiguousarray(vals),
        )

    def _state(self) -> tuple[NDArray[Any], ...]:
        return _k.state(self._pad, self._g, self._rhs, self._heap)

    def _params(self) -> tuple[Any, ...]:
        start = self._start if self._start is not None else (0, 0)
        goal_id = -1 if self._goal is None else self._goal[0] * self._ncols + self._goal[1]
        return _k.params(self._width, self._nrows, self._ncols, start, goal_id, self._km,
                         self._interp, self._hscale)

    def _search(self) -> FieldPath:
        assert self._start is not None and self._goal is not None
        pts, k, expanded, status = _k.extract_path(self._state(), self._params(),
                                                   self._lookahead)
        if status == _k.NO_PATH:
            raise NoPathError(
                f"goal {self._goal} is unreachable from start {self._start}", explored=expanded
            )
        if status != _k.OK:  # pragma: no cover - guarded by the strictly decreasing walk
            raise RuntimeError("Field D* path extraction failed to reach the goal")
        if self._interp and self._smooth and k > 2:
            points = _k.shortcut(self._pad, self._width, pts, k, _SHORTCUT_PATIENCE)
        else:
            points = pts[:k].copy()
        cost, length = _k.polyline_cost(self._pad, self._width, points, points.shape[0])
        points.flags.writeable = False
        return FieldPath(points=points, cost=float(cost), length=float(length),
                         expanded=int(expanded))


def field_dstar(
    costs: ArrayLike,
    start: ArrayLike,
    goal: ArrayLike,
    *,
    interpolate: bool = True,
    lookahead: bool = True,
    smooth: bool = True,
) -> FieldPath:
    """One-shot Field D* path between two nodes of a cost grid.

    Equivalent to ``FieldDStar(costs, ...).plan(start, goal)``; see
    :class:`FieldDStar` for the conventions.

    Examples
    --------
    >>> import numpy as np
    >>> from navkit.planning import field_dstar
    >>> costs = np.ones((10, 10))
    >>> costs[2:8, 4] = np.inf
    >>> path = field_dstar(costs, (5, 0), (5, 10))
    >>> path.points[0].tolist(), path.points[-1].tolist()
    ([5.0, 0.0], [5.0, 10.0])
    >>> bool(path.cost > 10.0)
    True
    """
    planner = FieldDStar(costs, interpolate=interpolate, lookahead=lookahead, smooth=smooth)
    return planner.plan(start, goal)



def field_dstar_cells(
    costs: NDArray[np.float64],
    start: tuple[int, int],
    goal: tuple[int, int],
    **options: Any,
) -> tuple[FloatArray, float, int]:
    """Field D* between two passable cells, for :func:`navkit.planning.plan_path`.

    Field D* plans between cell corners; here the path runs from the centre of
    the ``start`` cell to its corner nearest the goal cell, through the Field D*
    path to the corner of the ``goal`` cell nearest the start cell, and on to
    the goal cell's centre. The two end segments lie inside passable cells; the
    whole polyline then gets the cost-never-increasing shortcut pass (when
    ``smooth``), so the link corners are not forced into the path.

    Parameters
    ----------
    costs : (rows, cols) float64 ndarray
        Validated cell costs (>= 1, inf impassable).
    start, goal : (int, int)
        Passable cells ``(row, col)``.
    **options
        ``interpolate``, ``lookahead``, ``smooth`` of :class:`FieldDStar`.

    Returns
    -------
    points : (K, 2) float64 ndarray
        Continuous ``(row, col)`` with integers at cell centres (the
        ``plan_path`` planner convention), from the start to the goal cell centre.
    cost : float
        Exact cost of the polyline (cost units × cells).
    expanded : int
        Node expansions.
    """
    planner = FieldDStar(costs, **options)
    if tuple(start) == tuple(goal):
        return np.array([start], dtype=np.float64), 0.0, 0
    centre_s = np.array(start, dtype=np.float64) + 0.5
    centre_g = np.array(goal, dtype=np.float64) + 0.5
    # The corner of each end cell nearest the other end's centre (ties: lowest).
    corners = np.array([(0, 0), (0, 1), (1, 0), (1, 1)], dtype=np.int64)
    node_s = np.asarray(start) + corners[np.argmin(np.hypot(*(start + corners - centre_g).T))]
    node_g = np.asarray(goal) + corners[np.argmin(np.hypot(*(goal + corners - centre_s).T))]
    path = planner.plan(node_s, node_g)
    points = np.vstack([centre_s, path.points, centre_g])
    if planner._smooth:
        points = _k.shortcut(planner._pad, planner._width, points, points.shape[0],
                             _SHORTCUT_PATIENCE)
    cost, _ = _k.polyline_cost(planner._pad, planner._width, points, points.shape[0])
    return points - 0.5, float(cost), path.expanded
