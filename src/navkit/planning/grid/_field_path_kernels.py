"""numba kernels extracting the Field D* path from the D* Lite cost field (private).

The walk starts at the start node and at each point (a node or a point on a
grid line) steps to the best crossing point of the far edges of the cells
around it, settling (:func:`navkit.planning.grid._dstar_lite_kernels.settle`)
every node value it reads first. Points are in node coordinates (cell
``(r, c)`` covers ``[r, r+1] × [c, c+1]``); the ``st``/``prm`` calling convention
is that of :mod:`navkit.planning.grid._dstar_lite_kernels`.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from navkit._shared.jit import njit_cached, njit_inline
from navkit.planning.grid._dstar_lite_kernels import (
    PAIR_AC,
    PAIR_AR,
    PAIR_BC,
    PAIR_BR,
    PAIR_CC,
    PAIR_CR,
    PAIR_DC,
    PAIR_DR,
    heuristic,
    key_reached,
    settle,
)
from navkit.planning.grid._polyline_kernels import cell_cost

# Status codes of :func:`extract_path`.
OK = 0
NO_PATH = 1
STUCK = 2
# The work limit of the state (``work[1]``) was reached: the repair was cut short.
ABORTED = 3


@njit_cached
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


@njit_inline
def _node_value(
    st: tuple[np.ndarray, ...],
    prm: tuple[Any, ...],
    i: int,
    j: int,
    counter: np.ndarray,
) -> float:
    """Exact cost-to-goal of node (i, j), settling it first (expansions -> counter).

    A node already settled (consistent, its key not above the queue's top, the
    stopping rule of :func:`settle`) is read without calling :func:`settle`.
    """
    g = st[1]
    rhs = st[2]
    keys = st[4]
    size = st[6]
    ncols = prm[2]
    s = i * ncols + j
    gs = g[s]
    if gs == rhs[s] and (
        size[0] == 0
        or key_reached(keys[0, 0], keys[0, 1], gs, heuristic(prm[3], prm[4], i, j, prm[8]),
                       prm[6])
    ):
        return float(gs)
    counter[0] += settle(st, prm, s)
    return float(g[s])


@njit_inline
def _line_cost(pad: np.ndarray, width: int, pr: float, pc: float, i: int, j: int) -> float:
    """Cost per unit length along the grid line from p to node (i, j) (one cell long)."""
    if pr == i:
        col = math.floor(min(pc, j))
        return min(cell_cost(pad, width, i - 1, col), cell_cost(pad, width, i, col))
    row = math.floor(min(pr, i))
    return min(cell_cost(pad, width, row, j - 1), cell_cost(pad, width, row, j))


@njit_cached
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


@njit_cached
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
            cost = cell_cost(pad, width, r, c)
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


@njit_cached
def _push_point(pts: np.ndarray, k: int, r: float, c: float) -> np.ndarray:
    if k == pts.shape[0]:
        grown = np.empty((2 * k, 2), dtype=np.float64)
        grown[:k] = pts
        pts = grown
    pts[k, 0] = r
    pts[k, 1] = c
    return pts


@njit_cached
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
            cost = cell_cost(pad, width, r, c)
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


@njit_cached
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
    corner of lower exact cost-to-goal (from a node one always exists while the
    values are below 2**52: a node's value exceeds that of the neighbour it
    comes from by at least 1/sqrt(2)). From a point inside an edge there may be
    none: a crossing point a hair from an edge's end can carry exactly that
    end's value after rounding (the difference of the end values times the
    distance to the end falls below half an ulp). There the walk steps to the
    cheapest corner whose value is below that of the last node it passed,
    which exists because the point's value is not below the least of its
    cells' corners. So the values at the nodes met strictly decrease, the walk
    has no cycle and it ends at the goal. 8-connected mode takes only
    :func:`_descend` steps: an optimal D* Lite path.

    The walk stops with status ``ABORTED`` as soon as the state's work limit
    is reached (:func:`settle`).

    Returns (points (K', 2) with the first K valid, K, expansions, status).
    """
    g = st[1]
    work = st[7]
    nrows, ncols, sr, sc, goal, interp = prm[1], prm[2], prm[3], prm[4], prm[5], prm[7]
    start = sr * ncols + sc
    counter = np.zeros(1, dtype=np.int64)
    counter[0] = settle(st, prm, start)
    pts = np.empty((4 * (nrows + ncols), 2), dtype=np.float64)
    if work[0] > work[1]:
        return pts, 0, counter[0], ABORTED
    if g[start] == np.inf:
        return pts, 0, counter[0], NO_PATH
    gi = goal // ncols
    gj = goal - gi * ncols
    pts = _push_point(pts, 0, sr, sc)
    k = 1
    pr = float(sr)
    pc = float(sc)
    cur = g[start]
    # Value at the last node the walk passed (the start, at first).
    node_v = cur
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
        if work[0] > work[1]:
            return pts, k, counter[0], ABORTED
        if best == np.inf:
            best, best_v, qr, qc = _descend(st, prm, pr, pc, cur, counter)
            if best == np.inf and (pr != math.floor(pr) or pc != math.floor(pc)):
                # A point inside an edge whose value rounded to a corner's.
                best, best_v, qr, qc = _descend(st, prm, pr, pc, node_v, counter)
            if work[0] > work[1]:
                return pts, k, counter[0], ABORTED
            if best == np.inf:
                return pts, k, counter[0], STUCK
        pts = _push_point(pts, k, qr, qc)
        k += 1
        pr = qr
        pc = qc
        cur = best_v
        if qr == math.floor(qr) and qc == math.floor(qc):
            node_v = best_v
    return pts, k, counter[0], ABORTED if work[0] > work[1] else STUCK

