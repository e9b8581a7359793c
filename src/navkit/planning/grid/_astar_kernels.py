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

Indices (review 23). Every array index the search and its queue compute is
passed as ``np.uint64(...)``: for a signed index numba adds Python's
wraparound (the array's length added to a negative index: a shift, a mask and
an add, or a compare and a ``cmov``, per access) wherever LLVM cannot prove it
non-negative, which it could not for a neighbour (``u - cols``), a record
(``4 * v + 2``) or a heap slot. These indices are never negative, so the
unsigned one names the same element with none of that code. The cast goes on
the index alone: numba types arithmetic mixing uint64 and int64 as float64.
Same expansions, paths and costs; A* about 8 % faster with corner cutting and
10 % without, on the 1024² benchmark maps; about 0.07 s more of first use.
Tried in the same review and dropped (A* ÷ pyastar2d with corner cutting,
medians of 3-5 alternating runs, every variant with the same expansions): a
tournament selecting the winners' keys along with their slots (no reload),
1-3 % faster before the unsigned indices and no faster with them, and 0.2 s
more of first use; a queue with lazy deletion (a lowered cell queued again,
stale entries skipped when popped; no heap slots in the records), 1.2-1.25
on all three maps against 0.8-1.0, the stale entries of cells expanded as
candidates costing a whole pop each; the tournament of Field D*'s pop (first
components alone unless tied), slower (0.84 -> 0.92 on random 20 %), f ties
among siblings being common in A* on maps of one cost; an 8-ary heap with
128-byte families, slower on the random maps (0.83 -> 0.90); prefetching the
pop's next families, or the neighbour rows' records and costs at each
expansion, no change; the first level of a push written into :func:`_relax`
(no call when the entry stays a leaf), no change; branch-free
comparisons (the lexicographic test) in :func:`_relax` and the sift-up, no change.

Integer queue entries (session 40, issue 17's A* row on an AVX-512 Xeon,
where random 35 % was 1.00-1.04 times pyastar2d's time). The queue holds f
as its IEEE 754 bits and the tie key as an integer (see
:mod:`navkit.planning.grid._search_heap`): integer comparisons in every
heap walk and candidate test, the tie keys' as a carry
(``f1 < f2 + (k1 < k2)``), and node ids read with a mask instead of a
float-to-integer conversion; and a queued candidate that does not go next
is taken out of its slot and queued again by the top's removal (one walk
from the root that stops near the top) instead of being moved up and the
top popped (a walk to a leaf). Same expansions, paths and costs. A* ÷
pyastar2d with corner cutting (thread CPU, medians of alternating runs in
one process, the kernel alone): 0.80 / 0.97 / 0.81 -> 0.74 / 0.87 / 0.68
on random 20 %, random 35 % and rooms (integer entries with the
lexicographic comparison alone: 0.76 / 0.93 / 0.77; the carry gave the
rest). Tried in the same session and
dropped (no gain or slower, every variant with the same expansions): a
branch-free mask of the moves to open or unreached traversable cells,
walked with a trailing-zero count (16-25 % slower) or tested bit by bit
(8-12 % slower); one comparison per move against a limit selected from
the mark (closed -inf, queued g, unreached +inf; 4-14 % slower): the
branches let the CPU run ahead to the next loads, which a chain of
selects does not; heap slots in an int32 array of their own (denser than
the records; 2-4 % slower); a top-down pop (sift-down of the last entry)
instead of Floyd's, or the pop's sift-up LLVM-inlined, within noise; the
search compiled for corner cutting only (constants for ``eight`` and
``corner_cutting``), within noise; costs read from a float32 copy of the
grid (an experiment, not exact for every grid), 2-4 %. A profile
(``perf record -e cpu-clock``, no hardware counters in this virtual
machine) put about 47 % of the search in the heap walks, most of it in
the pop's dependent chain of child loads and comparisons, and about 14 %
in loading the marks and costs of neighbours not yet in cache.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from navkit._shared.jit import (
    bind_numba_names,
    njit_force_inline,
    njit_helper,
    njit_inline,
    njit_released,
)
from navkit._shared.types import KernelInt

# grid_search's machine code holds the heap operations below, and numba keys its
# cache on this file alone: a change to them is recorded here so that a cache
# built with the old ones is dropped (review 50: their comparisons written out).
from navkit.planning.grid._search_heap import (
    F_BAND,
    HEAP_TIE_LIMIT,
    REC_BASE,
    rec_pop,
    rec_remove,
    rec_replace_top,
    rec_sift_up,
    tie_key_bits,
    tie_resolution,
)

