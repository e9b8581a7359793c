"""Exact cost-to-go fields on cost grids (Dijkstra to exhaustion), one-shot."""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike

from navkit._shared.types import CellLike, FloatArray
from navkit._shared.validation import as_bool
from navkit.planning.grid._arguments import check_connectivity, traversable_cell
from navkit.planning.grid._astar import AStarPlanner
from navkit.planning.grid._distance_field_kernels import (
    GROW,
    MAX_SLOTS,
    SQRT2,
    WIDTH_MARGIN,
    bucket_field,
    pad_grid,
)
from navkit.planning.grid._limits import checked_cost_range, read_only

__all__ = ["distance_field"]

MAX_PADDED_CELLS = 2**31 - 1
"""Most cells of the padded grid (``(rows + 2) * (cols + 2)``) the bucket queue can
hold: its entries are int32 padded cell ids."""

#: A field is returned as a view of its padded work buffer (no copy) when the
#: buffer holds at most this factor more cells: the border kept alive, <= 20 %
#: of it. A copy costs 8 bytes a cell of peak memory (it is made while the
#: padded field is alive): with 1.02, uniform grids with a side under about 100
#: (200 x 200, 90 x 5000) peaked at 16 bytes a cell, not the documented 9 (review
#: 19); copies are left for grids whose border is a large part of what a view
#: keeps alive (a side under 9 cells, a square under 17).
_VIEW_SLACK = 1.25


def distance_field(
    costs: ArrayLike,
    goal_cell: CellLike,
    *,
    connectivity: int = 8,
    corner_cutting: bool = False,
) -> FloatArray:
    """Least cost from every cell to ``goal_cell`` (a navigation function), one-shot.

    Dijkstra's algorithm from ``goal_cell`` until every reachable cell is
    expanded. Move costs are symmetric (``step * (c_u + c_v) / 2``), so the
    cost from the goal to a cell is that cell's cost-to-go. When the dearest
    move costs at most about 60 times the cheapest (every grid whose finite
    costs span a factor of up to about 40), the queue is a ring of buckets one
    cheapest move wide (Dial's algorithm, O(1) per queue operation); otherwise,
    and on grids within ``2 * (rows + cols) + 4`` cells of the ``2**31 - 1``
    limit, it is the indexed heap of :func:`astar`. Both give the same field, bit for
    bit: that of :meth:`AStarPlanner.distance_field`, the prepared form.

    Parameters
    ----------
    costs : array_like, shape (rows, cols)
        Per-cell traversal cost: finite values in ``[1, 1e12]`` traversable,
        ``np.inf`` impassable; at most ``2**31 - 1`` cells. Integer or float
        dtype; booleans, complex numbers, strings, NaN, values below 1 or
        finite values above 1e12, empty arrays or other dimensions raise
        ``ValueError``. Not modified. (1e12 is every grid planner's
        maximum: sums of such costs over any grid stay far from overflow, and
        it leaves Field D*, whose path costs must stay below ``2**52``, see
        :class:`FieldDStar`, paths of 4,500 cells at that cost.)
    goal_cell : (int, int)
        Goal cell ``(row, col)``; inside the grid and traversable.
    connectivity : {8, 4}, default 8
        As in :func:`astar`.
    corner_cutting : bool, default False
        As in :func:`astar`.

    Returns
    -------
    ndarray of float64, shape (rows, cols)
        Cost-to-go of each cell (in the units of ``costs`` × cells); 0 at the
        goal and ``np.inf`` where the goal is unreachable (including impassable
        cells).

    Raises
    ------
    ValueError
        Invalid ``costs``, ``goal_cell`` outside the grid or impassable, bad
        ``connectivity``.
    TypeError
        ``goal_cell`` not a pair of integers, non-integer connectivity,
        non-bool ``corner_cutting``.

    Notes
    -----
    Peak memory, in bytes a cell: 9 on a grid of one finite cost, 17
    otherwise (the padded field, which becomes the float64 result in place,
    the padded costs and a traversable flag), plus 8 when ``costs`` is not
    C-contiguous float64 (its converted copy) and a small queue; padded cells
    count (a one-cell border all round). The result is a view of the padded
    field (holding its border); where the border is more than a fifth of it
    (a side under 9 cells, a square under 17), a copy: 8 bytes a cell more at
    the peak. The heap search (wide cost ranges) keeps a per-thread workspace
    of 16 bytes a cell between calls and needs about 9 more.

    Examples
    --------
    >>> import numpy as np
    >>> costs = np.ones((2, 3))
    >>> costs[0, 1] = np.inf
    >>> distance_field(costs, (0, 0))
    array([[ 0., inf,  4.],
           [ 1.,  2.,  3.]])
    >>> distance_field(costs, (0, 0), corner_cutting=True).round(4)
    array([[0.    ,    inf, 2.8284],
           [1.    , 1.4142, 2.4142]])
    """
    grid, lowest, highest = checked_cost_range(costs)
    eight = check_connectivity(connectivity)
    cutting = as_bool(corner_cutting, "corner_cutting")
    goal = traversable_cell(grid, goal_cell, "goal_cell")
    field = _bucket_field(grid, lowest, highest, goal, eight, cutting)
    if field is not None:
        return field
    planner = AStarPlanner._borrowing(grid, lowest, connectivity, cutting, 1.0, "astar", highest)
    return planner.distance_field(goal)


