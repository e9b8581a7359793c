"""numba kernels extracting the Field D* path from the D* Lite cost field (private).

The walk starts at the start node and at each point (a node or a point on a
grid line) steps to the best crossing point of the far edges of the cells
around it, settling (:func:`navkit.planning.grid._dstar_lite_kernels.settle`)
every node value it reads first. Points are in node coordinates (cell
``(r, c)`` covers ``[r, r+1] × [c, c+1]``); the ``st``/``prm`` calling convention
is that of :mod:`navkit.planning.grid._dstar_lite_kernels`.

Compilation: :func:`extract_path` is the one kernel called from Python and the
one caller of :func:`settle`: the candidate kernels only read settled values
and, meeting a node that is not settled yet, hand it back to be settled and
the step repeated, so the search loop's machine code is not linked into
them. (numba links :func:`settle` into :func:`extract_path`, whose cache is
keyed on this file alone: a change of :func:`settle` or of the heap code it
inlines, such as the box of written records it keeps in ``work[2:6]`` since
review 27 (in repairs too since review 28) or the tournament on key bits
of review 48, must come with a change of this file, or a cache made before it
keeps running the old code.)
The walk is two functions (review 53): :func:`extract_path` and
:func:`_candidates`, which makes every kind of candidate (edge crossings,
grid lines, option-D pairs and, in its corner mode, the straight steps to
corners) in one loop with one site each for reading a node value, paying a
grid edge and writing a row, the edge minimum written in. There were six (a
straight-step kernel ``_descend`` with its own corner loop and the helpers
``_edge_min``, ``_settled_value``, ``_line_cost``), each with numba's fixed
cost per function (its passes, its LLVM module, its cache file) and every
call site lowered with its arguments: a cold plan + ``update_costs`` +
``replan`` took about 0.2 s less CPU (medians 3.30 -> 3.13 s and 3.48 -> 3.23 s
of alternating pairs, docs/compilation.md), with the same
candidates in the same order (paths, costs and expansions bit for bit). A
helper is still compiled once and called, never inlined by numba (which
types and lowers its body again at every call site: ``_candidates`` has one
site, and folding it into :func:`extract_path` cost 0.13 s more, the walk's
type inference then passing over both bodies together).
Every ``hypot`` with a zero side (a step along a grid line, a crossing at an
edge's end) is written as the other side's magnitude, which is what it
returns: the calls were about 40 % of a walk's time (review 53, FDWALK2). A
loop of its own for the corner mode, keeping the best step as it goes, brought
the 8-connected walk back from 1.5 times its time before the two functions,
but cost a cold first use about 0.15 s (1,337 more LLVM instructions), so it
was dropped. Cell costs are read inline (``pad[(r + 1) * width + c + 1]``)
and ``min()`` of two values is written out: a function for either (an
LLVM-inlined ``cell_cost``, numba's ``min()``, compiled once per argument type
set) was compiled on its own and
optimised again in every kernel linking it. ``math.floor`` already returns an
int (``int()`` of it compiled numba's ``int()`` too). The caller
passes every buffer (float64/int64, C-contiguous, writable), so the kernels
allocate nothing and run without reference counting.

Type inference repeats its pass over a whole kernel until no type changes; a
loop counter started at a literal (``k = 0``) is ``Literal[int](0)`` at first
and widens to int64 one pass later, once per level of nested loops (two more
passes for :func:`extract_path`), so counters start from a variable 0 instead
(``capacity - capacity``). Constants are frozen globals (``INF``, ``NAN``,
``floor`` from :mod:`math`): ``np.inf`` or ``math.floor`` is two IR
statements (the module, then its attribute), each typed and lowered at every
use. Together about 0.2-0.3 s of the 4.5 s first use.

Buffers are flat and the helpers take their arrays and scalars one by one
(review 49): a 2-D element access (``pts[k, 0]``) lowered to about twice the
instructions of a flat one (``pts[2 * k]``), and a helper taking the
``st``/``prm`` tuples had them taken apart at every call and rebuilt at its
entry (about 100 instructions each way). The walk's kernels and the polyline
kernel were over half of the LLVM IR numba emits for a first Field D* plan,
though they are not its hot loop: 13,299 -> 11,874 instructions (numba
0.68.1; ``tests/planning/test_review49_fdscold_walk_ir.py``), the machine
code after LLVM's optimisation about the same. Only :func:`extract_path`
takes the tuples (its Python caller builds them) and hands :func:`settle`
them as they are.

Indices stay signed (review 25): indexed with ``np.uint64`` as A* is (see
Indices in :mod:`navkit.planning.grid._astar_kernels`), the walk's cell,
record and candidate reads lost their wraparound code (all 12 in
:func:`_candidates` and the straight-step and helper kernels of then), but a walk
takes about 1 % of a fresh 1024² plan, and alone (replans from each point of the
path in turn, costs unchanged: nothing to search) ÷ A* it went 3.00 -> 2.91
(random 20 %), 3.85 -> 3.76 (random 35 %), 0.72 -> 0.71 (rooms), medians of
5 alternating runs: below the noise, dropped.
"""

