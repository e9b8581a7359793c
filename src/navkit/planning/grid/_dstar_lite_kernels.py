"""numba kernels of the D* Lite search on cell corners, for Field D* (private).

Node values, their repair after cost changes and the search loop; the path
extraction is in :mod:`navkit.planning.grid._field_path_kernels` and the exact
polyline costs in :mod:`navkit.planning.grid._polyline_kernels`.

Geometry. The kernels work in node coordinates: the search nodes are the
integer corners of the cells, node ``(i, j)`` (``0 <= i <= rows``,
``0 <= j <= cols``) having flat index ``i * ncols + j`` with ``ncols = cols + 1``,
and cell ``(r, c)`` covers ``[r, r+1] × [c, c+1]``. (Node coordinates are
navkit's continuous cell coordinates plus ½: node ``(i, j)`` sits at
``(i - 0.5, j - 0.5)``.) Cell costs are read from a padded flat array ``pad`` of
shape ``(rows+2) * (cols+2)`` whose border is ``+inf``, so cell ``(r, c)``
(``-1 <= r <= rows``, ``-1 <= c <= cols``) is ``pad[(r + 1) * width + c + 1]``
with ``width = cols + 2`` and no bounds checks are needed.

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

Compilation. The helpers inlined at several sites (:func:`_pair_value`,
:func:`_pairs_through`, :func:`_corner`, :func:`heuristic`,
:func:`key_reached`, :func:`update_vertex`, :func:`_lower_neighbour`, written
out eight times with a known ring index) are LLVM-inlined (numba's
``forceinline``: typed and lowered once) rather than inlined by numba at IR
level, which translates, types and lowers the body again at each site (about
10 ms a site even for a one-line helper; 0.17 s more for
:func:`update_vertex`); the rarely hot :func:`node_rhs` stays a call.
:func:`corner_cost` stays IR-inlined at its one site, :func:`_corner` (tests
call it from Python); the search reaches it through :func:`_corner` at five
sites (one in :func:`_pair_value`, four in :func:`_pairs_through`).
Every heap change is a call of
:func:`navkit.planning.grid._dstar_heap.heap_update`, except the two hot ones,
LLVM-inlined into :func:`settle`: the pop of the top
(:func:`~navkit.planning.grid._dstar_heap.change`) and the sift-up of a
lowered value's key (:func:`~navkit.planning.grid._dstar_heap.heap_lower`). ``min()`` of two
values is written out (``b if b < a else a``, the value numba's ``min(a, b)``
picks): numba compiles ``min()`` as a function of its own for every argument
type set.

Calling convention. The search kernels take the planner's arrays as one tuple
``st = (pad, vals, nodes, keys, pos, size, work, changed)``: ``vals`` the node
records of :func:`navkit.planning.grid._dstar_heap.node_records` flattened
(``g`` of node ``s`` is ``vals[RECORD * s]``, its ``rhs`` ``vals[RECORD * s +
RHS]``; its heap slot ``pos[RECORD * s]`` shares the record: one cache line holds all
three), ``nodes, keys, pos, size`` the indexed heap of
:mod:`navkit.planning.grid._dstar_heap` in its kernel view (``keys`` flat,
``pos`` from :func:`~navkit.planning.grid._dstar_heap.flat_positions`: node
``s``'s slot at ``pos[RECORD * s]``), ``work`` the int64 (work done,
work limit, then the box of the records written: first and last row, first
and last column), see :func:`settle`, and ``changed`` the int64 list of cells
changed since the last search: their count, then their padded flat indices,
written by ``FieldDStar.update_costs``. Flat records, not a (nodes, 3)
array: a two-index read is more IR at each of the many sites, and first
use compiled measurably longer with it (about 0.3 s of CPU). Its scalars
come as ``prm = (width, nrows, ncols, start_row, start_col, goal, km, interp, hscale,
walk, goal_cell, fresh)``; both are built by :func:`state` and :func:`params`.
``(start_row, start_col)`` is the start of the heuristic; ``walk`` the node
where the path extraction starts, or -1 for the corner of least value of the
cell ``(start_row, start_col)`` (whose top-left corner is that node).
``goal`` is the goal node, or -1 when the goal is a cell: then ``goal_cell``
is the node of the cell's top-left corner (else -1), and each of the cell's
four corners is a source valued at the cost of the segment from the cell's
centre to it (a virtual goal at the centre linked to all four corners): its
``rhs`` is the least of that and :func:`node_rhs`. ``fresh`` is true for a
search from scratch (not a repair), see Prefetch.

Prefetch (review 19). A fresh search, after each pop of the top, prefetches
(``llvm.prefetch``, :mod:`navkit.planning.grid._prefetch`) what the next
expansion reads while the neighbours of the node just popped are settled: the
records of the next top's eight neighbours and its own (three rows of three
records) and the 4 x 4 cells around it (its neighbours' pairs read them; the
integer division for its row is off the critical path). Bit-identical (a
hint changes no value); fresh 1024² plans took about 10 % less time (÷ A*,
medians of 4 alternating runs: 3.37 -> 3.05 random 20 %, 2.48 -> 2.26 random
35 %, 3.14 -> 2.78 rooms; the records alone gave 1-4 %). Repairs (``fresh``
false) skip it: always on, the records' prefetch made mid-path replans 5-9 %
slower (review 18); gated, their time ÷ A* is unchanged. The flag is read
once per pop and the code compiled once for both. Where the target has no
prefetch instruction, LLVM drops the intrinsic (a no-op).

Indices stay signed (review 25). Indexed with ``np.uint64`` as A* is (see
Indices in :mod:`navkit.planning.grid._astar_kernels`), the record and cell
reads of :func:`settle` and the pair helpers lost 18 of their 20 wraparounds
(the heap's slots are already masked, see :mod:`~navkit.planning.grid._dstar_heap`),
but fresh 1024² plans ÷ A* went only 2.80 -> 2.75 (random 20 %), 2.06 -> 2.03
(random 35 %), 2.46 -> 2.41 (rooms), and repairs ÷ fresh plans 0.99-1.00 of
before (medians of 10 alternating runs): below the noise, dropped.
"""