SQRT2 = math.sqrt(2.0)
_OCTILE_EXTRA = SQRT2 - 1.0
# The bits of a float64 (an LLVM bitcast, see navkit.planning.grid._float_bits),
# bound when numba loads: importing this module must not import numba.
_f64_bits: Any = None


def _f64_bits_python(x: float) -> np.uint64:
    """``_f64_bits`` when the JIT is disabled: NumPy's view of the scalar."""
    return np.float64(x).view(np.uint64)


bind_numba_names(globals(), "navkit.planning.grid._float_bits",
                 python={"_f64_bits": _f64_bits_python}, _f64_bits="f64_bits")  # fmt: skip

# "No candidate yet": above the bits of every f a search queues (finite, >= 0:
# below 2**63) and every tie key, and below 2**64 - 1 (see _bits_precede).
_NONE = np.uint64(2**63)

# Move directions: 0-3 orthogonal (N, S, W, E), 4-7 diagonal (NW, NE, SW, SE).
# A diagonal d passes beside the orthogonal cells (DR[d], 0) and (0, DC[d]).
DR = np.array([-1, 1, 0, 0, -1, -1, 1, 1], dtype=np.int64)
DC = np.array([0, 0, -1, 1, -1, 1, -1, 1], dtype=np.int64)


@njit_inline
def _cells_to_goal(r: KernelInt, c: KernelInt, gr: int, gc: int, octile: bool) -> float:
    """Octile (8-connected) or Manhattan (4-connected) distance in cells."""
    # mypy infers abs() of an ``int | np.int64`` as ``object``.
    dr: KernelInt = abs(r - gr)  # type: ignore[assignment]
    dc: KernelInt = abs(c - gc)  # type: ignore[assignment]
    if octile:
        # Selects (LLVM makes them branch-free: the comparison is unpredictable),
        # not the min/max builtins, which numba compiles as overloads of their own.
        longer = dr if dr > dc else dc
        shorter = dc if dr > dc else dr
        return longer + _OCTILE_EXTRA * shorter
    return float(dr + dc)


@njit_force_inline
def _relax(
    flat: np.ndarray,
    rec: np.ndarray,
    meta: np.ndarray,
    heap: np.ndarray,
    n: KernelInt,
    open_mark: int,
    closed_mark: int,
    v: KernelInt,
    code: int,
    step: float,
    gu: float,
    cu: float,
    r: KernelInt,
    c: KernelInt,
    gr: int,
    gc: int,
    octile: bool,
    scale: float,
    tie_res: float,
    limit: np.uint64,
    next_f: np.uint64,
    next_key: np.uint64,
    next_v: KernelInt,
    next_queued: bool,
) -> tuple[np.uint64, np.uint64, KernelInt, KernelInt, bool]:
    """Try a move to cell ``v`` = (r, c); return the next-node candidate and queue size.

    ``code`` is what the cell's record stores when the move improves it,
    ``open_mark << 4 | (d + 1)`` for the move's direction ``d`` (computed by
    the caller: a literal argument would compile this function once more).
    The candidate (next_f, next_key, next_v, next_queued) is the best
    neighbour this expansion improved (next_v = -1: none yet); its f and
    tie key are in the queue's uint64 form (see ``heap`` in
    :mod:`navkit.planning.grid._search_heap`), as ``heap`` is. It is often
    the very node the next pop would return, so its queue update waits:
    a newly reached candidate is not pushed, a queued one (next_queued)
    keeps its old, larger priority in the heap until it is either expanded
    next (and removed from its slot) or loses the place of candidate.
    """
    cv = flat[np.uint64(v)]
    if cv == np.inf:
        return next_f, next_key, next_v, n, next_queued
    mark = meta[np.uint64(4 * v + 2)] >> 4
    if mark == closed_mark:
        return next_f, next_key, next_v, n, next_queued
    new_g = gu + step * 0.5 * (cu + cv)
    # The record of a cell this search has not reached is stale: test the mark first.
    queued = mark == open_mark
    if queued and new_g >= rec[np.uint64(2 * v)]:
        return next_f, next_key, next_v, n, next_queued
    rec[np.uint64(2 * v)] = new_g
    meta[np.uint64(4 * v + 2)] = code
    h = _cells_to_goal(r, c, gr, gc, octile)
    # The bits of f (>= 0, finite), which order as f does, less the low bits
    # F_BAND clears below ``limit`` (the bits of F_BAND_COSTS times the
    # smallest cell cost): f within 2**-40 of itself (a plateau's f rounded
    # differently) ties (see F_TIE_BITS in _search_heap, with the bound).
    bits: np.uint64 = _f64_bits(new_g + scale * h)
    f: np.uint64 = bits & F_BAND if bits < limit else bits
    # Ties in f go to the cell nearer the goal, which keeps A* from expanding
    # whole plateaus of equal f (h to 1 / tie_res cells, at every distance).
    key = tie_key_bits(h, v, tie_res)
    if f < next_f + np.uint64(key < next_key):  # _bits_precede, written out
        if next_v < 0:
            return f, key, v, n, queued
        # v becomes the candidate and the old candidate goes to the heap instead.
        f, key, v, queued, next_f, next_key, next_v, next_queued = (
            next_f, next_key, next_v, next_queued, f, key, v, queued
        )
    # A queued cell's entry moves up from its slot (A* only lowers priorities);
    # any other cell is pushed. (Written here, not as a helper: one function
    # fewer to compile on first use.)
    if queued:
        rec_sift_up(heap, meta, np.int64(meta[np.uint64(4 * v + 3)]), f, key)
    else:
        rec_sift_up(heap, meta, n, f, key)
        n += 1
    return next_f, next_key, next_v, n, next_queued


