"""Indexed 4-ary min-heap for the monotone grid searches, A* and Dijkstra (private).

A* and Dijkstra only ever lower a queued node's key (decrease-key), so their
queue can be leaner than the general indexed heap of :mod:`navkit.planning.grid._dstar_heap`
that D* Lite needs. Each entry is two 64-bit values stored side by side in one
array, so a heap level is read from a single cache line:

``heap`` uint64, from :func:`aligned_heap`
    Slot ``i`` holds the primary key ``f`` at entry ``REC_BASE + 2 * i`` and its
    tie key, ``floor(resolution * tie) << 32 | node`` (see :func:`tie_key_bits`
    and Tie keys below), next to it: ties in ``f`` go to the smaller ``tie``,
    then to the smaller node id, so the order is total and a search is
    deterministic. Packing the node id into the tie key
    saves a third array and a random access per move. The array is 64-byte
    aligned and offset by ``REC_BASE`` so the four children of a slot share one
    cache line. ``f`` is stored as its IEEE 754 bits (``f.view(np.uint64)``):
    for the values a search queues (finite, >= 0, never -0.0 or NaN) the bits
    order as the numbers do, so the operations compare integers, which is
    cheaper than comparing floats, with the tie keys' comparison as a carry
    (:func:`_bits_precede`), and read a node id with a mask rather than a
    float conversion (issue 17, session 40: A* with corner cutting 7-14 %
    faster on the 1024² benchmark maps, the same expansions and paths). The
    ``rec_*`` operations take this uint64 form only (a float64 heap would be
    misordered by the carry); jump point search's queue keeps float64 entries
    and :func:`smallest_child`.
``meta``
    The A* kernel's 16-byte cell records (see
    :func:`navkit.planning.grid._astar_kernels.grid_search`): each queued node's
    heap slot lives in its record, not in a separate position array.

The heap is 4-ary (children of slot i are 4i + 1 .. 4i + 4): half the depth of a
binary heap, and :func:`rec_pop` moves the hole down along the smallest children
to a leaf and then sifts the last entry up from there (Floyd's bottom-up
method), which needs one comparison per child instead of two. :func:`rec_remove`
takes the entry out of any slot (A* expands a lowered node without first moving
it to the top).

Every index these operations compute is unsigned (``np.uint64``), so numba
adds no negative-index wraparound code to the accesses (review 23; see
Indices in :mod:`navkit.planning.grid._astar_kernels`).

Tie keys. The searches' tie is h, the heuristic distance to the goal in
cells (below ``rows + cols``), quantised to ``1 / resolution`` of a cell;
:func:`tie_resolution` picks, per grid, the finest power of two up to 16 whose
quantised ties fit the key: 31 bits in the ``rec_*`` heap's integer keys (a
key stays below 2**63, the "no candidate" sentinel of the A* kernel), 21 bits
in jump point search's float64 keys (below 2**53, exact). That is 1/16 of a
cell on every grid with ``rows + cols`` below 2**27 (A*) or 2**17 = 131,072
(JPS), and coarser by halves on longer grids only, never saturating. (Until
review 38 the tie was ``min(16 h, 2**20 - 1)`` on every grid: from 65,536
cells away from the goal every tie went by node id alone, which favours the
upper rows, and A* on a tall open grid with the goal at the bottom expanded
the plateau of equal f row by row: 101,248 cells for a path of 70,007 on a
4-connected 70,000 x 8 grid, 2,035,436 for 200,000 corner to corner on an
8-connected 16 x 200,000 one. The keys are the same bits as before wherever
every h is below 65,535.9375 on grids within those spans.)

Ties in f (session 43). Equal f means equal as computed, and sums of the
same moves in different orders round differently: on open grids of one cost
the cells of a plateau of equal f differ by an ulp or a few, and A* expanded
them in the order of those ulps rather than towards the goal (an empty 512 x
512 grid from (0, 0) to (511, 250): 63,760 cells for a path of 512). The A*
kernel therefore queues f's bits with the lowest :data:`F_TIE_BITS` cleared
(:data:`F_BAND`; the exponent and the 40 highest mantissa bits kept): values
of f less than 2**-40 of f apart, mostly the same value rounded differently,
share a key and are ordered by the tie key, towards the goal (512 cells
expanded there). Bands are fixed intervals, so two roundings of one value
straddling a band's edge still split (rarely: see :data:`F_TIE_BITS`, with
the bound on the path's cost). Only f below :data:`F_BAND_COSTS` times the
smallest cell cost is banded (review 40: the band's width grows with f, and
behind a few cells of cost 1e12 it spanned whole cheap rooms), and Dijkstra
to exhaustion (the distance fields) keeps every bit.

Limits: node ids below 2**32 and at most 2**31 - 1 queued nodes; the public
functions reject larger grids.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import NDArray

from navkit._shared.jit import (
    NO_REFCOUNT,
    njit_force_inline,
    njit_helper,
    njit_inline,
    typed_njit,
)
from navkit._shared.types import KernelInt

# The heap operations are called only from the search kernels, so they are
# compiled without a Python wrapper (a wrapper costs about a tenth of a second
# of first-use compilation each); the tests call them through kernels of their
# own. rec_sift_up is called from an LLVM-inlined function (the A* relax step):
# it says explicitly that it is not to be inlined itself.
_helper_not_inlined = typed_njit(**NO_REFCOUNT, no_cpython_wrapper=True, forceinline=False)

MAX_NODES = 2**31 - 1
"""Largest number of nodes (grid cells) the heap can index."""

_TWO32 = float(2**32)
_LOW32 = 2**32 - 1
_U32 = np.uint64(32)

TIE_RESOLUTION = 16.0
"""The finest tie resolution, per cell (ties in f go to the smaller h to 1/16 cell)."""
HEAP_TIE_LIMIT = float(2**31)
"""Quantised ties of the ``rec_*`` heap stay below this: its keys below 2**63."""
FLOAT_TIE_LIMIT = float(2**21)
"""Quantised ties of float64 keys (jump point search) stay below this: keys below 2**53."""


@njit_inline
def tie_resolution(rows: int, cols: int, limit: float) -> float:
    """Finest power of two up to :data:`TIE_RESOLUTION` with ``resolution * (rows + cols) < limit``.

    Every tie a search on a ``rows`` x ``cols`` grid makes (h in cells, octile
    or Manhattan, to a goal or, for Dijkstra, to cell (0, 0)) is below
    ``rows + cols``, so ``floor(resolution * h)`` is below ``limit``: the tie
    keys never saturate (see Tie keys in this module's docstring). A power of
    two, so ``resolution * h`` is exact.
    """
    resolution = TIE_RESOLUTION
    span = float(rows) + float(cols)
    while resolution * span >= limit:
        resolution *= 0.5
    return resolution


@njit_inline
def tie_key(tie: float, node: KernelInt, resolution: float) -> float:
    """Tie key of ``node``, a float: ``floor(resolution * tie) * 2**32 + node``.

    ``tie`` >= 0 with ``resolution * tie`` below :data:`FLOAT_TIE_LIMIT` (see
    :func:`tie_resolution`), so the key is an exact integer below 2**53.
    """
    return math.floor(tie * resolution) * _TWO32 + node


@njit_inline
def tie_key_bits(tie: float, node: KernelInt, resolution: float) -> np.uint64:
    """:func:`tie_key` as an integer, ``floor(resolution * tie) << 32 | node``.

    ``tie`` >= 0 with ``resolution * tie`` below :data:`HEAP_TIE_LIMIT` (see
    :func:`tie_resolution`), so the key is below 2**63. The conversion
    truncates, which is the floor of a number >= 0 (no rounding instruction).
    """
    return (np.uint64(np.int64(tie * resolution)) << _U32) | np.uint64(node)


@njit_inline
def node_of(key: float) -> KernelInt:
    """Node id packed into a tie key."""
    # np.int64, not int(): numba compiles int() as an overload of its own on first use.
    return np.int64(key) & _LOW32


@njit_inline
def _bits_precede(f1: np.uint64, k1: np.uint64, f2: np.uint64, k2: np.uint64) -> bool:
    """Whether entry (f1, k1) of the ``rec_*`` heap comes before (f2, k2): ``f1 < f2 + (k1 < k2)``.

    One comparison of the f bits with the tie keys' as a carry (LLVM: a
    compare and an add with carry), where the lexicographic test
    ``(f1 < f2) | ((f1 == f2) & (k1 < k2))`` (jump point search's float64
    queue) takes two comparisons and their logic. Exact for integers when
    ``f2`` is below 2**64 - 1, which the bits of a finite f >= 0 are (below
    2**63).

    The heap operations and the A* kernel write this expression out where
    they compare (review 50): numba copied and typed a call of this function
    again at each of its ten call sites (``inline="always"``), a few
    hundredths of a second of A*'s first use, for the same machine code. It
    stays as the expression's definition, which the tests check.
    """
    return bool(f1 < f2 + np.uint64(k1 < k2))


F_TIE_BITS = 12
"""Low bits of f's IEEE 754 bits that A*'s queue ignores: f within 2**-40 of itself ties.