from __future__ import annotations

import math
from math import sqrt
from typing import Any

import numpy as np

from navkit._shared.jit import NO_REFCOUNT, bind_numba_names, njit_inline, typed_njit
from navkit.planning.grid._dstar_heap import (
    NN,
    RECORD,
    RHS,
    change,
    flat_positions,
    heap_lower,
    heap_update,
)

# ``settle`` compiles the heap's ``change`` into itself, and numba's cache keys
# ``settle`` on this file alone: a change of ``_dstar_heap`` needs a change here
# too, or a cache made before it keeps running the old heap (review 48: the key
# bits tournament reached no existing cache until this note).

SQRT2 = math.sqrt(2.0)
# Read by the kernels as one frozen global (``np.inf`` is two IR statements: the
# module, then its attribute, each typed and lowered at every use).
INF = math.inf
FIELD_HSCALE = 1.0 / SQRT2
OCT = SQRT2 - 1.0
# Distance from a cell's centre to each of its corners.
HALF_DIAGONAL = math.hypot(0.5, 0.5)
# Least cost above g(u) of any option through an axis neighbour u (cell costs >= 1).
_AXIS_GAIN = 1.0 / SQRT2

# Ring of the 8 neighbours, counter-clockwise from east: even entries are the
# axis neighbours, odd entries the diagonal ones. Pair k is (ring[k], ring[k+1]).
RING_R = np.array([0, -1, -1, -1, 0, 1, 1, 1], dtype=np.int64)
RING_C = np.array([1, 1, 0, -1, -1, -1, 0, 1], dtype=np.int64)

