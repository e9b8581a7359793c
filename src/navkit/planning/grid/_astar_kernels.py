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

from navkit._shared.jit import njit_cached, njit_inline, njit_inline_no_refcount, njit_no_refcount
from navkit.planning.grid._search_heap import clear, pop, precedes_top, push, tie_key

SQRT2 = math.sqrt(2.0)
_OCTILE_EXTRA = SQRT2 - 1.0

# Move directions: 0-3 orthogonal (N, S, W, E), 4-7 diagonal (NW, NE, SW, SE).
# A diagonal d passes beside the orthogonal cells (DR[d], 0) and (0, DC[d]).
DR = np.array([-1, 1, 0, 0, -1, -1, 1, 1], dtype=np.int64)
DC = np.array([0, 0, -1, 1, -1, 1, -1, 1], dtype=np.int64)


@njit_inline
def _cells_to_goal(r: int, c: int, gr: int, gc: int, octile: bool) -> float:
    """Octile (8-connected) or Manhattan (4-connected) distance in cells."""
    dr = abs(r - gr)
    dc = abs(c - gc)
    if octile:
        # min/max rather than a branch: the comparison is unpredictable.
        return max(dr, dc) + _OCTILE_EXTRA * min(dr, dc)
    return float(dr + dc)


@njit_inline_no_refcount
def _relax(
    flat: np.ndarray,
    g: np.ndarray,
    parent: np.ndarray,
    mark: np.ndarray,
    heap: np.ndarray,
    pos: np.ndarray,
    size: np.ndarray,
    open_mark: int,
    closed_mark: int,
    v: int,
    d: int,
    step: float,
    gu: float,
    cu: float,
    r: int,
    c: int,
    gr: int,
    gc: int,
    octile: bool,
    scale: float,
    next_f: float,
    next_key: float,
    next_v: int,
) -> tuple[float, float, int]:
    """Try the move ``d`` to cell ``v`` = (r, c); return the updated next-node candidate.

    The candidate (next_f, next_key, next_v) is the best improved neighbour that
    is not queued; it is kept out of the heap because it is often the very node
    the next pop would return (next_v = -1: none yet).
    """
    cv = flat[v]
    if cv == np.inf:
        return next_f, next_key, next_v
    m = mark[v]
    if m == closed_mark:
        return next_f, next_key, next_v
    new_g = gu + step * 0.5 * (cu + cv)
    # g of a cell this search has not reached is stale: test the mark first.
    if m == open_mark and new_g >= g[v]:
        return next_f, next_key, next_v
    g[v] = new_g
    parent[v] = d
    mark[v] = open_mark
    h = _cells_to_goal(r, c, gr, gc, octile)
    f = new_g + scale * h
    # Ties in f go to the cell nearer the goal, which keeps A* from expanding
    # whole plateaus of equal f.
    key = tie_key(h, v)
    if pos[v] < 0 and (f < next_f or (f == next_f and key < next_key)):
        if next_v >= 0:
            push(heap, pos, size, next_f, next_key)
        return f, key, v
    push(heap, pos, size, f, key)
    return next_f, next_key, next_v


@njit_no_refcount
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
    heap: np.ndarray,
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
        Grid shape; ``rows * cols`` at most ``_search_heap.MAX_NODES``.
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
    g, parent, mark, heap, pos, size, stamp
        Scratch from :func:`navkit.planning.grid._workspace.workspace` (at least
        ``rows * cols`` cells). On return ``mark[v] == stamp + 1`` for every
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

    Notes
    -----
    The queue orders cells by (f, tie key) with f = g + scale × distance in
    cells; the order is total, so the search is deterministic. After expanding
    a cell, its best improved neighbour that is not queued is expanded next
    directly when it precedes the heap's top, which is exactly the cell a push
    and pop would return, without the two heap walks. The eight moves are
    written out one by one so each has constant offsets and bounds tests.
    """
    open_mark = stamp
    closed_mark = stamp + 1
    gr = goal // cols if goal >= 0 else 0
    gc = goal - gr * cols if goal >= 0 else 0
    g[start] = 0.0
    parent[start] = -1
    mark[start] = open_mark
    expanded = 0
    found = False
    u = start
    while True:
        mark[u] = closed_mark
        expanded += 1
        if u == goal:
            found = True
            break
        r = u // cols
        c = u - r * cols
        gu = g[u]
        cu = flat[u]
        n_in = r > 0
        s_in = r + 1 < rows
        w_in = c > 0
        e_in = c + 1 < cols
        nf = np.inf
        nk = np.inf
        nv = -1
        if n_in:
            nf, nk, nv = _relax(flat, g, parent, mark, heap, pos, size, open_mark, closed_mark,
                                u - cols, 0, 1.0, gu, cu, r - 1, c, gr, gc, eight, scale,
                                nf, nk, nv)
        if s_in:
            nf, nk, nv = _relax(flat, g, parent, mark, heap, pos, size, open_mark, closed_mark,
                                u + cols, 1, 1.0, gu, cu, r + 1, c, gr, gc, eight, scale,
                                nf, nk, nv)
        if w_in:
            nf, nk, nv = _relax(flat, g, parent, mark, heap, pos, size, open_mark, closed_mark,
                                u - 1, 2, 1.0, gu, cu, r, c - 1, gr, gc, eight, scale,
                                nf, nk, nv)
        if e_in:
            nf, nk, nv = _relax(flat, g, parent, mark, heap, pos, size, open_mark, closed_mark,
                                u + 1, 3, 1.0, gu, cu, r, c + 1, gr, gc, eight, scale,
                                nf, nk, nv)
        if eight:
            if corner_cutting:
                nw = n_in and w_in
                ne = n_in and e_in
                sw = s_in and w_in
                se = s_in and e_in
            else:
                # A diagonal needs both cells it passes beside (MovingAI rule).
                n_ok = n_in and flat[u - cols] < np.inf
                s_ok = s_in and flat[u + cols] < np.inf
                w_ok = w_in and flat[u - 1] < np.inf
                e_ok = e_in and flat[u + 1] < np.inf
                nw = n_ok and w_ok
                ne = n_ok and e_ok
                sw = s_ok and w_ok
                se = s_ok and e_ok
            if nw:
                nf, nk, nv = _relax(flat, g, parent, mark, heap, pos, size, open_mark,
                                    closed_mark, u - cols - 1, 4, SQRT2, gu, cu, r - 1, c - 1,
                                    gr, gc, eight, scale, nf, nk, nv)
            if ne:
                nf, nk, nv = _relax(flat, g, parent, mark, heap, pos, size, open_mark,
                                    closed_mark, u - cols + 1, 5, SQRT2, gu, cu, r - 1, c + 1,
                                    gr, gc, eight, scale, nf, nk, nv)
            if sw:
                nf, nk, nv = _relax(flat, g, parent, mark, heap, pos, size, open_mark,
                                    closed_mark, u + cols - 1, 6, SQRT2, gu, cu, r + 1, c - 1,
                                    gr, gc, eight, scale, nf, nk, nv)
            if se:
                nf, nk, nv = _relax(flat, g, parent, mark, heap, pos, size, open_mark,
                                    closed_mark, u + cols + 1, 7, SQRT2, gu, cu, r + 1, c + 1,
                                    gr, gc, eight, scale, nf, nk, nv)
        if nv >= 0:
            if precedes_top(heap, size, nf, nk):
                u = nv
                continue
            push(heap, pos, size, nf, nk)
        if size[0] == 0:
            break
        u = pop(heap, pos, size)
    clear(heap, pos, size)
    return expanded, found


@njit_cached
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