from __future__ import annotations

import math
from math import floor, hypot, sqrt
from typing import Any

import numpy as np

from navkit._shared.jit import NO_REFCOUNT, RELEASES_GIL, typed_njit
from navkit.planning.grid._dstar_heap import RECORD, RHS
from navkit.planning.grid._dstar_lite_kernels import (
    INF,
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

# Status codes of :func:`extract_path`.
OK = 0
NO_PATH = 1
STUCK = 2
# The work limit of the state (``work[1]``) was reached: the repair was cut short.
ABORTED = 3
# The point buffer is full: call again with a larger one (values stay settled).
FULL = 4
# Rows of a candidate buffer: at most 4 cells x 4 edges + 4 lines + 8 pairs.
CANDIDATES = 32
# A frozen global for the kernels (see INF in the D* Lite kernels).
NAN = math.nan

# This module's compile options, written in this file as in each Field D* kernel
# module (the heap's, the search's, the path's, the polyline's): numba's cache keys
# a kernel's machine code on its own source file only, so options imported from
# another file could change there while these kernels kept loading code compiled
# with the old ones (tests/planning/grid/test_review23_fd_kernel_options.py checks
# it, and that the four modules agree). See ``KERNEL_OPTIONS`` in
# :mod:`navkit.planning.grid._dstar_heap` for what the options are for.
KERNEL_OPTIONS: dict[str, Any] = {**NO_REFCOUNT, "error_model": "numpy"}
HELPER_OPTIONS: dict[str, Any] = {**KERNEL_OPTIONS, "no_cpython_wrapper": True}
_kernel = typed_njit(**KERNEL_OPTIONS, **RELEASES_GIL)
_helper = typed_njit(**HELPER_OPTIONS)


@_helper
def _candidates(
    pad: np.ndarray,
    width: int,
    nrows: int,
    ncols: int,
    vals: np.ndarray,
    keys: np.ndarray,
    size: np.ndarray,
    sr: int,
    sc: int,
    km: float,
    hscale: float,
    pr: float,
    pc: float,
    out: np.ndarray,
    corner_g: np.ndarray,
    need: np.ndarray,
    corners: bool,
    below: float,
) -> int:
    """Next-point candidates of the interpolated path from point p on the grid lines.

    Rows of ``out`` (flat: row n at ``4 n`` .. ``4 n + 3``): (cost from p to
    q, interpolated cost-to-goal at q, q_row, q_col). They are: the optimal
    crossing point of every far edge of every passable cell touching p, the
    ends of the grid edges through p (paying the cheaper cell beside the edge)
    and, from a node, the point where option D of :func:`corner_cost` leaves
    the cheap edge. ``corner_g`` (4,) is scratch.

    With ``corners`` the rows are instead the straight steps from p to the
    corners of the passable cells touching p, p itself left out: the
    8-connected move set from a node, where an axis move is offered by both
    cells beside the edge and pays the cheaper of the two. Only corners of
    value below ``below`` are rows (the walk's straight step must lower the
    value); ``below`` is not read without ``corners``.

    Returns the number of rows, or -1 when a node value it needs is not
    settled yet (its id in ``need[0]``): values are read in the order the
    rows are made, so the nodes handed back, and with them the search's
    work, follow the walk.
    """
    # A variable, not the literal 0 (see the module notes).
    n: int = width - width
    fr = floor(pr)
    fc = floor(pc)
    on_r = pr == fr
    on_c = pc == fc
    r_lo = fr - 1 if on_r else fr
    c_lo = fc - 1 if on_c else fc
    # Items, each reading one node value at the one site below (review 53: one
    # loop, where a loop per kind each had its own read, row and helper calls):
    # 0-15 the corners of the cells (r_lo + (item >> 3), c_lo + (item >> 2 & 1))
    # touching p, then the grid lines through p (16-19) and, from a node, the
    # option-D pairs (20-27).
    items = 16 if corners else 28 if on_r and on_c else 20
    for item in range(items):
        q = item & 3
        along = False
        mult = INF
        if item < 16:
            r = r_lo + (item >> 3)
            c = c_lo + (item >> 2 & 1)
            if r > fr or c > fc:
                continue
            cost = pad[(r + 1) * width + c + 1]  # cell (r, c)
            if cost == INF:
                continue
            # Corner q of the cell: (r, c), (r, c+1), (r+1, c), (r+1, c+1).
            i = r + (q >> 1)
            j = c + (q & 1)
            if corners:
                if i == pr and j == pc:
                    continue
                mult = cost
                along = i == pr or j == pc
        elif item < 20:
            # Along the grid lines through p, to the nearest nodes on either side.
            side = q >> 1
            if q & 1 == 0:
                if not on_r:
                    continue
                i = fr
                j = fc - 1 + 2 * side if on_c else fc + side
            else:
                if not on_c:
                    continue
                i = fr - 1 + 2 * side if on_r else fr + side
                j = fc
            if i < 0 or i >= nrows or j < 0 or j >= ncols:
                continue
            along = True
        else:
            k = item - 20
            base = fr * width + fc
            # Option D: along the cheap edge (cell cost b) to the point where the
            # straight crossing of the dear cell (cost dear) to corner D begins.
            dear = pad[base + PAIR_CR[k] * width + PAIR_CC[k]]
            b = pad[base + PAIR_BR[k] * width + PAIR_BC[k]]
            if not b < dear or dear == INF:
                continue
            w = b / sqrt(dear * dear - b * b)
            if w >= 1.0:
                continue
            x = 1.0 - w
            c0 = b * x
            extra = dear * sqrt(1.0 + w * w)
            qr = fr + x * PAIR_AR[k]
            qc = fc + x * PAIR_AC[k]
            i = fr + PAIR_DR[k]
            j = fc + PAIR_DC[k]
        if along:
            # The grid edge from p to node (i, j) pays the cheaper cell beside it
            # (comparisons written out: numba compiles min() as a function of its own).
            if pr == i:
                col = j if j < pc else floor(pc)
                # Cells (i - 1, col) and (i, col).
                lo = pad[i * width + col + 1]
                hi = pad[(i + 1) * width + col + 1]
            else:
                row = i if i < pr else floor(pr)
                # Cells (row, j - 1) and (row, j).
                lo = pad[(row + 1) * width + j]
                hi = pad[(row + 1) * width + j + 1]
            if hi < lo:
                lo = hi
            if lo < mult:
                mult = lo
            if mult == INF:
                continue
        # The node's value, if settled (consistent, its key not above the
        # queue's top: the stopping rule of settle); else it is handed back.
        s = i * ncols + j
        g = vals[RECORD * s]
        if not (
            g == vals[RECORD * s + RHS]
            and (
                size[0] == 0
                or key_reached(keys[0], keys[1], g, heuristic(sr, sc, i, j, hscale), km)
            )
        ):
            need[0] = s
            return -1
        if item < 16 and not corners:
            corner_g[q] = g
            if q < 3:
                continue
            # The four far edges of cell (r, c): rows r and r+1 (along the
            # columns), columns c and c+1, each offering its best crossing point.
            for e in range(4):
                if e < 2:
                    if pr == r + e:
                        continue
                    e0r = float(r + e)
                    e0c = float(c)
                    tr = 0.0
                    tc = 1.0
                    g0 = corner_g[2 * e]
                    g1 = corner_g[2 * e + 1]
                else:
                    if pc == c + e - 2:
                        continue
                    e0r = float(r)
                    e0c = float(c + e - 2)
                    tr = 1.0
                    tc = 0.0
                    g0 = corner_g[e - 2]
                    g1 = corner_g[e]
                if g0 == INF and g1 == INF:
                    continue
                # The best point q = e0 + u t (u in [0, 1]) minimises
                # cost |p - q| + (1 - u) g0 + u g1, a convex function of u whose
                # stationary point is u0 - dg d / sqrt(cost^2 - dg^2) (dg = g1 - g0,
                # u0 the projection of p and d its distance to the edge line); a
                # stationary point within 1e-12 of an end counts as that end.
                wr = pr - e0r
                wc = pc - e0c
                u0 = wr * tr + wc * tc
                d = abs(wr * tc - wc * tr)
                best_u = 0.0
                best = INF
                if g0 < INF:
                    best = cost * (abs(u0) if d == 0.0 else d if u0 == 0.0 else hypot(d, u0)) + g0
                if g1 < INF:
                    dr = 1.0 - u0
                    t = cost * (abs(dr) if d == 0.0 else d if dr == 0.0 else hypot(d, dr)) + g1
                    if t < best:
                        best = t
                        best_u = 1.0
                if g0 < INF and g1 < INF and d > 0.0:
                    dg = g1 - g0
                    if abs(dg) < cost:
                        u = u0 - dg * d / sqrt(cost * cost - dg * dg)
                        # Not within rounding of an end: a minimum at an end in
                        # exact arithmetic came out at u = 1 - 1e-16 on one drawing
                        # of the grid and at u <= 0 on its mirror image, and from a
                        # point a hair off the node the next step along a grid line
                        # paid the cell beside it instead of the cheaper of the two
                        # (a path 14 % dearer; review 30).
                        if 1e-12 < u < 1.0 - 1e-12:
                            t = cost * hypot(d, u - u0) + g0 + dg * u
                            if t < best:
                                best = t
                                best_u = u
                if best_u == 0.0:
                    qr, qc, gq = e0r, e0c, g0
                elif best_u == 1.0:
                    qr, qc, gq = e0r + tr, e0c + tc, g1
                else:
                    qr = e0r + best_u * tr
                    qc = e0c + best_u * tc
                    gq = g0 + (g1 - g0) * best_u
                row = 4 * n
                dr = pr - qr
                dc = pc - qc
                step = abs(dc) if dr == 0.0 else abs(dr) if dc == 0.0 else hypot(dr, dc)
                out[row] = cost * step
                out[row + 1] = gq
                out[row + 2] = qr
                out[row + 3] = qc
                n += 1
            continue
        if g == INF or (corners and not g < below):
            continue
        if item < 20:
            # hypot with a zero side is the other side's magnitude (C99 Annex F),
            # and libm's hypot was about 40 % of the walk's time: the call is kept
            # for the steps that need it (review 53, FDWALK2), as in the edges'.
            dr = pr - i
            dc = pc - j
            c0 = mult * (abs(dc) if dr == 0.0 else abs(dr) if dc == 0.0 else hypot(dr, dc))
            extra = 0.0
            qr = float(i)
            qc = float(j)
        row = 4 * n
        out[row] = c0
        out[row + 1] = extra + g
        out[row + 2] = qr
        out[row + 3] = qc
        n += 1
    return n


@_kernel
def extract_path(
    st: tuple[np.ndarray, ...],
    prm: tuple[Any, ...],
    lookahead: bool,
    pts: np.ndarray,
    cand: np.ndarray,
    cand2: np.ndarray,
    corner_g: np.ndarray,
    counter: np.ndarray,
    need: np.ndarray,
) -> tuple[int, int]:
    """Settle the start and follow the cost field from it to the goal.

    The walk starts at node ``walk`` (``prm[9]``) or, when that is -1, at the
    corner of least value of the start cell (the cell whose top-left corner is
    the heuristic's start; ties: the first of (0, 0), (0, 1), (1, 0), (1, 1)),
    all four settled first. It ends at the goal node or, with a goal cell
    (``prm[10]``), at the first point on the goal cell's boundary (where
    every value is the corners' source value: the rest of the way is the
    straight segment to the centre, inside the cell).

    Interpolated mode: at each point take the candidate of :func:`_candidates`
    minimising (cost to q) + (cost-to-goal at q), where with ``lookahead`` the
    cost-to-goal of a q inside an edge is not its linear interpolation but the
    best one-step continuation from q. The estimate must decrease at every step;
    when no candidate lowers it, a straight step (the corner mode of
    :func:`_candidates`, picked by the same loop) goes to a
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
    straight steps: an optimal D* Lite path.

    Buffers (all written, flat, see the module notes): ``pts`` (2 K,) the
    path points (point k at ``2 k``, ``2 k + 1``), ``cand`` and ``cand2``
    (4 :data:`CANDIDATES`,) candidate rows (row n at ``4 n`` .. ``4 n + 3``),
    ``corner_g`` (4,) scratch, ``counter`` (1,) int64 to which the expansions are added,
    ``need`` (1,) int64 scratch.

    The walk stops with status ``ABORTED`` as soon as the state's work limit
    is reached (:func:`settle`), and with ``FULL`` when ``pts`` has no room
    left (call again with a larger buffer).

    Returns (K, status): the first K points of ``pts`` are the path.
    """
    pad, vals, keys, size, work = st[0], st[1], st[3], st[5], st[6]
    width, nrows, ncols, sr, sc = prm[0], prm[1], prm[2], prm[3], prm[4]
    km, interp, hscale, start, goal_cell = prm[6], prm[7], prm[8], prm[9], prm[10]
    # The walk ends in the box [gi, gi_hi] x [gj, gj_hi]: the goal node, or the
    # boundary of the goal cell (points of the walk lie on grid lines).
    goal = prm[5] if goal_cell < 0 else goal_cell
    gi = goal // ncols
    gj = goal - gi * ncols
    gi_hi = gi if goal_cell < 0 else gi + 1
    gj_hi = gj if goal_cell < 0 else gj + 1
    # Start-cell corners still to settle before the walk picks its start (-1: none).
    corner = -1
    if start < 0:
        corner = 0
        start = sr * ncols + sc
    capacity = pts.shape[0] >> 1
    pr = 0.0
    pc = 0.0
    cur = INF
    # Value at the last node the walk passed (the start, at first).
    node_v = INF
    # Counters start from a variable 0, not the literal: a literal types as
    # Literal[int](0) first, and widening it to int64 cost numba's type inference
    # two more passes over the whole kernel (see the module notes).
    zero = capacity - capacity
    k = zero
    steps = zero
    max_steps = 4 * nrows * ncols + 16
    need[0] = start
    while True:
        if need[0] >= 0:
            # The one call of the search loop: the start first, then any node
            # value a step needs that is not settled yet (the step is repeated).
            counter[0] += settle(st, prm, need[0])
            need[0] = -1
            if work[0] > work[1]:
                return k, ABORTED
            if k == 0:
                if corner >= 0:
                    if corner < 3:
                        corner += 1
                        need[0] = (sr + (corner >> 1)) * ncols + sc + (corner & 1)
                        continue
                    corner = -1
                    for q in range(4):
                        s = (sr + (q >> 1)) * ncols + sc + (q & 1)
                        if vals[RECORD * s] < vals[RECORD * start]:
                            start = s
                if vals[RECORD * start] == INF:
                    return 0, NO_PATH
                cur = vals[RECORD * start]
                node_v = cur
                pr = float(start // ncols)
                pc = float(start - (start // ncols) * ncols)
                pts[0] = pr
                pts[1] = pc
                k = 1
        if gi <= pr <= gi_hi and gj <= pc <= gj_hi:
            return k, OK
        if steps >= max_steps:
            return k, STUCK
        if k == capacity:
            return k, FULL
        best = INF
        best_v = INF
        qr = 0.0
        qc = 0.0
        # Mode 0, interpolated: the candidates of p. When none lowers the value
        # (and in 8-connected mode, which starts there), mode 1: a straight step
        # to a corner below the current value, then, from a point inside an edge
        # whose value rounded to a corner's, mode 2: below the value of the last
        # node passed. One loop picks in every mode (one _candidates site).
        mode = zero if interp else zero + 1
        while True:
            below = node_v if mode == 2 else cur
            # Candidates of p (a = -1), then for each candidate a inside an
            # edge its own candidates (the lookahead; corners are nodes).
            n = zero
            a = -1
            while a < n:
                if a < 0:
                    cr = pr
                    cc = pc
                    v = 0.0
                    expand = True
                else:
                    cr = cand[4 * a + 2]
                    cc = cand[4 * a + 3]
                    v = cand[4 * a + 1]
                    expand = lookahead and (cr != floor(cr) or cc != floor(cc))
                if expand:
                    buf = cand if a < 0 else cand2
                    m = _candidates(pad, width, nrows, ncols, vals, keys, size, sr, sc, km, hscale,
                                    cr, cc, buf, corner_g, need, mode > 0, below)  # fmt: skip
                    if m < 0:
                        break
                    if a < 0:
                        n = m
                        a = 0
                        continue
                    la = INF
                    for b2 in range(m):
                        t = cand2[4 * b2] + cand2[4 * b2 + 1]
                        if t < la:
                            la = t
                    v = la
                t = cand[4 * a] + v
                if t < best and v < below:
                    best = t
                    best_v = v
                    qr = cr
                    qc = cc
                a += 1
            if need[0] >= 0 or best < INF or mode == 2:
                break
            if mode == 1 and pr == floor(pr) and pc == floor(pc):
                break
            mode += 1
        if need[0] >= 0:
            continue
        if best == INF:
            return k, STUCK
        pts[2 * k] = qr
        pts[2 * k + 1] = qc
        k += 1
        steps += 1
        pr = qr
        pc = qc
        cur = best_v
        if qr == floor(qr) and qc == floor(qc):
            node_v = best_v