# This module's compile options, written in this file as in each Field D* kernel
# module (the heap's, the search's, the path's, the polyline's): numba's cache keys
# a kernel's machine code on its own source file only, so options imported from
# another file could change there while these kernels kept loading code compiled
# with the old ones (tests/planning/grid/test_review23_fd_kernel_options.py checks
# it, and that the four modules agree). See ``KERNEL_OPTIONS`` in
# :mod:`navkit.planning.grid._dstar_heap` for what the options are for.
# (Helpers only: no kernel here is called from Python.)
HELPER_OPTIONS: dict[str, Any] = {
    **NO_REFCOUNT, "error_model": "numpy", "no_cpython_wrapper": True
}  # fmt: skip
_helper = typed_njit(**HELPER_OPTIONS)
# Compiled once and inlined by LLVM into every caller (numba's ``forceinline``):
# numba's own ``inline="always"`` types and lowers the body again at each call site.
_inlined = typed_njit(**HELPER_OPTIONS, forceinline=True)
# A callee of an LLVM-inlined helper that stays a call (numba passes ``forceinline``
# on to callees that leave it unset).
_called = typed_njit(**HELPER_OPTIONS, forceinline=False)


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

# A software prefetch (``llvm.prefetch``, see :mod:`navkit.planning.grid._prefetch`),
# bound when numba loads (importing this module must not import numba). A hint:
# LLVM drops it on targets without a prefetch instruction.
_prefetch: Any = None


def _no_prefetch(arr: Any, idx: Any) -> None:
    """``_prefetch`` when the JIT is disabled: nothing to do."""


bind_numba_names(globals(), "navkit.planning.grid._prefetch",
                 python={"_prefetch": _no_prefetch}, _prefetch="prefetch")  # fmt: skip


# Work units of an expansion in :func:`settle`: a node whose value falls costs one,
# one whose value rises (g set to inf and its dependants' rhs recomputed) costs
# about this many (measured: 2.5-3.5x the time of a lowering expansion).
RAISE_WORK = 3


def state(
    pad: np.ndarray,
    records: np.ndarray,
    heap: tuple[np.ndarray, ...],
    work: np.ndarray,
    changed: np.ndarray,
) -> tuple[np.ndarray, ...]:
    """The ``st`` tuple of the search kernels (``records`` from ``node_records``, flattened).

    The heap's keys are passed flat (slot i's key at ``2 i``, ``2 i + 1``).
    """
    nodes, keys, pos, size = heap
    return (
        pad, records.reshape(-1), nodes, keys.reshape(-1), flat_positions(pos), size, work, changed
    )


def params(
    width: int,
    nrows: int,
    ncols: int,
    start: tuple[int, int],
    goal: int,
    km: float,
    interp: bool,
    hscale: float,
    walk: int,
    goal_cell: int,
    fresh: bool = False,
) -> tuple[Any, ...]:
    """The ``prm`` tuple of the search kernels (types fixed so numba compiles once).

    ``fresh``: the search starts from scratch (no repair), see :func:`settle`.
    """
    return (
        int(width),
        int(nrows),
        int(ncols),
        int(start[0]),
        int(start[1]),
        int(goal),
        float(km),
        bool(interp),
        float(hscale),
        int(walk),
        int(goal_cell),
        bool(fresh),
    )


