"""numba kernels for grid A* and Dijkstra (private).

Plain functions on flat arrays, compiled with ``cache=True``; the public layer in
:mod:`navkit.planning` validates input before calling them. Cells are addressed by
their flat index ``row * cols + col`` into a C-contiguous cost grid.

Graph model (shared by :func:`grid_search` and every test oracle): a move between
neighbouring traversable cells u, v costs ``step * (c_u + c_v) / 2`` with
``step`` 1 for an orthogonal and sqrt(2) for a diagonal move. Without corner
cutting a diagonal move also needs both cells it passes beside to be traversable
(the MovingAI convention); with it, only its two end cells matter (the model of
scikit-image's ``MCP_Geometric``).
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from navkit.planning._heap import heap_pop, heap_push

SQRT2 = math.sqrt(2.0)
_OCTILE_EXTRA = SQRT2 - 1.0

# Move directions: 0-3 orthogonal (N, S, W, E), 4-7 diagonal (NW, NE, SW, SE).
# A diagonal d passes beside the orthogonal cells (DR[d], 0) and (0, DC[d]).
DR = np.array([-1, 1, 0, 0, -1, -1, 1, 1], dtype=np.int64)
DC = np.array([0, 0, -1, 1, -1, 1, -1, 1], dtype=np.int64)


@njit(cache=True, inline="always")
def _heuristic(r: int, c: int, gr: int, gc: int, octile: bool, scale: float) -> float:
    """Weighted lower bound on the cost from (r, c) to (gr, gc).

    Octile distance (8-connected) or Manhattan distance (4-connected) times
    ``scale`` = heuristic weight × minimum cell cost.
    """
    dr = abs(r - gr)
    dc = abs(c - gc)
    if octile:
        if dr < dc:
            return scale * (dc + _OCTILE_EXTRA * dr)
        return scale * (dr + _OCTILE_EXTRA * dc)
    return scale * (dr + dc)


@njit(cache=True)
def grid_search(
    flat: np.ndarray,
    rows: int,
    cols: int,
    start: int,
    goal: int,
    eight: bool,
    corner_cutting: bool,
    scale: float,
    g: np.ndarray,
    parent: np.ndarray,
    mark: np.ndarray,
    nodes: np.ndarray,
    keys: np.ndarray,
    pos: np.ndarray,
    size: np.ndarray,
    stamp: int,
) -> tuple[int, bool]:
    """Best-first search from ``start``: A*, weighted A* or Dijkstra.

    Parameters
    ----------
    flat : (rows * cols,) float64
        Cell costs in row-major order, finite >= 1 or +inf (impassable). Both
        end cells must be traversable (checked by the caller).
    rows, cols : int
        Grid shape.
    start : int
        Flat index of the source cell.
    goal : int
        Flat index of the target cell, or -1 to search until every reachable
        cell is closed (Dijkstra to exhaustion; ``scale`` must then be 0).
    eight : bool
        8-connected (True) or 4-connected (False).
    corner_cutting : bool
        Allow diagonal moves beside impassable cells.
    scale : float
        Heuristic weight × minimum cell cost; 0 gives Dijkstra.
    g, parent, mark, nodes, keys, pos, size, stamp
        Scratch from :func:`navkit.planning._workspace.workspace` (at least
        ``rows * cols`` long). On return ``mark[v] == stamp + 1`` for every
        closed cell (exhaustion closes every reachable one), ``g`` holds their
        cost from ``start`` (exact when the heuristic weight is <= 1) and
        ``parent`` the direction index (into ``DR``/``DC``) of the move that
        reached them, -1 at ``start``. The heap is left empty.

    Returns
    -------
    expanded : int
        Number of cells closed.
    found : bool
        Whether ``goal`` was closed.
    """
    open_mark = stamp
    closed_mark = stamp + 1
    gr = goal // cols if goal >= 0 else 0
    gc = goal - gr * cols if goal >= 0 else 0
    n_dirs = 8 if eight else 4

    g[start] = 0.0
    parent[start] = -1
    mark[start] = open_mark
    sr = start // cols
    h0 = _heuristic(sr, start - sr * cols, gr, gc, eight, scale)
    heap_push(nodes, keys, pos, size, start, h0, h0)
    expanded = 0
    found = False
    while size[0] > 0:
        u = heap_pop(nodes, keys, pos, size)
        mark[u] = closed_mark
        expanded += 1
        if u == goal:
            found = True
            break
        r = u // cols
        c = u - r * cols
        gu = g[u]
        cu = flat[u]
        # Orthogonal neighbours inside the grid and traversable; they also
        # gate the diagonals when corners may not be cut.
        n_in = r > 0
        s_in = r + 1 < rows
        w_in = c > 0
        e_in = c + 1 < cols
        n_ok = n_in and flat[u - cols] < np.inf
        s_ok = s_in and flat[u + cols] < np.inf
        w_ok = w_in and flat[u - 1] < np.inf
        e_ok = e_in and flat[u + 1] < np.inf
        # One loop body for all directions: numba passes arrays to helper
        # functions with reference counting, which costs more than the work.
        for d in range(n_dirs):
            dr = DR[d]
            dc = DC[d]
            if d < 4:
                if not (n_ok if d == 0 else s_ok if d == 1 else w_ok if d == 2 else e_ok):
                    continue
                step = 1.0
            else:
                if corner_cutting:
                    if not ((n_in if dr < 0 else s_in) and (w_in if dc < 0 else e_in)):
                        continue
                elif not ((n_ok if dr < 0 else s_ok) and (w_ok if dc < 0 else e_ok)):
                    continue
                step = SQRT2
            v = u + dr * cols + dc
            cv = flat[v]
            if cv == np.inf:
                continue
            m = mark[v]
            if m == closed_mark:
                continue
            new_g = gu + step * 0.5 * (cu + cv)
            # g of a cell this search has not reached is stale: test mark first.
            if m != open_mark or new_g < g[v]:
                g[v] = new_g
                parent[v] = d
                mark[v] = open_mark
                h = _heuristic(r + dr, c + dc, gr, gc, eight, scale)
                # Key (f, h): among equal f prefer the node nearer the goal,
                # which keeps A* from expanding whole plateaus of equal f.
                heap_push(nodes, keys, pos, size, v, new_g + h, h)
    # Leave the heap empty (pos == -1 everywhere) for the next search.
    for i in range(size[0]):
        pos[nodes[i]] = -1
    size[0] = 0
    return expanded, found


@njit(cache=True)
def trace_path(parent: np.ndarray, cols: int, goal: int) -> tuple[np.ndarray, float]:
    """Cells (K, 2) ``(row, col)`` from the search source to ``goal`` and their length.

    Follows the direction indices written by :func:`grid_search` back from
    ``goal`` until the source (direction -1). The length is geometric, in cells:
    orthogonal steps count 1 and diagonal steps sqrt(2).
    """
    k = 1
    v = goal
    while parent[v] >= 0:
        d = parent[v]
        v -= DR[d] * cols + DC[d]
        k += 1
    cells = np.empty((k, 2), dtype=np.int64)
    n_diag = 0
    v = goal
    for i in range(k - 1, -1, -1):
        r = v // cols
        cells[i, 0] = r
        cells[i, 1] = v - r * cols
        if i > 0:
            d = parent[v]
            if d >= 4:
                n_diag += 1
            v -= DR[d] * cols + DC[d]
    return cells, (k - 1 - n_diag) + SQRT2 * n_diag