f >= 0 below :data:`F_BAND_COSTS` times the smallest cell cost is queued
as ``bits(f) & F_BAND``, larger f as ``bits(f)`` (the keys still order as f
does: a banded key is at most its f's bits). Keys are equal only within one
binade (the exponent is kept) and an interval of 2**12 ulps there, so two f
with equal keys differ by less than 2**-40 times the smaller one, and the
keys order as f does otherwise (the bits are monotone in f). Bound: A*
expands a cell u before an open cell q only if ``f(u) < f(q) + 2**-40 f(u)``.
If q lies on an optimal path to u whose cells before q are closed with
their optimal cost (consistency: ``f*(q) <= f*(u)``), u is closed with
``g(u) < g*(u) + 2**-40 f(u)``. Closed cells are not reopened, so that
excess passes on to the cells reached through u; it grows past one band
only where such out-of-order expansions nest along an optimal path, each
needing two routes to one cell whose costs differ, in exact arithmetic, by
less than 2**-40 of f but not at all. With m of them nested the returned
cost is below ``C* / (1 - 2**-40)**m``, about ``C* (1 + m 2**-40)`` (C* the
optimum; each step: ``e' (1 - 2**-40) < e + 2**-40 C*``), on top of the
float arithmetic's rounding, which the exact comparison of f had too (it
orders f as rounded). On grids of one cost c, with heuristic weight 1, every
f is ``c (a + b sqrt(2))`` for integers a, b >= 0, and two different ones
below ``700,000 c`` differ by more than the band (``|p + q sqrt(2)| >= 1 /
(|p| + |q| sqrt(2))`` for integers p, q not both 0, as ``|p**2 - 2 q**2| >=
1``; that is at least ``c**2 / (2 f)`` against the band's ``2**-40 f``):
there the band merges only roundings of one value, and the path is
optimal up to the rounding. 12 bits: with 10, 6 of 400 searches between
random cells of an open 1024 x 1024 grid still split a plateau at a band's
edge; with 12, none of 636 on open grids of 256 x 256 to 8192 x 8192.
As only f below ``F_BAND_COSTS c_min`` (c_min the smallest cell cost) is
banded, each near tie adds less than ``2**-40 F_BAND_COSTS c_min = 2**-21
c_min``, a two-millionth of the cheapest move: the excess is below ``m
2**-40 min(C*, F_BAND_COSTS c_min)`` (review 40).
"""
F_BAND = np.uint64(2**64 - 2**F_TIE_BITS)
"""``bits(f) & F_BAND`` is A*'s queue key for f (see :data:`F_TIE_BITS`)."""
ALL_BITS = np.uint64(2**64 - 1)
"""The mask that keeps every bit of f (Dijkstra to exhaustion)."""
F_BAND_COSTS = float(2**19)
"""A*'s queue bands f (:data:`F_TIE_BITS`) only below this many times the smallest cell cost.

The band's width is relative, 2**-40 of f, and f counts every cost on the
way: behind three cells of cost 1e12 (f about 2.5e12), a band was 2 cost
units wide and the nested near ties of a 40 x 40 room of cost 1 took a path
6.6 units (cells) dearer than the optimum through it, which comparing f
exactly had found (review 40). Below ``2**19 c_min`` a band is narrower
than ``2**-21 c_min``: a grid of one cost c keeps the plateaus' fix where
it is exact (distinct f below about ``700,000 c`` differ by more than a
band, above), and no near tie costs more than 2**-21 of the cheapest move.
Above it f is compared exactly (paths of more than 524,288 cells of the
cheapest cost, or costs far above the cheapest on the way), and a plateau of
one f rounded differently is expanded whole again there, as before session
43: an open 512 x 512 grid of cost 1 from a 3 x 3 corner of cost 1e6 to
(511, 250) expands 59,599 cells for a path of 512 (517 banded everywhere).
Clearing one bit fewer in each binade above the end instead (the band then
never wider than ``2**-21 c_min``) keeps 517 there up to ``2**31 c_min``,
but cost 1-7 % more on the benchmark maps in alternating runs (review 40).
"""

REC_BASE = 3
"""Slot 0 sits at entry ``REC_BASE`` of the aligned array: with 16-byte entries,
the children ``4i + 1 .. 4i + 4`` of every slot then start on a 64-byte boundary
and share one cache line (``4i + 1 + REC_BASE`` is a multiple of 4)."""

# Placing entry (f, key) in slot i is written out where it happens (three
# stores: f, key, and the slot into the node's record at ``meta[4 * node + 3]``)
# rather than as an ``inline="always"`` helper: numba copies and re-processes
# such a helper's IR at every call site, a few hundredths of a second of
# first-use compilation each (issue 17).


@_helper_not_inlined
def rec_sift_up(
    heap: np.ndarray, meta: np.ndarray, i: KernelInt, f: np.uint64, key: np.uint64
) -> None:
    """Move the hole at slot i up past larger parents, then drop (f, key) in.

    ``i`` is the size of the heap to add an entry, or the queued node's slot to
    lower its priority (A* and Dijkstra only improve costs; not checked).
    """
    while i > 0:
        parent = (i - 1) >> 2
        pf = heap[np.uint64(2 * parent + 2 * REC_BASE)]
        pk = heap[np.uint64(2 * parent + 2 * REC_BASE + 1)]
        if f < pf + np.uint64(key < pk):  # _bits_precede, written out
            heap[np.uint64(2 * i + 2 * REC_BASE)] = pf
            heap[np.uint64(2 * i + 2 * REC_BASE + 1)] = pk
            meta[np.uint64(4 * (np.int64(pk) & _LOW32) + 3)] = i
            i = parent
        else:
            break
    heap[np.uint64(2 * i + 2 * REC_BASE)] = f
    heap[np.uint64(2 * i + 2 * REC_BASE + 1)] = key
    meta[np.uint64(4 * (np.int64(key) & _LOW32) + 3)] = i


@njit_inline
def smallest_child(
    heap: np.ndarray, b: KernelInt, i: KernelInt, n: KernelInt
) -> tuple[KernelInt, float, float]:
    """Smallest child (slot, f, key) of slot i among ``n`` entries; slot -1 when none.

    Slot ``j`` of the heap is at entries ``b + 2 * j`` (f) and ``b + 2 * j + 1``
    (tie key): ``b`` is 0 for the jump point search's float64 queue (the
    ``rec_*`` heap's uint64 entries have :func:`_smallest_bits`).
    """
    first = 4 * i + 1
    if first + 3 < n:
        # A two-round tournament on indices only, as in pop. (Selecting the
        # winners' keys along with their slots instead of loading them again
        # was no faster and took 0.2 s more of A*'s first use: review 23.)
        # Each comparison is the lexicographic test written out, its operands
        # loaded in the order of the calls it replaced (see _smallest_bits).
        a = b + 2 * first
        f1 = heap[np.uint64(a + 2)]
        k1 = heap[np.uint64(a + 3)]
        f0 = heap[np.uint64(a)]
        k0 = heap[np.uint64(a + 1)]
        b_wins = np.int64((f1 < f0) | ((f1 == f0) & (k1 < k0)))
        f3 = heap[np.uint64(a + 6)]
        k3 = heap[np.uint64(a + 7)]
        f2 = heap[np.uint64(a + 4)]
        k2 = heap[np.uint64(a + 5)]
        d_wins = np.int64((f3 < f2) | ((f3 == f2) & (k3 < k2)))
        left = first + b_wins
        right = first + 2 + d_wins
        fr = heap[np.uint64(b + 2 * right)]
        kr = heap[np.uint64(b + 2 * right + 1)]
        fl = heap[np.uint64(b + 2 * left)]
        kl = heap[np.uint64(b + 2 * left + 1)]
        r_wins = np.int64((fr < fl) | ((fr == fl) & (kr < kl)))
        best: KernelInt = left + r_wins * (right - left)
        return best, heap[np.uint64(b + 2 * best)], heap[np.uint64(b + 2 * best + 1)]
    if first >= n:
        return -1, 0.0, 0.0
    best = first
    bestf = heap[np.uint64(b + 2 * first)]
    bestk = heap[np.uint64(b + 2 * first + 1)]
    for j in range(first + 1, n):
        jf = heap[np.uint64(b + 2 * j)]
        jk = heap[np.uint64(b + 2 * j + 1)]
        if (jf < bestf) | ((jf == bestf) & (jk < bestk)):
            best = j
            bestf = jf
            bestk = jk
    return best, bestf, bestk


@njit_force_inline
def _smallest_bits(
    heap: np.ndarray, b: KernelInt, i: KernelInt, n: KernelInt
) -> tuple[KernelInt, np.uint64, np.uint64]:
    """:func:`smallest_child` of the ``rec_*`` heap (uint64 entries, at ``b`` = 2 * REC_BASE).

    The same tournament with :func:`_bits_precede`. (A copy rather than one
    function for both queues: the comparison differs with the entries' type.)

    Compiled once and inlined by LLVM into its two callers, :func:`rec_pop`
    and :func:`_rec_sift_down` (review 50): inlined by numba
    (``inline="always"``) it was copied, typed and lowered again in each, and
    with its comparisons written out a cold ``astar`` took 1.34-1.48 ->
    1.22-1.32 s CPU (numba imported before the clock, three alternating
    pairs). A* ÷ pyastar2d with corner cutting, seven alternating pairs on a
    busy 2-core machine, medians 0.713 / 0.906 / 0.659 -> 0.718 / 0.900 / 0.651
    (random 20 %, random 35 %, rooms), the pairs' spread 3 %: no change found.
    The same expansions, paths and costs.
    """
    first = 4 * i + 1
    if first + 3 < n:
        # A two-round tournament on indices only. (Selecting the winners'
        # keys along with their slots instead of loading them again was no
        # faster and took 0.2 s more of A*'s first use: review 23.) Each
        # comparison is _bits_precede written out, its operands loaded in
        # the order of the calls it replaced (the same machine code).
        a = b + 2 * first
        f1 = heap[np.uint64(a + 2)]
        k1 = heap[np.uint64(a + 3)]
        f0 = heap[np.uint64(a)]
        k0 = heap[np.uint64(a + 1)]
        b_wins = np.int64(f1 < f0 + np.uint64(k1 < k0))
        f3 = heap[np.uint64(a + 6)]
        k3 = heap[np.uint64(a + 7)]
        f2 = heap[np.uint64(a + 4)]
        k2 = heap[np.uint64(a + 5)]
        d_wins = np.int64(f3 < f2 + np.uint64(k3 < k2))
        left = first + b_wins
        right = first + 2 + d_wins
        fr = heap[np.uint64(b + 2 * right)]
        kr = heap[np.uint64(b + 2 * right + 1)]
        fl = heap[np.uint64(b + 2 * left)]
        kl = heap[np.uint64(b + 2 * left + 1)]
        r_wins = np.int64(fr < fl + np.uint64(kr < kl))
        best: KernelInt = left + r_wins * (right - left)
        return best, heap[np.uint64(b + 2 * best)], heap[np.uint64(b + 2 * best + 1)]
    if first >= n:
        # The heap's own entries, not literals: a literal 0.0 would type the
        # result as float64 (numba unifies the return types), rounding the
        # bits of f. The values are not used.
        return -1, heap[np.uint64(b)], heap[np.uint64(b + 1)]
    best = first
    bestf = heap[np.uint64(b + 2 * first)]
    bestk = heap[np.uint64(b + 2 * first + 1)]
    for j in range(first + 1, n):
        jf = heap[np.uint64(b + 2 * j)]
        jk = heap[np.uint64(b + 2 * j + 1)]
        if jf < bestf + np.uint64(jk < bestk):  # _bits_precede, written out
            best = j
            bestf = jf
            bestk = jk
    return best, bestf, bestk


@njit_helper
def rec_pop(heap: np.ndarray, meta: np.ndarray, n: KernelInt) -> KernelInt:
    """Remove the smallest of the ``n`` (> 0) entries and return its node."""
    top = np.int64(heap[2 * REC_BASE + 1]) & _LOW32  # node_of, written out
    last = n - 1
    if last == 0:
        return top
    f = heap[np.uint64(2 * REC_BASE + 2 * last)]
    key = heap[np.uint64(2 * REC_BASE + 2 * last + 1)]
    # Floyd's method: the hole goes down to a leaf, then the last entry up.
    # np.int64: a literal 0 would compile _smallest_bits once more.
    i: KernelInt = np.int64(0)
    while True:
        best, bestf, bestk = _smallest_bits(heap, 2 * REC_BASE, i, last)
        if best < 0:
            break
        heap[np.uint64(2 * i + 2 * REC_BASE)] = bestf
        heap[np.uint64(2 * i + 2 * REC_BASE + 1)] = bestk
        meta[np.uint64(4 * (np.int64(bestk) & _LOW32) + 3)] = i
        i = best
    rec_sift_up(heap, meta, np.int64(i), f, key)
    return top


@njit_helper
def rec_replace_top(
    heap: np.ndarray, meta: np.ndarray, n: KernelInt, f: np.uint64, key: np.uint64
) -> KernelInt:
    """Remove the top of the ``n`` (> 0) entries, add (f, key) and return the removed node.

    One walk down from the root, stopping where (f, key) fits: cheaper than a
    push and a pop when (f, key) is near the top, as the best new neighbour
    of the cell just expanded usually is.
    """
    top = np.int64(heap[2 * REC_BASE + 1]) & _LOW32  # node_of, written out
    # np.int64: a literal 0 would compile _rec_sift_down once more.
    _rec_sift_down(heap, meta, np.int64(0), n, f, key)
    return top


@njit_helper
def rec_remove(heap: np.ndarray, meta: np.ndarray, n: KernelInt, i: KernelInt) -> None:
    """Remove the entry in slot i of the ``n`` (> i) entries.

    The last entry fills the hole and moves up or down from there: a slot
    deep in the heap, where most entries sit, costs a walk of a level or two
    rather than the full depth that lowering the entry to the top and
    popping it would.
    """
    last = n - 1
    if i == last:
        return
    f = heap[np.uint64(2 * REC_BASE + 2 * last)]
    key = heap[np.uint64(2 * REC_BASE + 2 * last + 1)]
    if i > 0:
        parent = (i - 1) >> 2
        pf = heap[np.uint64(2 * parent + 2 * REC_BASE)]
        pk = heap[np.uint64(2 * parent + 2 * REC_BASE + 1)]
        if f < pf + np.uint64(key < pk):  # _bits_precede, written out
            rec_sift_up(heap, meta, i, f, key)
            return
    _rec_sift_down(heap, meta, i, last, f, key)


@njit_helper
def _rec_sift_down(
    heap: np.ndarray, meta: np.ndarray, i: KernelInt, n: KernelInt, f: np.uint64, key: np.uint64
) -> None:
    """Move the hole at slot i down past smaller children (``n`` entries), then put (f, key) in.

    A helper of its own, shared by :func:`rec_replace_top` and
    :func:`rec_remove` (issue 17: as an ``inline="always"`` function its body
    and the inlined :func:`_smallest_bits` were typed again in each, about
    0.4 s of first use). Not LLVM-inlined (``forceinline``) either: that made
    corner-cutting A* on rooms 3 % slower.
    """
    while True:
        best, bestf, bestk = _smallest_bits(heap, 2 * REC_BASE, i, n)
        # _bits_precede, written out.
        if best < 0 or not bestf < f + np.uint64(bestk < key):
            break
        heap[np.uint64(2 * i + 2 * REC_BASE)] = bestf
        heap[np.uint64(2 * i + 2 * REC_BASE + 1)] = bestk
        meta[np.uint64(4 * (np.int64(bestk) & _LOW32) + 3)] = i
        i = best
    heap[np.uint64(2 * i + 2 * REC_BASE)] = f
    heap[np.uint64(2 * i + 2 * REC_BASE + 1)] = key
    meta[np.uint64(4 * (np.int64(key) & _LOW32) + 3)] = i


def aligned_heap(entries: int) -> NDArray[np.uint64]:
    """A 64-byte aligned uint64 array for ``entries`` queue entries of the ``rec_*`` heap."""
    raw = np.empty(2 * (entries + REC_BASE) + 8, dtype=np.uint64)
    skip = (-raw.ctypes.data % 64) // 8
    return raw[skip : skip + 2 * (entries + REC_BASE)]