@njit_inline
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
       ``y = f / sqrt(c^2 - f^2)`` (when it is < 1), which simplifies to
       ``g1 + sqrt(c^2 - f^2)``;
    D. a distance x along the edge s-s1 at cost b, then straight through c to
       s2: ``b x + c sqrt(1 + (1 - x)^2) + g2`` with the optimal
       ``1 - x = b / sqrt(c^2 - b^2)`` (when it is < 1), which simplifies to
       ``g2 + b + sqrt(c^2 - b^2)``.

    Ferguson & Stentz pick one of C and D by testing ``f <= b`` and one of A and
    the rest by ``g1 <= g2``; here the minimum over every option that applies is
    taken. That is never larger than the paper's value and equals it wherever the
    paper's branch is the cheapest; it also keeps the along-edge option A when
    the crossed cell c is impassable and g1 > g2, where the paper's formula gives
    infinity for this pair (the node value is unaffected: the neighbouring pair,
    which crosses b, covers that edge). With
    ``interp`` false only A and B remain: the classic 8-connected move costs.
    """
    best = (b if b < c else c) + g1  # min(c, b), as numba's min picks
    if c < INF:
        v = c * SQRT2 + g2
        if v < best:
            best = v
        if interp and g2 < g1:
            # C at its optimum y = f / sqrt(c^2 - f^2) costs g1 + sqrt(c^2 - f^2)
            # (y < 1 means 2 f^2 < c^2); D at its optimum 1 - x = b / sqrt(c^2 - b^2)
            # costs g2 + b + sqrt(c^2 - b^2) (1 - x < 1 means 2 b^2 < c^2).
            cc = c * c
            if g1 < INF:
                f = g1 - g2
                if 2.0 * f * f < cc:
                    v = g1 + sqrt(cc - f * f)
                    if v < best:
                        best = v
            if 2.0 * b * b < cc:
                v = g2 + b + sqrt(cc - b * b)
                if v < best:
                    best = v
    return best


@_inlined
def heuristic(sr: int, sc: int, i: int, j: int, hscale: float) -> float:
    """Heuristic ``hscale * octile`` distance between nodes (sr, sc) and (i, j)."""
    dr = abs(i - sr)
    dc = abs(j - sc)
    if dr < dc:
        return hscale * (dc + OCT * dr)
    return hscale * (dr + OCT * dc)


@_inlined
def key_reached(top0: float, top1: float, m: float, h: float, km: float) -> bool:
    """Whether the queue's top key (top0, top1) is not below the key of a node.

    The node's key is ``(m + h + km, m)``. The stopping rule of :func:`settle`
    (with the node consistent). The weak heuristic makes the first components
    of a node and of a node its value comes from equal in exact arithmetic
    whenever the step costs exactly the heuristic's change (a straight run on
    unit costs); rounding may then order them either way, so first components
    within a relative 1e-9 count as equal and the second ones decide: such a
    queued node keeps the search going (a few extra expansions, never a
    value read early).
    """
    t1 = m + h + km
    if not t1 < INF:
        return top0 == INF and top1 >= m
    tol = 1e-9 * (1.0 + t1)
    return top0 > t1 + tol or (top0 >= t1 - tol and top1 >= m)


@_inlined
def _corner(g1: float, g2: float, c: float, b: float, interp: bool) -> float:
    """:func:`corner_cost`, compiled once and LLVM-inlined at its five sites."""
    return corner_cost(g1, g2, c, b, interp)


@_inlined
def _pair_value(
    pad: np.ndarray, width: int, vals: np.ndarray, ncols: int, i: int, j: int, k: int, interp: bool
) -> float:
    base = i * width + j
    c = pad[base + PAIR_CR[k] * width + PAIR_CC[k]]
    b = pad[base + PAIR_BR[k] * width + PAIR_BC[k]]
    if c == INF and b == INF:
        return INF
    # The axis node is a corner of whichever of b, c is finite: always on the grid.
    g1 = vals[RECORD * ((i + PAIR_AR[k]) * ncols + j + PAIR_AC[k])]
    if c == INF:
        return float(b + g1)
    return _corner(g1, vals[RECORD * ((i + PAIR_DR[k]) * ncols + j + PAIR_DC[k])], c, b, interp)


@_inlined
def _pairs_through(
    pad: np.ndarray,
    width: int,
    vals: np.ndarray,
    ncols: int,
    i: int,
    j: int,
    m: int,
    gu: float,
    interp: bool,
) -> float:
    """Least of the pairs m-1 and m of node (i, j), both through u = ring[m] (g(u) = gu).

    The value of :func:`_pair_value` for the two pairs (the least of them), with
    what the pairs share read once: for an axis u the two cells beside the edge
    to u (each pair's crossed cell is the other's edge-side cell), for a
    diagonal u the crossed cell (the one cell with corners s and u); and g(u),
    passed in. With it fresh 1024² plans took 3-5 % less time than with
    :func:`_pair_value` twice (bit-identical); one site per pair, g(u) passed
    in, saved nothing, and two ``corner_cost`` sites selecting their
    arguments by the parity of m saved 2-3 %.
    """
    base = i * width + j
    mp = m - 1 if m > 0 else 7
    x = pad[base + PAIR_CR[m] * width + PAIR_CC[m]]
    if m % 2 == 0:
        # u axial: pair m crosses x (edge side y) to ring[m+1], pair m-1 crosses y
        # (edge side x) to ring[m-1].
        y = pad[base + PAIR_CR[mp] * width + PAIR_CC[mp]]
        if x == INF and y == INF:
            return INF
        if x == INF:
            v = float(y + gu)
        else:
            v = _corner(
                gu, vals[RECORD * ((i + PAIR_DR[m]) * ncols + j + PAIR_DC[m])], x, y, interp
            )
        if y == INF:
            v2 = float(x + gu)
        else:
            v2 = _corner(
                gu, vals[RECORD * ((i + PAIR_DR[mp]) * ncols + j + PAIR_DC[mp])], y, x, interp
            )
    else:
        # u diagonal: both pairs cross x, with edge-side cells y (pair m) and z.
        y = pad[base + PAIR_BR[m] * width + PAIR_BC[m]]
        z = pad[base + PAIR_BR[mp] * width + PAIR_BC[mp]]
        v = INF
        if x < INF or y < INF:
            g1 = vals[RECORD * ((i + PAIR_AR[m]) * ncols + j + PAIR_AC[m])]
            v = float(y + g1) if x == INF else _corner(g1, gu, x, y, interp)
        v2 = INF
        if x < INF or z < INF:
            g1 = vals[RECORD * ((i + PAIR_AR[mp]) * ncols + j + PAIR_AC[mp])]
            v2 = float(z + g1) if x == INF else _corner(g1, gu, x, z, interp)
    return v2 if v2 < v else v


@_called
def node_rhs(
    pad: np.ndarray, width: int, vals: np.ndarray, ncols: int, i: int, j: int, interp: bool
) -> float:
    """Minimum over the eight neighbour pairs of node (i, j)."""
    best = INF
    for k in range(8):
        v = _pair_value(pad, width, vals, ncols, i, j, k, interp)
        if v < best:
            best = v
    return best


@_inlined
def update_vertex(
    s: int,
    i: int,
    j: int,
    vals: np.ndarray,
    nodes: np.ndarray,
    keys: np.ndarray,
    pos: np.ndarray,
    size: np.ndarray,
    sr: int,
    sc: int,
    km: float,
    hscale: float,
) -> None:
    """Queue node s = (i, j) with its key if it is inconsistent, else dequeue it.

    Node s is (i, j): passed in, as an integer division per call is costly.
    Compiled once and inlined by LLVM at its call sites (a rising node and its
    neighbours, a requeued key, the corners of changed cells): as a call of its
    own, on top of the call of :func:`heap_update`, repairs were about 5 %
    slower. Where a value falls, :func:`settle` queues the key itself.
    ``queued`` is passed on as computed (a literal ``True``/``False`` would
    compile :func:`heap_update` once per value).
    """
    gs = vals[RECORD * s]
    rs = vals[RECORD * s + RHS]
    queued = gs != rs
    if queued:
        m = rs if rs < gs else gs  # min(g, rhs), as numba's min picks
        heap_update(nodes, keys, pos, size, s, m + heuristic(sr, sc, i, j, hscale) + km, m, queued)
    elif pos[RECORD * s & NN] >= 0:
        heap_update(nodes, keys, pos, size, s, 0.0, 0.0, queued)


@_inlined
def _lower_neighbour(
    pad: np.ndarray,
    width: int,
    vals: np.ndarray,
    ncols: int,
    nrows: int,
    nodes: np.ndarray,
    keys: np.ndarray,
    pos: np.ndarray,
    size: np.ndarray,
    goal: int,
    ui: int,
    uj: int,
    ref: float,
    interp: bool,
    sr: int,
    sc: int,
    km: float,
    hscale: float,
    m: int,
) -> None:
    """Lower ring neighbour ``m`` of node u = (ui, uj), whose value fell to ``ref``.

    One neighbour of :func:`settle`'s loop over a lowered node, written out
    eight times there: LLVM-inlined with ``m`` a known constant at each site,
    the ring and pair tables, bounds and parity branches fold away (a fresh
    plan on a 1024² random map about 6 % faster, the same expansions). ``m`` is
    passed as a runtime integer (``zero + m``): numba would compile a literal
    once per value (eight copies of this helper and nine of
    :func:`_pairs_through`, 2.4 s more at first use).
    """
    si = ui - RING_R[m]
    sj = uj - RING_C[m]
    if si < 0 or si >= nrows or sj < 0 or sj >= ncols:
        return
    s = si * ncols + sj
    if s == goal:
        return
    # Every option through u costs at least ref + 1/sqrt(2) (u an axis
    # neighbour of s) or ref + 1 (diagonal), see the module notes. A
    # lowered u cannot improve a neighbour at or below that; a neighbour
    # below it did not take its value from a raised u, and raising g(u)
    # (which never lowers an option) leaves its rhs unchanged.
    gain = _AXIS_GAIN if m % 2 == 0 else 1.0
    bound = ref + gain - 1e-9 * (1.0 + ref)
    rs = vals[RECORD * s + RHS]
    if rs < bound or rs == bound:
        return
    # u is ring[m] of s: only the pairs m-1 and m of s contain it.
    v = _pairs_through(pad, width, vals, ncols, si, sj, m, ref, interp)
    if not v < rs:
        return
    vals[RECORD * s + RHS] = v
    gs = vals[RECORD * s]
    # update_vertex's own code, with the sift-up inlined (the hot path) and one
    # call of heap_update for its two other cases.
    kv = 0.0
    mv = 0.0
    if gs != v:
        mv = v if v < gs else gs
        kv = mv + heuristic(sr, sc, si, sj, hscale) + km
        if heap_lower(nodes, keys, pos, size, s, kv, mv):
            return
    elif pos[RECORD * s & NN] < 0:
        return
    heap_update(nodes, keys, pos, size, s, kv, mv, gs != v)


@_helper
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
    of expansions. Its first call after cost changes first requeues the corners
    of the changed cells (``FieldDStar.update_costs`` only lists them), so every search
    must call it before reading any node value.

    Work bound: every expansion adds its work units (1, or :data:`RAISE_WORK`
    for a node whose value rises) to ``work[0]``; once ``work[0] > work[1]`` the
    loop stops early, leaving the target unsettled and the state mid-repair (the
    caller then starts afresh, see :func:`extract_path`).

    Box of the records written: every node whose value falls goes into
    ``work[2:6]`` (first and last row, first and last column; ``FieldDStar``
    puts the sources it queues in it). g becomes finite only where a value
    falls, and a record leaves its blank state (g = rhs = inf, unqueued) only
    when its node is a source, when its value falls, when it is a neighbour of
    an expanded node (one whose value falls, or rises, which takes a finite
    g), or when its rhs becomes finite (a changed cell's corner requeued
    above: that takes a neighbour of finite g; one of inf stays blank). So
    every record written since the box was emptied lies in the box widened by
    one node, and the next fresh search blanks that instead of
    every record (a short plan on a large map cost time in proportion to the
    map; a fresh plan after a repair, to the map, until review 28 tracked
    repairs too). Kept where a value falls only, next to the fresh searches'
    prefetch: kept for every expansion, in registers, repairs took up to 4 %
    longer (the ``maze512-32-9`` mid-path replan) and fresh 1024² plans up to
    4 % (rooms, review 27); as it is, within the noise (see review 28's notes
    in ``FieldDStar._blank``).

    Called (never inlined) by its one caller, :func:`extract_path` of the path
    kernels, so its body is compiled once.
    """
    pad, vals, nodes, keys, pos, size, work, changed = st
    width, nrows, ncols, sr, sc, goal, km, interp, hscale, _, goal_cell, fresh = prm
    # Source value of the goal cell's corners (rows gi..gi+1, columns gj..gj+1), or
    # inf without a goal cell: written out here, as a helper function compiled more.
    seed = INF
    gi = goal_cell // ncols
    gj = goal_cell - gi * ncols
    if goal_cell >= 0:
        seed = pad[(gi + 1) * width + gj + 1] * HALF_DIAGONAL
    n_changed = changed[0]
    if n_changed > 0:
        # Cells changed since the last search (listed by update_costs): rhs of a node depends
        # only on the four cells around it, so their corners are the only nodes
        # whose rhs can change. Requeued here, with the current start and km.
        changed[0] = 0
        for q in range(1, n_changed + 1):
            cell_i = changed[q] // width - 1
            cell_j = changed[q] - (cell_i + 1) * width - 1
            for di in range(2):
                for dj in range(2):
                    i = cell_i + di
                    j = cell_j + dj
                    s = i * ncols + j
                    if s != goal:
                        v = node_rhs(pad, width, vals, ncols, i, j, interp)
                        if seed < v and gi <= i <= gi + 1 and gj <= j <= gj + 1:
                            v = seed
                        vals[RECORD * s + RHS] = v
                        update_vertex(s, i, j, vals, nodes, keys, pos, size, sr, sc, km, hscale)
    ti = target // ncols
    th = heuristic(sr, sc, ti, target - ti * ncols, hscale)
    spent = work[0]
    # A variable 0, not the literal (whose widening to int64 cost type inference
    # two more passes over this kernel).
    expanded: int = spent - spent
    limit = work[1]
    while size[0] > 0 and spent <= limit:
        gt = vals[RECORD * target]
        rt = vals[RECORD * target + RHS]
        mt = rt if rt < gt else gt
        top0 = keys[0]
        top1 = keys[1]
        if gt == rt and key_reached(top0, top1, mt, th, km):
            break
        u = nodes[0]
        ui = u // ncols
        uj = u - ui * ncols
        if km > 0.0:
            # Keys stored before the start moved may be low: requeue with the
            # current one (with km == 0 the start never moved and keys are exact).
            gu = vals[RECORD * u]
            ru = vals[RECORD * u + RHS]
            mu = ru if ru < gu else gu
            k0 = mu + heuristic(sr, sc, ui, uj, hscale) + km
            if top0 < k0 or (top0 == k0 and top1 < mu):
                # A queued node is inconsistent: this requeues it with its key.
                update_vertex(u, ui, uj, vals, nodes, keys, pos, size, sr, sc, km, hscale)
                continue
        expanded += 1
        # One neighbour loop for both cases: u's value falls to rhs(u) (lowered)
        # or rises to inf; ref is the value that options through u are bounded by.
        lowered = vals[RECORD * u] > vals[RECORD * u + RHS]
        if lowered:
            spent += 1
            vals[RECORD * u] = vals[RECORD * u + RHS]
            ref = vals[RECORD * u]
            # u (the top) is consistent now: dequeuing it pops the top. (ref != rhs(u)
            # is False, but not a literal: that would compile heap_update again.)
            change(nodes, keys, pos, size, u, ref, ref, ref != vals[RECORD * u + RHS], fresh)
            # The box of the records written (see above).
            if ui < work[2]:
                work[2] = ui
            if ui > work[3]:
                work[3] = ui
            if uj < work[4]:
                work[4] = uj
            if uj > work[5]:
                work[5] = uj
            if fresh and size[0] > 0:
                # The records of the next top's neighbours (three rows of three
                # records, 72 bytes a row: the lines of its first and last), fetched
                # while u's neighbours are settled. Fresh searches only: repairs
                # were slower with it (see Prefetch in the module notes).
                nx = nodes[0]
                for dr in range(-1, 2):
                    row = RECORD * (nx + dr * ncols - 1)
                    _prefetch(vals, row)
                    _prefetch(vals, row + 2 * RECORD + 2)
                # The cells its neighbours' pairs read: cell rows i-2..i+1, columns
                # j-2..j+1 of the next top (i, j) (padded index of cell (i-2, j-2):
                # nx + i - width - 1), 32 bytes a row: its first and last cell.
                cell = nx + nx // ncols - width - 1
                for dr in range(4):
                    _prefetch(pad, cell + dr * width)
                    _prefetch(pad, cell + dr * width + 3)
        else:
            spent += RAISE_WORK
            ref = vals[RECORD * u]
            vals[RECORD * u] = INF
        if lowered:
            # Written out (see _lower_neighbour); zero keeps m a runtime integer.
            zero = ui - ui
            _lower_neighbour(pad, width, vals, ncols, nrows, nodes, keys, pos, size, goal,
                             ui, uj, ref, interp, sr, sc, km, hscale, zero + 0)
            _lower_neighbour(pad, width, vals, ncols, nrows, nodes, keys, pos, size, goal,
                             ui, uj, ref, interp, sr, sc, km, hscale, zero + 1)
            _lower_neighbour(pad, width, vals, ncols, nrows, nodes, keys, pos, size, goal,
                             ui, uj, ref, interp, sr, sc, km, hscale, zero + 2)
            _lower_neighbour(pad, width, vals, ncols, nrows, nodes, keys, pos, size, goal,
                             ui, uj, ref, interp, sr, sc, km, hscale, zero + 3)
            _lower_neighbour(pad, width, vals, ncols, nrows, nodes, keys, pos, size, goal,
                             ui, uj, ref, interp, sr, sc, km, hscale, zero + 4)
            _lower_neighbour(pad, width, vals, ncols, nrows, nodes, keys, pos, size, goal,
                             ui, uj, ref, interp, sr, sc, km, hscale, zero + 5)
            _lower_neighbour(pad, width, vals, ncols, nrows, nodes, keys, pos, size, goal,
                             ui, uj, ref, interp, sr, sc, km, hscale, zero + 6)
            _lower_neighbour(pad, width, vals, ncols, nrows, nodes, keys, pos, size, goal,
                             ui, uj, ref, interp, sr, sc, km, hscale, zero + 7)
        else:
            for m in range(8):
                si = ui - RING_R[m]
                sj = uj - RING_C[m]
                if si < 0 or si >= nrows or sj < 0 or sj >= ncols:
                    continue
                s = si * ncols + sj
                if s == goal:
                    continue
                # Every option through u costs at least ref + 1/sqrt(2) (u an axis
                # neighbour of s) or ref + 1 (diagonal), see the module notes. A
                # lowered u cannot improve a neighbour at or below that; a neighbour
                # below it did not take its value from a raised u, and raising g(u)
                # (which never lowers an option) leaves its rhs unchanged.
                gain = _AXIS_GAIN if m % 2 == 0 else 1.0
                bound = ref + gain - 1e-9 * (1.0 + ref)
                if vals[RECORD * s + RHS] < bound:
                    continue
                v = node_rhs(pad, width, vals, ncols, si, sj, interp)
                # A goal cell's corner keeps its source value (a lowered u only
                # lowers rhs: the least of the two stays).
                if seed < v and gi <= si <= gi + 1 and gj <= sj <= gj + 1:
                    v = seed
                vals[RECORD * s + RHS] = v
                update_vertex(s, si, sj, vals, nodes, keys, pos, size, sr, sc, km, hscale)
        if not lowered:
            # rhs(u) depends on its neighbours only: unchanged, but u now
            # needs requeueing (or leaves the queue if g = rhs = inf).
            update_vertex(u, ui, uj, vals, nodes, keys, pos, size, sr, sc, km, hscale)
    work[0] = spent
    return expanded