def _bucket_field(
    grid: FloatArray,
    lowest: float,
    highest: float,
    goal: tuple[int, int],
    eight: bool,
    cutting: bool,
    cap: int = 0,
) -> FloatArray | None:
    """The field by the bucket-queue kernel, or None when the cost range needs too many buckets.

    Also None when the padded grid has more cells than the int32 bucket entries
    can name (:data:`MAX_PADDED_CELLS`): grids within a border's worth of
    cells of the ``2**31 - 1`` limit.

    ``lowest``, ``highest``: the smallest and largest finite costs of ``grid``.
    ``cap``: initial bucket segment length (0: about one wavefront, ``4 * (rows + cols)``).
    """
    rows, cols = grid.shape
    n_padded = (rows + 2) * (cols + 2)
    if n_padded > MAX_PADDED_CELLS:
        # A padded cell id would wrap around in the int32 buckets; the heap search
        # indexes the unpadded cells, which the callers keep below 2**31.
        return None
    width = lowest * WIDTH_MARGIN
    w_max = SQRT2 * highest if eight else highest
    span = int(w_max / width) + 3
    if span > MAX_SLOTS:
        return None
    flat = read_only(grid.reshape(-1))
    n_slots = 1 << (span - 1).bit_length()
    uniform = highest == lowest
    free = np.empty(n_padded, dtype=np.uint8)
    padded = np.empty(0 if uniform else n_padded, dtype=np.float64)
    dist = np.empty(n_padded, dtype=np.float64)
    pad_grid(flat, rows, cols, free, padded, uniform, dist)
    cap = max(8, cap) if cap else max(64, 4 * (rows + cols))
    buckets = np.empty(n_slots * cap, dtype=np.int32)
    counts = np.zeros(n_slots, dtype=np.int64)
    state = np.array([0, 0, 1], dtype=np.int64)
    source = (goal[0] + 1) * (cols + 2) + goal[1] + 1
    dist[source] = 0.0
    buckets[0] = source
    counts[0] = 1
    inv = 1.0 / width
    mask = n_slots - 1
    uniform_cost = lowest if uniform else 0.0
    while (
        bucket_field(free, padded, uniform_cost, rows, cols, eight, cutting, inv, mask, dist,
                     buckets, cap, counts, state)
        == GROW
    ):
        grown = np.empty(n_slots * 2 * cap, dtype=np.int32)
        for s in range(n_slots):
            grown[2 * s * cap : 2 * s * cap + counts[s]] = buckets[s * cap : s * cap + counts[s]]
        buckets = grown
        cap *= 2
    del free, padded, buckets
    # The kernel moved the interior to the front of ``dist`` in place (each value
    # moves towards the start, onto cells already read): the result takes no second
    # field-sized array (8 bytes a cell of peak memory). It stays a view of the
    # padded buffer where the border is a small part of it (no resize: numpy 2.5's
    # shrinking resize allocates a new buffer and copies, twice the peak); a narrow
    # grid, whose border would be most of what the view keeps alive, gets a copy.
    field = dist[: rows * cols].reshape(rows, cols)
    if n_padded > _VIEW_SLACK * (rows * cols):
        return field.copy()
    return field