@njit_released
def grid_search(
    flat: np.ndarray,
    rows: int,
    cols: int,
    start: int,
    goal: int,
    eight: bool,
    corner_cutting: bool,
    scale: float,
    band_end: float,
    rec: np.ndarray,
    meta: np.ndarray,
    heap: np.ndarray,
    stamp: int,
) -> tuple[int, int, int, int]:
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
    band_end : float
        f below which the queue ignores f's lowest ``F_TIE_BITS`` bits when
        ``goal`` >= 0: ``F_BAND_COSTS`` times the minimum cell cost (0: f
        compared exactly everywhere; see
        :data:`navkit.planning.grid._search_heap.F_BAND_COSTS`).
    rec : (2 * rows * cols,) float64
        Cell records, 16 bytes each so one cache line holds a cell's whole
        search state: ``rec[2 * v]`` is its cost from ``start``; ``meta``, an
        int32 view of the same memory, holds ``mark << 4 | (d + 1)`` at
        ``4 * v + 2``, with ``d`` the direction index (into ``DR``/``DC``) of
        the move that reached it (-1 at ``start``), and its heap slot while
        queued at ``4 * v + 3``. A mark below ``stamp`` means never reached by
        this search (the rest of the record is then stale).
    meta : (4 * rows * cols,) int32
        The int32 view of ``rec``.
    heap : (2 * capacity,) uint64
        Scratch for the queue, (f, tie key) pairs of the indexed 4-ary heap of
        :func:`navkit.planning.grid._search_heap.rec_pop` in their integer
        form (the bits of f and the integer tie key, see that module; slot i
        at entry ``i + REC_BASE``; 64-byte aligned, from ``aligned_heap``).
        Receives the path when the goal is reached (see ``cells``).
    stamp : int
        This search's open mark (closed is ``stamp + 1``), above every mark
        left in ``meta`` by earlier searches and below ``2**27 - 1``.

    Returns
    -------
    expanded : int
        Number of cells closed.
    found : int
        1 when ``goal`` was closed, 0 when not (unreachable, or ``goal`` -1),
        -1 when ``heap`` filled up, -2 when the path did not fit in it
        (``cells`` cells): search again with a larger one and a fresh stamp.
    cells : int
        Number of cells on the path when found (else 0); ``heap[2 * i]``,
        ``heap[2 * i + 1]`` are then the row and column of its i-th cell
        from ``start`` (see :func:`_trace`).
    diagonal : int
        How many of its steps are diagonal: its length in cells is
        ``cells - 1 - diagonal + sqrt(2) * diagonal``.

    Notes
    -----
    On return the mark is ``stamp + 1`` for every closed cell (exhaustion
    closes every reachable one) and its cost is exact when the heuristic
    weight is <= 1 (to the f band's bound below when ``goal`` >= 0). The
    queue orders cells by (f, tie key) with f = g + scale
    × distance in cells, f's lowest ``F_TIE_BITS`` bits ignored when ``goal``
    >= 0 and f is below ``band_end`` (f within 2**-40 of itself ties; the
    bound on the cost is at
    :data:`navkit.planning.grid._search_heap.F_TIE_BITS`); the order is
    total, so the search is deterministic.
    A queued cell's heap slot is kept in its record, in the cache line the
    search reads for the cell anyway. After expanding a cell, the best
    neighbour it improved is expanded next directly when it precedes the
    heap's top, which is exactly the cell the heap would return, without
    the heap walks: a newly reached one is never pushed, a queued one is
    removed from its slot (a level or two deep, usually) instead of being
    moved up to the top and popped: the same expansions, 5-14 % faster on
    1024² random and room maps with corner cutting, 2-10 % without. The
    eight moves are written out one by one so each has constant offsets and
    bounds tests.
    """
    open_mark = stamp
    closed_mark = stamp + 1
    gr = goal // cols if goal >= 0 else 0
    gc = goal - gr * cols if goal >= 0 else 0
    open16 = open_mark << 4
    # Ties to 1/16 cell unless rows + cols >= 2**27 (see _search_heap).
    tie_res = tie_resolution(rows, cols, HEAP_TIE_LIMIT)
    # f's lowest bits ignored when searching for a goal (session 43), below
    # band_end only (review 40); kept by Dijkstra to exhaustion (the distance
    # fields: exact order).
    limit = _f64_bits(band_end) if goal >= 0 else np.uint64(0)
    rec[np.uint64(2 * start)] = 0.0
    meta[np.uint64(4 * start + 2)] = open_mark << 4
    expanded = 0
    found = 0
    n: KernelInt = np.int64(0)  # np.int64: a literal 0 would compile callees once more
    u: KernelInt = start
    while True:
        meta[np.uint64(4 * u + 2)] = (closed_mark << 4) | (meta[np.uint64(4 * u + 2)] & 15)
        expanded += 1
        if u == goal:
            found = 1
            break
        # One expansion queues at most 8 cells.
        if 2 * (n + 8 + REC_BASE) > heap.size:
            return expanded, -1, 0, 0
        r = u // cols
        c = u - r * cols
        gu = rec[np.uint64(2 * u)]
        cu = flat[np.uint64(u)]
        n_in = r > 0
        s_in = r + 1 < rows
        w_in = c > 0
        e_in = c + 1 < cols
        nf = _NONE
        nk = _NONE
        nv: KernelInt = np.int64(-1)
        # Not the literal False: numba would compile _relax once more for its type.
        nq = bool(nv >= 0)
        if n_in:
            nf, nk, nv, n, nq = _relax(
                flat, rec, meta, heap, n, open_mark, closed_mark, u - cols, open16 | 1, 1.0, gu, cu,
                r - 1, c, gr, gc, eight, scale, tie_res, limit, nf, nk, nv, nq
            )  # fmt: skip
        if s_in:
            nf, nk, nv, n, nq = _relax(
                flat, rec, meta, heap, n, open_mark, closed_mark, u + cols, open16 | 2, 1.0, gu, cu,
                r + 1, c, gr, gc, eight, scale, tie_res, limit, nf, nk, nv, nq
            )  # fmt: skip
        if w_in:
            nf, nk, nv, n, nq = _relax(
                flat, rec, meta, heap, n, open_mark, closed_mark, u - 1, open16 | 3, 1.0, gu, cu, r,
                c - 1, gr, gc, eight, scale, tie_res, limit, nf, nk, nv, nq
            )  # fmt: skip
        if e_in:
            nf, nk, nv, n, nq = _relax(
                flat, rec, meta, heap, n, open_mark, closed_mark, u + 1, open16 | 4, 1.0, gu, cu, r,
                c + 1, gr, gc, eight, scale, tie_res, limit, nf, nk, nv, nq
            )  # fmt: skip
        if eight:
            if corner_cutting:
                nw = n_in and w_in
                ne = n_in and e_in
                sw = s_in and w_in
                se = s_in and e_in
            else:
                # A diagonal needs both cells it passes beside (MovingAI rule).
                n_ok = n_in and flat[np.uint64(u - cols)] < np.inf
                s_ok = s_in and flat[np.uint64(u + cols)] < np.inf
                w_ok = w_in and flat[np.uint64(u - 1)] < np.inf
                e_ok = e_in and flat[np.uint64(u + 1)] < np.inf
                nw = n_ok and w_ok
                ne = n_ok and e_ok
                sw = s_ok and w_ok
                se = s_ok and e_ok
            if nw:
                nf, nk, nv, n, nq = _relax(
                    flat, rec, meta, heap, n, open_mark, closed_mark, u - cols - 1, open16 | 5,
                    SQRT2, gu, cu, r - 1, c - 1, gr, gc, eight, scale, tie_res, limit,
                    nf, nk, nv, nq
                )  # fmt: skip
            if ne:
                nf, nk, nv, n, nq = _relax(
                    flat, rec, meta, heap, n, open_mark, closed_mark, u - cols + 1, open16 | 6,
                    SQRT2, gu, cu, r - 1, c + 1, gr, gc, eight, scale, tie_res, limit,
                    nf, nk, nv, nq
                )  # fmt: skip
            if sw:
                nf, nk, nv, n, nq = _relax(
                    flat, rec, meta, heap, n, open_mark, closed_mark, u + cols - 1, open16 | 7,
                    SQRT2, gu, cu, r + 1, c - 1, gr, gc, eight, scale, tie_res, limit,
                    nf, nk, nv, nq
                )  # fmt: skip
            if se:
                nf, nk, nv, n, nq = _relax(
                    flat, rec, meta, heap, n, open_mark, closed_mark, u + cols + 1, open16 | 8,
                    SQRT2, gu, cu, r + 1, c + 1, gr, gc, eight, scale, tie_res, limit,
                    nf, nk, nv, nq
                )  # fmt: skip
        if nv >= 0:
            top_f = heap[2 * REC_BASE]
            # Equal keys: the top is the candidate's own entry (a queued cell
            # whose g fell by less than f's rounding), which goes next.
            if n == 0 or nf < top_f + np.uint64(nk <= heap[2 * REC_BASE + 1]):
                if nq:
                    rec_remove(heap, meta, n, np.int64(meta[np.uint64(4 * nv + 3)]))
                    n -= 1
                u = nv
                continue
            if nq:
                # Out of its slot (a walk of a level or two), then queued again
                # with the top's removal below: a walk down from the root that
                # stops where it fits, near the top, where moving it up and
                # popping walked the hole down to a leaf (A* ÷ pyastar2d on
                # random 35 %, corner cutting: 1-4 % faster; session 40).
                rec_remove(heap, meta, n, np.int64(meta[np.uint64(4 * nv + 3)]))
                n -= 1
            # Queue it and take the top in one walk down from the root.
            u = rec_replace_top(heap, meta, n, nf, nk)
            continue
        if n == 0:
            break
        u = rec_pop(heap, meta, n)
        n -= 1
    if not found:
        return expanded, 0, 0, 0
    cells, diagonal = _trace(meta, cols, goal, heap)
    return expanded, 1 if cells <= heap.size >> 1 else -2, cells, diagonal


@njit_helper
def _trace(meta: np.ndarray, cols: int, goal: int, out: np.ndarray) -> tuple[int, int]:
    """Write the path's cells into ``out``; return (cell count, diagonal steps).

    Follows the direction indices written by :func:`grid_search` (low 4 bits
    of ``meta[4 * v + 2]``, direction + 1) back from ``goal`` until the source
    (0 there): ``out[2 * i]``, ``out[2 * i + 1]`` are the row and column of
    the i-th cell from the source. Writes nothing when ``out`` is too small
    (the count says how large it must be). Run by the search kernel rather
    than as a kernel of its own: a kernel that allocates the path costs a
    quarter of a second of first-use compilation.
    """
    k = 1
    v = goal
    while meta[4 * v + 2] & 15:
        d = (meta[4 * v + 2] & 15) - 1
        v -= DR[d] * cols + DC[d]
        k += 1
    if 2 * k > out.size:
        return k, 0
    n_diag = 0
    v = goal
    for i in range(k - 1, -1, -1):
        r = v // cols
        out[2 * i] = r
        out[2 * i + 1] = v - r * cols
        if i > 0:
            d = (meta[4 * v + 2] & 15) - 1
            if d >= 4:
                n_diag += 1
            v -= DR[d] * cols + DC[d]
    return k, n_diag
