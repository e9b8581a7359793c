"""numba kernels for Field D* and 8-connected D* Lite on cell corners (private).

Geometry. Cell ``(r, c)`` covers ``[r, r+1] × [c, c+1]`` in continuous
``(row, col)`` grid coordinates; the search nodes are the integer corners, node
``(i, j)`` having flat index ``i * ncols + j`` with ``ncols = cols + 1``. Cell
costs are read from a padded flat array ``pad`` of shape ``(rows+2) * (cols+2)``
whose border is ``+inf``, so cell ``(r, c)`` (``-1 <= r <= rows``,
``-1 <= c <= cols``) is ``pad[(r + 1) * width + c + 1]`` with ``width = cols + 2``
and no bounds checks are needed.

Search. D* Lite (Koenig & Likhachev 2002, optimised version) searching backwards
from the goal: ``g`` and ``rhs`` are cost-to-goal estimates, keys are
``(min(g, rhs) + h(start, s) + km, min(g, rhs))``. ``rhs(s)`` is the minimum over
the eight consecutive neighbour pairs of :func:`corner_cost` (Field D*, Ferguson
& Stentz) or, with ``interp`` false, over the classic 8-connected moves.

Heuristic. ``h = hscale * octile(start, s)``, with ``hscale = 1`` for the
8-connected search and ``1/sqrt(2)`` for Field D*. Interpolation makes a node's
cost depend on both nodes of a pair, including the costlier one, and a plain
admissible heuristic then lets the search settle a node before the pair partner
that lowers it (measured on a 1024² random map with the octile distance scaled
by 1/1.082 to be admissible: 1.85 expansions per node, and the search stopped
with a start cost 3e-5 too high). Every option of :func:`corner_cost` exceeds
each neighbour cost it uses by at least 1/sqrt(2) for the axis neighbour
(``min(b, c) >= 1`` along the edge, ``sqrt(c^2 - f^2) > c/sqrt(2)`` through the
cell) and at least ``c >= 1`` for the diagonal one, while h changes by at most
``hscale`` resp. ``hscale * sqrt(2)`` between neighbours; so with the factor
1/sqrt(2) the key of a node is never below the keys of the nodes its cost
depends on: each node is expanded once per search and the stopping rule is
exact. (Costs are >= 1, so this holds after any cost update.)

Calling convention. The search kernels take the planner's arrays as one tuple
``st = (pad, g, rhs, nodes, keys, pos, size)`` (``nodes, keys, pos, size`` being
the indexed heap of :mod:`navkit.planning.grid._dstar_heap`) and its scalars as
``prm = (width, nrows, ncols, start_row, start_col, goal, km, interp, hscale)``;
both are built by :func:`state` and :func:`params`.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
from numba import njit

from navkit.planning.grid._dstar_heap import heap_push, heap_remove

SQRT2 = math.sqrt(2.0)
FIELD_HSCALE = 1.0 / SQRT2
_OCT = SQRT2 - 1.0
# Least cost above g(u) of any option through an axis neighbour u (cell costs >= 1).
_AXIS_GAIN = 1.0 / SQRT2

# Status codes of :func:`extract_path`.
OK = 0
NO_PATH = 1
STUCK = 2

# Ring of the 8 neighbours, counter-clockwise from east: even entries are the
# axis neighbours, odd entries the diagonal ones. Pair k is (ring[k], ring[k+1]).
RING_R = np.array([0, -1, -1, -1, 0, 1, 1, 1], dtype=np.int64)
RING_C = np.array([1, 1, 0, -1, -1, -1, 0, 1], dtype=np.int64)


def _pair_tables() -> tuple[np.ndarray, ...]:
    """Per pair k: axis node, diagonal node, crossed cell c and edge-side cell b.

    Cells are given as (row, col) offsets in {0, 1} from the padded index of the
    node's NW cell (padded (i, j) is cell (i - 1, j - 1)).
    """
    ar = np.empty(8, np.int64)
    ac = np.empty(8, np.int64)
    dr = np.empty(8, np.int64)
    dc = np.empty(8, np.int64)
    cr = np.empty(8, np.int64)
    cc = np.empty(8, np.int64)
    br = np.empty(8, np.int64)
    bc = np.empty(8, np.int64)
    for k in range(8):
        k2 = (k + 1) % 8
        a, d = (k, k2) if k % 2 == 0 else (k2, k)
        ar[k], ac[k] = RING_R[a], RING_C[a]
        dr[k], dc[k] = RING_R[d], RING_C[d]
        # The cell holding s, a and d lies on d's side in both axes.
        cr[k] = 0 if dr[k] < 0 else 1
        cc[k] = 0 if dc[k] < 0 else 1
        # b shares the edge s-a with c, on the other side of it.
        if ar[k] == 0:
            br[k], bc[k] = 1 - cr[k], cc[k]
        else:
            br[k], bc[k] = cr[k], 1 - cc[k]
    return ar, ac, dr, dc, cr, cc, br, bc


PAIR_AR, PAIR_AC, PAIR_DR, PAIR_DC, PAIR_CR, PAIR_CC, PAIR_BR, PAIR_BC = _pair_tables()


def state(
    pad: np.ndarray, g: np.ndarray, rhs: np.ndarray, heap: tuple[np.ndarray, ...]
) -> tuple[np.ndarray, ...]:
    """The ``st`` tuple of the search kernels."""
    return (pad, g, rhs, *heap)


def params(
    width: int,
    nrows: int,
    ncols: int,
    start: tuple[int, int],
    goal: int,
    km: float,
    interp: bool,
    hscale: float,
) -> tuple[Any, ...]:
    """The ``prm`` tuple of the search kernels (types fixed so numba compiles once)."""
    return (int(width), int(nrows), int(ncols), int(start[0]), int(start[1]), int(goal),
            float(km), bool(interp), float(hscale))


@njit(cache=True, inline="always")
def corner_cost(g1: float, g2: float, c: float, b: float, interp: bool) -> float:
    """Cost-to-goal of a node through the edge between neighbours s1 and s2.

    ``s1`` is the axis neighbour (distance 1), ``s2`` the diagonal one, ``c`` the
    cost of the cell with corners s, s1, s2 and ``b`` that of the cell on the
    other side of the edge s-s1; ``g1``, ``g2`` their cost-to-goal. The options,
    each the cost of a real path through the cell under linear interpolation of
    g along the edge s1-s2, are

    A. along the edge s-s1 (paying min(b, c)), then ``g1``;
    B. the diagonal through c to s2;
    C. through c to the point at distance y from s1 on the edge s1-s2:
       ``c sqrt(1 + y^2) + f (1 - y) + g2`` with f = g1 - g2 and the optimal
       ``y = f / sqrt(c^2 - f^2)`` (when it is < 1);
    D. a distance x along the edge s-s1 at cost b, then straight through c to
       s2: ``b x + c sqrt(1 + (1 - x)^2) + g2`` with the optimal
       ``1 - x = b / sqrt(c^2 - b^2)`` (when it is < 1).

    Ferguson & Stentz pick one of C and D by testing ``f <= b`` and one of A and
    the rest by ``g1 <= g2``; here the minimum over every option that applies is
    taken. That is never larger than the paper's value and equals it wherever the
    paper's branch is the cheapest; it also keeps the along-edge option A when
    the crossed cell c is impassable and g1 > g2, where the paper's formula gives
    infinity for this pair (the node value is unaffected: the neighbouring pair,
    which crosses b, covers that edge). With
    ``interp`` false only A and B remain: the classic 8-connected move costs.
    """
    best = min(c, b) + g1
    if c < np.inf:
        v = c * SQRT2 + g2
        if v < best:
            best = v
        if interp and g2 < g1:
            if g1 < np.inf:
                f = g1 - g2
                if f < c:
                    y = f / math.sqrt(c * c - f * f)
                    if y < 1.0:
                        v = c * math.sqrt(1.0 + y * y) + f * (1.0 - y) + g2
                        if v < best:
                            best = v
            if b < c:
                w = b / math.sqrt(c * c - b * b)
                if w < 1.0:
                    v = c * math.sqrt(1.0 + w * w) + b * (1.0 - w) + g2
                    if v < best:
                        best = v
    return best


@njit(cache=True, inline="always")
def _h(sr: int, sc: int, i: int, j: int, hscale: float) -> float:
    dr = abs(i - sr)
    dc = abs(j - sc)
    if dr < dc:
        return hscale * (dc + _OCT * dr)
    return hscale * (dr + _OCT * dc)


@njit(cache=True, inline="always")
def _pair_value(
    pad: np.ndarray, width: int, g: np.ndarray, ncols: int, i: int, j: int, k: int, interp: bool
) -> float:
    base = i * width + j
    c = pad[base + PAIR_CR[k] * width + PAIR_CC[k]]
    b = pad[base + PAIR_BR[k] * width + PAIR_BC[k]]
    if c == np.inf and b == np.inf:
        return np.inf
    # The axis node is a corner of whichever of b, c is finite: always on the grid.
    g1 = g[(i + PAIR_AR[k]) * ncols + j + PAIR_AC[k]]
    if c == np.inf:
        return float(b + g1)
    return corner_cost(g1, g[(i + PAIR_DR[k]) * ncols + j + PAIR_DC[k]], c, b, interp)


@njit(cache=True)
def node_rhs(
    pad: np.ndarray, width: int, g: np.ndarray, ncols: int, i: int, j: int, interp: bool
) -> float:
    """Minimum over the eight neighbour pairs of node (i, j)."""
    best = np.inf
    for k in range(8):
        v = _pair_value(pad, width, g, ncols, i, j, k, interp)
        if v < best:
            best = v
    return best


@njit(cache=True, inline="always")
def _update_vertex(
    s: int,
    g: np.ndarray,
    rhs: np.ndarray,
    nodes: np.ndarray,
    keys: np.ndarray,
    pos: np.ndarray,
    size: np.ndarray,
    ncols: int,
    sr: int,
    sc: int,
    km: float,
    hscale: float,
) -> None:
    if g[s] != rhs[s]:
        m = min(g[s], rhs[s])
        i = s // ncols
        heap_push(nodes, keys, pos, size, s, m + _h(sr, sc, i, s - i * ncols, hscale) + km, m)
    elif pos[s] >= 0:
        heap_remove(nodes, keys, pos, size, s)


@njit(cache=True)
def settle(
    st: tuple[np.ndarray, ...],
    prm: tuple[Any, ...],
    target: int,
) -> int:
    """D* Lite ``ComputeShortestPath`` run until node ``target`` is settled.

    On return ``g[target]`` is its exact cost-to-goal (``inf`` if unreachable):
    the target is locally consistent and no queued key is below its key. Called
    with the start as target this is the plain D* Lite search; the path
    extraction calls it again for every node it reads, so every value it uses is
    exact and the same in a fresh plan and in a repaired one. Returns the number
    of expansions.
    """
    pad, g, rhs, nodes, keys, pos, size = st
    width, nrows, ncols, sr, sc, goal, km, interp, hscale = prm
    ti = target // ncols
    th = _h(sr, sc, ti, target - ti * ncols, hscale)
    expanded = 0
    while size[0] > 0:
        mt = min(g[target], rhs[target])
        t1 = mt + th + km
        top0 = keys[0, 0]
        top1 = keys[0, 1]
        if not (top0 < t1 or (top0 == t1 and top1 < mt) or g[target] != rhs[target]):
            break
        u = nodes[0]
        ui = u // ncols
        uj = u - ui * ncols
        if km > 0.0:
            # Keys stored before the start moved may be low: requeue with the
            # current one (with km == 0 the start never moved and keys are exact).
            mu = min(g[u], rhs[u])
            k0 = mu + _h(sr, sc, ui, uj, hscale) + km
            if top0 < k0 or (top0 == k0 and top1 < mu):
                heap_push(nodes, keys, pos, size, u, k0, mu)
                continue
        expanded += 1
        if g[u] > rhs[u]:
            g[u] = rhs[u]
            gu = g[u]
            heap_remove(nodes, keys, pos, size, u)
            for m in range(8):
                si = ui - RING_R[m]
                sj = uj - RING_C[m]
                if si < 0 or si >= nrows or sj < 0 or sj >= ncols:
                    continue
                s = si * ncols + sj
                # Every option through u costs at least g(u) + 1/sqrt(2) (u an
                # axis neighbour of s) or g(u) + 1 (diagonal), see the module
                # notes; a neighbour already below that cannot improve.
                gain = _AXIS_GAIN if m % 2 == 0 else 1.0
                if s == goal or rhs[s] <= gu + gain - 1e-9 * (1.0 + gu):
                    continue
                # u is ring[m] of s: only the pairs m-1 and m of s contain it.
                v = _pair_value(pad, width, g, ncols, si, sj, m, interp)
                v2 = _pair_value(pad, width, g, ncols, si, sj, m - 1 if m > 0 else 7, interp)
                if v2 < v:
                    v = v2
                if v < rhs[s]:
                    rhs[s] = v
                    _update_vertex(s, g, rhs, nodes, keys, pos, size, ncols, sr, sc, km, hscale)
        else:
            g[u] = np.inf
            for m in range(9):
                if m < 8:
                    si = ui - RING_R[m]
                    sj = uj - RING_C[m]
                    if si < 0 or si >= nrows or sj < 0 or sj >= ncols:
                        continue
                else:
                    si = ui
                    sj = uj
                s = si * ncols + sj
                if s != goal:
                    rhs[s] = node_rhs(pad, width, g, ncols, si, sj, interp)
                _update_vertex(s, g, rhs, nodes, keys, pos, size, ncols, sr, sc, km, hscale)
    return expanded


@njit(cache=True)
def update_cells(
    st: tuple[np.ndarray, ...],
    prm: tuple[Any, ...],
    cell_r: np.ndarray,
    cell_c: np.ndarray,
    values: np.ndarray,
) -> None:
    """Write new cell costs and requeue the four corners of every changed cell.

    ``rhs`` of a node depends only on the four cells around it, so these corners
    are the only nodes whose ``rhs`` can change.
    """
    pad, g, rhs, nodes, keys, pos, size = st
    width, _, ncols, sr, sc, goal, km, interp, hscale = prm
    for n in range(cell_r.shape[0]):
        pad[(cell_r[n] + 1) * width + cell_c[n] + 1] = values[n]
    for n in range(cell_r.shape[0]):
        for di in range(2):
            for dj in range(2):
                i = cell_r[n] + di
                j = cell_c[n] + dj
                s = i * ncols + j
                if s == goal:
                    continue
                rhs[s] = node_rhs(pad, width, g, ncols, i, j, interp)
                _update_vertex(s, g, rhs, nodes, keys, pos, size, ncols, sr, sc, km, hscale)


@njit(cache=True, inline="always")
def _cell(pad: np.ndarray, width: int, r: int, c: int) -> float:
    return float(pad[(r + 1) * width + c + 1])


@njit(cache=True)
def _edge_min(
    pr: float,
    pc: float,
    e0r: float,
    e0c: float,
    tr: float,
    tc: float,
    g0: float,
    g1: float,
    c: float,
    out: np.ndarray,
    n: int,
) -> int:
    """Best point q = e0 + u t (u in [0, 1], t a unit axis vector) on one edge.

    Minimises ``c |p - q| + (1 - u) g0 + u g1``, a convex function of u whose
    stationary point is ``u0 - k d / sqrt(c^2 - k^2)`` (k = g1 - g0, u0 the
    projection of p and d its distance to the edge line). Appends the candidate
    (cost to q, value at q, q) to ``out`` and returns the new count.
    """
    if g0 == np.inf and g1 == np.inf:
        return n
    wr = pr - e0r
    wc = pc - e0c
    u0 = wr * tr + wc * tc
    d = abs(wr * tc - wc * tr)
    best_u = 0.0
    best = np.inf
    if g0 < np.inf:
        best = c * math.hypot(d, u0) + g0
    if g1 < np.inf:
        v = c * math.hypot(d, 1.0 - u0) + g1
        if v < best:
            best = v
            best_u = 1.0
    if g0 < np.inf and g1 < np.inf and d > 0.0:
        k = g1 - g0
        if abs(k) < c:
            u = u0 - k * d / math.sqrt(c * c - k * k)
            if 0.0 < u < 1.0:
                v = c * math.hypot(d, u - u0) + g0 + k * u
                if v < best:
                    best = v
                    best_u = u
    if best_u == 0.0:
        qr, qc, gq = e0r, e0c, g0
    elif best_u == 1.0:
        qr, qc, gq = e0r + tr, e0c + tc, g1
    else:
        qr = e0r + best_u * tr
        qc = e0c + best_u * tc
        gq = g0 + (g1 - g0) * best_u
    out[n, 0] = c * math.hypot(pr - qr, pc - qc)
    out[n, 1] = gq
    out[n, 2] = qr
    out[n, 3] = qc
    return n + 1


@njit(cache=True)
def _node_value(
    st: tuple[np.ndarray, ...],
    prm: tuple[Any, ...],
    i: int,
    j: int,
    counter: np.ndarray,
) -> float:
    """Exact cost-to-goal of node (i, j), settling it first (expansions -> counter)."""
    g = st[1]
    ncols = prm[2]
    counter[0] += settle(st, prm, i * ncols + j)
    return float(g[i * ncols + j])


@njit(cache=True, inline="always")
def _line_cost(pad: np.ndarray, width: int, pr: float, pc: float, i: int, j: int) -> float:
    """Cost per unit length along the grid line from p to node (i, j) (one cell long)."""
    if pr == i:
        col = math.floor(min(pc, j))
        return min(_cell(pad, width, i - 1, col), _cell(pad, width, i, col))
    row = math.floor(min(pr, i))
    return min(_cell(pad, width, row, j - 1), _cell(pad, width, row, j))


@njit(cache=True)
def _line_candidate(
    st: tuple[np.ndarray, ...],
    prm: tuple[Any, ...],
    pr: float,
    pc: float,
    i: int,
    j: int,
    counter: np.ndarray,
    out: np.ndarray,
    n: int,
) -> int:
    """Append the move along the grid line from p to the node (i, j) if it is open."""
    pad = st[0]
    width, nrows, ncols = prm[0], prm[1], prm[2]
    if i < 0 or i >= nrows or j < 0 or j >= ncols:
        return n
    edge = _line_cost(pad, width, pr, pc, i, j)
    if edge == np.inf:
        return n
    gq = _node_value(st, prm, i, j, counter)
    if gq == np.inf:
        return n
    out[n, 0] = edge * math.hypot(pr - i, pc - j)
    out[n, 1] = gq
    out[n, 2] = i
    out[n, 3] = j
    return n + 1


@njit(cache=True)
def _candidates(
    st: tuple[np.ndarray, ...],
    prm: tuple[Any, ...],
    pr: float,
    pc: float,
    counter: np.ndarray,
    out: np.ndarray,
) -> int:
    """Next-point candidates of the interpolated path from point p on the grid lines.

    Rows of ``out``: (cost from p to q, interpolated cost-to-goal at q, q_row,
    q_col). They are: the optimal crossing point of every far edge of every
    passable cell touching p, the ends of the grid edges through p (paying the
    cheaper cell beside the edge) and, from a node, the point where option D of
    :func:`corner_cost` leaves the cheap edge.
    """
    pad = st[0]
    width = prm[0]
    n = 0
    fr = math.floor(pr)
    fc = math.floor(pc)
    on_r = pr == fr
    on_c = pc == fc
    r_lo = int(fr) - 1 if on_r else int(fr)
    c_lo = int(fc) - 1 if on_c else int(fc)
    for r in range(r_lo, int(fr) + 1):
        for c in range(c_lo, int(fc) + 1):
            cost = _cell(pad, width, r, c)
            if cost == np.inf:
                continue
            g00 = _node_value(st, prm, r, c, counter)
            g01 = _node_value(st, prm, r, c + 1, counter)
            g10 = _node_value(st, prm, r + 1, c, counter)
            g11 = _node_value(st, prm, r + 1, c + 1, counter)
            if pr != r:
                n = _edge_min(pr, pc, r, c, 0.0, 1.0, g00, g01, cost, out, n)
            if pr != r + 1:
                n = _edge_min(pr, pc, r + 1, c, 0.0, 1.0, g10, g11, cost, out, n)
            if pc != c:
                n = _edge_min(pr, pc, r, c, 1.0, 0.0, g00, g10, cost, out, n)
            if pc != c + 1:
                n = _edge_min(pr, pc, r, c + 1, 1.0, 0.0, g01, g11, cost, out, n)
    # Along the grid lines through p, to the nearest nodes on either side.
    for side in range(2):
        if on_r:
            j = int(fc) - 1 + 2 * side if on_c else int(fc) + side
            n = _line_candidate(st, prm, pr, pc, int(fr), j, counter, out, n)
        if on_c:
            i = int(fr) - 1 + 2 * side if on_r else int(fr) + side
            n = _line_candidate(st, prm, pr, pc, i, int(fc), counter, out, n)
    if on_r and on_c:
        i = int(fr)
        j = int(fc)
        base = i * width + j
        for k in range(8):
            c = pad[base + PAIR_CR[k] * width + PAIR_CC[k]]
            b = pad[base + PAIR_BR[k] * width + PAIR_BC[k]]
            if not b < c or c == np.inf:
                continue
            w = b / math.sqrt(c * c - b * b)
            if w >= 1.0:
                continue
            g2 = _node_value(st, prm, i + PAIR_DR[k], j + PAIR_DC[k], counter)
            if g2 == np.inf:
                continue
            x = 1.0 - w
            out[n, 0] = b * x
            out[n, 1] = c * math.sqrt(1.0 + w * w) + g2
            out[n, 2] = i + x * PAIR_AR[k]
            out[n, 3] = j + x * PAIR_AC[k]
            n += 1
    return n


@njit(cache=True)
def _push_point(pts: np.ndarray, k: int, r: float, c: float) -> np.ndarray:
    if k == pts.shape[0]:
        grown = np.empty((2 * k, 2), dtype=np.float64)
        grown[:k] = pts
        pts = grown
    pts[k, 0] = r
    pts[k, 1] = c
    return pts


@njit(cache=True)
def _descend(
    st: tuple[np.ndarray, ...],
    prm: tuple[Any, ...],
    pr: float,
    pc: float,
    cur: float,
    counter: np.ndarray,
) -> tuple[float, float, float, float]:
    """Cheapest straight step from p to a corner of a passable cell touching p.

    Only corners whose cost-to-goal is below ``cur`` qualify. From a node this
    is the 8-connected move set (an axis move is offered by both cells beside
    the edge, so it pays the cheaper one). Returns (total, g at the corner,
    corner row, corner col), total = inf when no corner qualifies.
    """
    pad = st[0]
    width = prm[0]
    best = np.inf
    best_g = np.inf
    qr = 0.0
    qc = 0.0
    fr = math.floor(pr)
    fc = math.floor(pc)
    r_lo = int(fr) - 1 if pr == fr else int(fr)
    c_lo = int(fc) - 1 if pc == fc else int(fc)
    for r in range(r_lo, int(fr) + 1):
        for c in range(c_lo, int(fc) + 1):
            cost = _cell(pad, width, r, c)
            if cost == np.inf:
                continue
            for di in range(2):
                for dj in range(2):
                    i = r + di
                    j = c + dj
                    if i == pr and j == pc:
                        continue
                    gn = _node_value(st, prm, i, j, counter)
                    if not gn < cur:
                        continue
                    di_r = i - pr
                    dj_c = j - pc
                    if di_r == 0.0 or dj_c == 0.0:
                        # Along a grid line: the cheaper cell beside it is paid.
                        t = min(cost, _line_cost(pad, width, pr, pc, i, j)) * math.hypot(
                            di_r, dj_c) + gn
                    else:
                        t = cost * math.hypot(di_r, dj_c) + gn
                    if t < best:
                        best = t
                        best_g = gn
                        qr = float(i)
                        qc = float(j)
    return best, best_g, qr, qc


@njit(cache=True)
def extract_path(
    st: tuple[np.ndarray, ...],
    prm: tuple[Any, ...],
    lookahead: bool,
) -> tuple[np.ndarray, int, int, int]:
    """Settle the start and follow the cost field from it to the goal.

    Interpolated mode: at each point take the candidate of :func:`_candidates`
    minimising (cost to q) + (cost-to-goal at q), where with ``lookahead`` the
    cost-to-goal of a q inside an edge is not its linear interpolation but the
    best one-step continuation from q. The estimate must decrease at every step;
    when no candidate lowers it, :func:`_descend` takes a straight step to a
    corner of lower exact cost-to-goal (one always exists), so the node values
    met along the walk strictly decrease and it ends at the goal. 8-connected
    mode takes only :func:`_descend` steps: an optimal D* Lite path.

    Returns (points (K', 2) with the first K valid, K, expansions, status).
    """
    g = st[1]
    nrows, ncols, sr, sc, goal, interp = prm[1], prm[2], prm[3], prm[4], prm[5], prm[7]
    start = sr * ncols + sc
    counter = np.zeros(1, dtype=np.int64)
    counter[0] = settle(st, prm, start)
    pts = np.empty((4 * (nrows + ncols), 2), dtype=np.float64)
    if g[start] == np.inf:
        return pts, 0, counter[0], NO_PATH
    gi = goal // ncols
    gj = goal - gi * ncols
    pts = _push_point(pts, 0, sr, sc)
    k = 1
    pr = float(sr)
    pc = float(sc)
    cur = g[start]
    cand = np.empty((32, 4), dtype=np.float64)
    cand2 = np.empty((32, 4), dtype=np.float64)
    max_steps = 4 * nrows * ncols + 16
    for _ in range(max_steps):
        if pr == gi and pc == gj:
            return pts, k, counter[0], OK
        best = np.inf
        best_v = np.inf
        qr = 0.0
        qc = 0.0
        if interp:
            n = _candidates(st, prm, pr, pc, counter, cand)
            for a in range(n):
                v = cand[a, 1]
                cr = cand[a, 2]
                cc = cand[a, 3]
                if lookahead and (cr != math.floor(cr) or cc != math.floor(cc)):
                    n2 = _candidates(st, prm, cr, cc, counter, cand2)
                    la = np.inf
                    for b2 in range(n2):
                        t = cand2[b2, 0] + cand2[b2, 1]
                        if t < la:
                            la = t
                    v = la
                t = cand[a, 0] + v
                if t < best and v < cur:
                    best = t
                    best_v = v
                    qr = cr
                    qc = cc
        if best == np.inf:
            best, best_v, qr, qc = _descend(st, prm, pr, pc, cur, counter)
            if best == np.inf:
                return pts, k, counter[0], STUCK
        pts = _push_point(pts, k, qr, qc)
        k += 1
        pr = qr
        pc = qc
        cur = best_v
    return pts, k, counter[0], STUCK


@njit(cache=True)
def segment_cost(pad: np.ndarray, width: int, r0: float, c0: float, r1: float, c1: float) -> float:
    """Exact cost of the straight segment p0 -> p1: sum of length × cell cost.

    The segment is split where it crosses grid lines; each piece pays the cell
    containing its midpoint, or the cheaper of the two cells beside a grid line
    it runs along. Pieces shorter than 1e-12 (passing through a corner) are free.
    """
    dr = r1 - r0
    dc = c1 - c0
    length = math.hypot(dr, dc)
    if length == 0.0:
        return 0.0
    total = 0.0
    t = 0.0
    # Index of the next integer line in each axis, stepped by counters to avoid drift.
    if dr > 0:
        nr_line = math.floor(r0) + 1.0
    elif dr < 0:
        nr_line = math.ceil(r0) - 1.0
    else:
        nr_line = 0.0
    if dc > 0:
        nc_line = math.floor(c0) + 1.0
    elif dc < 0:
        nc_line = math.ceil(c0) - 1.0
    else:
        nc_line = 0.0
    step_r = 1.0 if dr > 0 else -1.0
    step_c = 1.0 if dc > 0 else -1.0
    while t < 1.0:
        tr = (nr_line - r0) / dr if dr != 0.0 else np.inf
        tc = (nc_line - c0) / dc if dc != 0.0 else np.inf
        t1 = min(tr, tc, 1.0)
        if tr <= t1:
            nr_line += step_r
        if tc <= t1:
            nc_line += step_c
        piece = (t1 - t) * length
        if piece > 1e-12:
            tm = 0.5 * (t + t1)
            mr = r0 + tm * dr
            mc = c0 + tm * dc
            rr = round(mr)
            rc = round(mc)
            if abs(mr - rr) < 1e-9 and abs(dr) * (t1 - t) < 1e-9:
                col = math.floor(mc)
                cost = min(_cell(pad, width, int(rr) - 1, col), _cell(pad, width, int(rr), col))
            elif abs(mc - rc) < 1e-9 and abs(dc) * (t1 - t) < 1e-9:
                row = math.floor(mr)
                cost = min(_cell(pad, width, row, int(rc) - 1), _cell(pad, width, row, int(rc)))
            else:
                cost = _cell(pad, width, math.floor(mr), math.floor(mc))
            if cost == np.inf:
                return np.inf
            total += cost * piece
        t = t1
    return total


@njit(cache=True)
def polyline_cost(pad: np.ndarray, width: int, pts: np.ndarray, k: int) -> tuple[float, float]:
    """(cost, length) of the polyline through the first ``k`` points."""
    cost = 0.0
    length = 0.0
    for a in range(k - 1):
        cost += segment_cost(pad, width, pts[a, 0], pts[a, 1], pts[a + 1, 0], pts[a + 1, 1])
        length += math.hypot(pts[a + 1, 0] - pts[a, 0], pts[a + 1, 1] - pts[a, 1])
    return cost, length


@njit(cache=True)
def shortcut(pad: np.ndarray, width: int, pts: np.ndarray, k: int, patience: int) -> np.ndarray:
    """Replace runs of the polyline by straight segments that cost no more.

    From each kept point, the farthest later point whose straight segment costs
    at most the polyline between them is kept next; the scan gives up after
    ``patience`` consecutive refusals. The result's cost never exceeds the
    input's, and a segment through an impassable cell interior costs inf, so it
    is never taken.
    """
    out = np.empty((k, 2), dtype=np.float64)
    out[0] = pts[0]
    m = 1
    i = 0
    while i < k - 1:
        best = i + 1
        acc = 0.0
        misses = 0
        j = i + 1
        while j < k:
            acc += segment_cost(pad, width, pts[j - 1, 0], pts[j - 1, 1], pts[j, 0], pts[j, 1])
            if j > i + 1:
                direct = segment_cost(pad, width, pts[i, 0], pts[i, 1], pts[j, 0], pts[j, 1])
                if direct <= acc * (1.0 + 1e-12):
                    best = j
                    misses = 0
                else:
                    misses += 1
                    if misses > patience:
                        break
            j += 1
        out[m] = pts[best]
        m += 1
        i = best
    res: np.ndarray = out[:m].copy()
    return res
