"""numba kernels for jump point search (JPS) on uniform-cost grids (private).

Jump point search (D. Harabor and A. Grastien, "Online Graph Pruning for
Pathfinding on Grid Maps", AAAI 2011) is A* on an 8-connected grid of equal
cell costs that expands only "jump points": from each expanded node it scans
straight and diagonal lines and stops only where an optimal path may have to
turn. The rules here are those of the variant without corner cutting (a
diagonal move needs both cells it passes beside to be free, the MovingAI
convention; Harabor and Grastien, "Improving Jump Point Search", ICAPS 2014):

* a straight scan stops at a cell with a *forced* side neighbour: the side
  cell is free while the side cell one step back is blocked (the side cell
  could not be reached diagonally from the cell behind, so an optimal path
  may turn there);
* a diagonal scan stops at a cell from which either straight scan along its
  two components reaches a jump point; diagonal moves have no forced
  neighbours of their own;
* a node reached by a straight move continues straight and, on each side
  with a forced neighbour, turns onto that side both straight and
  diagonally; a node reached diagonally continues along the diagonal and its
  two straight components; the start scans all eight directions.

A jump point reached by a straight move whose cell ahead is blocked and
which has exactly one forced side (the corner of a one-cell corridor) has a
single successor: it is passed through (:func:`_follow_corridor`) instead of
queued, so a winding corridor costs no queue operations and a dead-end
branch none at all.

The straight scans read 64 cells at a time from bit rows (the block-based
scanning of Harabor and Grastien 2014): one bit board for the rows and a
transposed one for the columns, each line padded by a blocked border so no
bounds test is needed, each bit row padded by one empty word at both ends so
a shifted word can always borrow its neighbour's edge bit.

Coordinates inside the scans are *padded*: cell ``(r, c)`` of the grid is
``(r + 1, c + 1)``. Search nodes (``g``, marks, heap and parents) are the
unpadded flat indices ``r * cols + c`` of the caller's grid.

The tables, node records, queue and path tracing here also serve the
corner-cutting variant, :mod:`navkit.planning.grid._jps_cut_kernels`.

Ties in f (review 40). The queue orders jump points by f as A*'s does (see
Ties in f in :mod:`navkit.planning.grid._search_heap`): f with its lowest
:data:`~navkit.planning.grid._search_heap.F_TIE_BITS` bits cleared (the
float64 with the bits ``bits(f) & F_BAND``) where f is below
:data:`~navkit.planning.grid._search_heap.F_BAND_COSTS` cells (2**19; above,
f exactly), then the tie key, towards the goal. Costs are sums of 1 and
sqrt(2) in different orders, so one f reached by different routes differs by
an ulp or a few; compared exactly, the queue expanded such plateaus in the
order of those ulps rather than towards the goal. On MovingAI's
``random512-10-0`` (its 1,780 problems) that was 9,031,338 jump points
without corner cutting and 1,807,384 with it, now 8,004,276 and 1,114,374
(up to 17 and 38 times fewer on one problem); 0.3-1.4 % fewer on the street
and game maps, the mazes and rooms unchanged within 0.1 %. Every f here is
``a + b sqrt(2)`` for integers a, b >= 0 (lengths in cells), and two
different ones below 700,000 cells never share a band (the argument at
``F_TIE_BITS``): the band merges roundings of one value only, and the paths
stay optimal up to rounding, possibly another of the equally short ones. The
cost of the band: five instructions per queued jump point, branch-free (the
bits' mask and a masked move after a comparison with ``F_BAND_COSTS``).

Reached again at the same length (review 41, measured and not kept). An open
node reached by another route of the same length, summed in another order,
can come out an ulp or a few shorter: :func:`_reach` then records it again
and it is queued a second time (the first entry is dropped when popped;
with corner cutting a diagonal walk also goes on past it). Over all MovingAI
problems of the shared data that is 0.74 % of the reaches on
``random512-10-0`` (88,667 of 11,910,873) and 1.2 % with corner cutting
(52,412 of 4,397,931), at most 0.7 % on the other maps and none on the
mazes. Refusing them (below ``F_BAND_COSTS`` cells lengths within 2**-40 of
each other are one value, the argument above) is exact, every cost the same
bits over the 33,440 problems, and on ``random512-10-0`` expands 0.06 % and,
with corner cutting, 1.1 % fewer jump points, but was not faster: thread CPU
over the problems of ``random512-10-0``, ``8room_000``, ``arena2`` and
``Berlin_0_1024`` with and without corner cutting, medians of 4 alternating
pairs of runs 0.99-1.05 of the code kept, each range spanning 1.

Indices (review 25). The bit scans (:func:`_scan_line`, :func:`_free`) index
the bit tables with ``np.uint64``, as A* indexes its arrays (see Indices in
:mod:`navkit.planning.grid._astar_kernels`): numba then emits no wraparound
of negative indices, which LLVM could not drop for ``side + w - 1`` and the
like. Each such index is non-negative: padded lines are at least 1 and each
bit row has a padding word at both ends, so a scan never leaves its line's
words (the -1 results, "blocked" or "no target on this line", are never
indices and stay signed). The scan loop lost its 18 wraparounds (448 -> 289
lines of assembly). Same expansions, paths and costs; JPS ÷ A* (prepared
planners, 20 MovingAI queries a map, medians of 5 alternating runs) took
0.59-0.86 of its former time: 0.77 / 0.72 (arena2, without / with corner
cutting), 0.86 / 0.73 (maze512-1-0), 0.62 / 0.59 (maze512-32-9), 0.78 / 0.81
(8room_000), 0.67 / 0.60 (Berlin_0_1024); corner-cutting JPS ÷ pyastar2d on
the 1024² maps 0.79 -> 0.69 (random 20 %), 0.91 -> 0.82 (random 35 %), 0.029
-> 0.026 (rooms); first use no slower (cold CPU about 2.0 s either way).
The node records' and queue's indices in :func:`_reach`, :func:`_expand`,
:func:`_next_node` and the corridor walk, unsigned as well, gained nothing
measurable (0.92-1.09 of the time, the noise) and stay signed.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from navkit._shared.jit import (
    NO_REFCOUNT,
    bind_numba_names,
    njit_helper,
    njit_released,
    typed_njit,
)
from navkit._shared.types import KernelInt
from navkit.planning.grid._limits import INF_BITS, read_only, scanned_cost_range
from navkit.planning.grid._search_heap import (
    F_BAND,
    F_BAND_COSTS,
    FLOAT_TIE_LIMIT,
    node_of,
    smallest_child,
    tie_key,
    tie_resolution,
)

SQRT2 = math.sqrt(2.0)
_OCTILE_EXTRA = SQRT2 - 1.0

# numba intrinsics (LLVM cttz / ctlz), bound when numba is loaded (importing this
# module must not import numba), typed for mypy as plain callables.
_ctz: Any = None
_clz: Any = None


def _ctz_python(x: Any) -> int:
    """Trailing zero bits of a uint64 (64 for 0): ``_ctz`` when the JIT is disabled."""
    v = int(x)
    return (v & -v).bit_length() - 1 if v else 64


def _clz_python(x: Any) -> int:
    """Leading zero bits of a uint64 (64 for 0): ``_clz`` when the JIT is disabled."""
    return 64 - int(x).bit_length()


bind_numba_names(globals(), "numba.cpython.unsafe.numbers",
                 python={"_ctz": _ctz_python, "_clz": _clz_python},
                 _ctz="trailing_zeros", _clz="leading_zeros")  # fmt: skip

# The bits of a float64 and back (LLVM bitcasts, see
# navkit.planning.grid._float_bits), for the f band of the queue (see Ties in
# f above), bound when numba loads like the intrinsics above.
_f64_bits: Any = None
_f64_from_bits: Any = None


def _f64_bits_python(x: float) -> np.uint64:
    """``_f64_bits`` when the JIT is disabled: NumPy's view of the scalar."""
    return np.float64(x).view(np.uint64)


def _f64_from_bits_python(x: np.uint64) -> float:
    """``_f64_from_bits`` when the JIT is disabled: NumPy's view of the scalar."""
    return float(np.uint64(x).view(np.float64))


bind_numba_names(globals(), "navkit.planning.grid._float_bits",
                 python={"_f64_bits": _f64_bits_python, "_f64_from_bits": _f64_from_bits_python},
                 _f64_bits="f64_bits", _f64_from_bits="f64_from_bits")  # fmt: skip

_ONE = np.uint64(1)
_ALL = np.uint64(0xFFFFFFFFFFFFFFFF)
_B63 = np.uint64(63)

# Move directions as in _astar_kernels: 0-3 orthogonal (N, S, W, E), 4-7 diagonal
# (NW, NE, SW, SE).
_DR = np.array([-1, 1, 0, 0, -1, -1, 1, 1], dtype=np.int64)
_DC = np.array([0, 0, -1, 1, -1, 1, -1, 1], dtype=np.int64)

# Helpers called only from other kernels are compiled without a Python wrapper
# (njit_helper): a wrapper costs tenths of a second of first-use compilation.
# These are also kept out of LLVM inlining explicitly (numba passes a caller's
# forceinline on to callees that leave it unset).
_helper_not_inlined = typed_njit(**NO_REFCOUNT, no_cpython_wrapper=True, forceinline=False)
# Typed once and inlined by LLVM into each caller (numba's inline="always" would
# type the body again at every call site).
_helper_inlined = typed_njit(**NO_REFCOUNT, no_cpython_wrapper=True, forceinline=True)


@njit_helper
def _transpose64(block: np.ndarray) -> None:
    """Transpose the 64 x 64 bit matrix ``block`` in place (bit j of word i <-> bit i of word j).

    The recursive block swap of Hacker's Delight (2nd ed., section 7-3):
    six rounds of 32 word pairs.
    """
    width = 32
    mask = np.uint64(0x00000000FFFFFFFF)
    while width:
        shift = np.uint64(width)
        k = 0
        while k < 64:
            for i in range(k, k + width):
                a = block[i]
                b = block[i + width]
                t = ((a >> shift) ^ b) & mask
                block[i] = a ^ (t << shift)
                block[i + width] = b ^ t
            k += 2 * width
        width >>= 1
        mask ^= mask << np.uint64(width)


def jps_tables(
    grid: np.ndarray, name: str = "costs"
) -> tuple[np.ndarray, np.ndarray, float, float]:
    """Bit tables of a cost grid for :func:`jps_search`, and the grid's checked cost range.

    Parameters
    ----------
    grid : (rows, cols) float64
        Costs converted by :func:`~navkit.planning.grid._limits.converted_costs`
        (C-contiguous) but not yet checked: the kernel that builds the tables
        also scans the values, in the same pass over the grid.
    name : str
        The grid's name in error messages.

    Returns
    -------
    row_bits : ((rows + 2) * W,) uint64
        Bit rows of ``W = ((cols + 2 + 63) >> 6) + 2`` words: bit ``p`` of
        padded row ``q`` (word ``q * W + (p >> 6) + 1``, bit ``p & 63``) is
        set when padded cell ``(q, p)`` is traversable.
    col_bits : ((cols + 2) * V,) uint64
        The same for the columns (the transposed grid), ``V`` words each.
    lowest, highest : float
        The smallest value and the largest finite value (inf and -inf when no
        cell is traversable); JPS applies when they are equal.

    Raises
    ------
    ValueError
        Values the planners refuse, as
        :func:`~navkit.planning.grid._limits.checked_cost_range`.

    Notes
    -----
    One compiled pass (:func:`_build_tables`) reads the grid once: it finds
    the smallest and largest bit patterns, as
    :func:`~navkit.planning.grid._limits.compiled_cost_range` does, and packs
    the rows' bits on the way. Until review 48 the values were scanned by
    that kernel, the rows marked by ``np.less`` into a grid of bools and
    packed by ``np.packbits``, and the columns transposed by a second kernel:
    three passes over grid-sized arrays where this is one: 0.21-0.25 ->
    0.10-0.15 ms a call on ``maze512-1-0`` (512 x 512; it was a sixth of a
    one-shot ``astar(..., method="jps")`` there). Every array is new, so a
    signal handler building tables in this thread meanwhile has arrays of
    its own.
    """
    rows, cols = grid.shape
    hw = ((cols + 2 + 63) >> 6) + 2
    row_bits = np.zeros((rows + 2) * hw, dtype=np.uint64)
    col_bits = np.zeros((cols + 2) * (((rows + 2 + 63) >> 6) + 2), dtype=np.uint64)
    # One padded bit row's cells as bytes (0 or 1), each word of 8 packed into
    # one byte of the row, then a 64 x 64 bit block: the kernel's scratch (it
    # allocates nothing).
    flags = np.zeros(8 * (hw - 2) + 64, dtype=np.uint64)
    lo_bits, hi_bits = _build_tables(
        read_only(grid.reshape(-1).view(np.int64)),
        rows,
        cols,
        INF_BITS,
        row_bits,
        row_bits.view(np.uint8),
        col_bits,
        flags,
        flags.view(np.uint8),
    )
    lowest, highest = scanned_cost_range(grid, name, lo_bits, hi_bits)
    return row_bits, col_bits, lowest, highest


_B7 = np.uint64(7)
_B14 = np.uint64(14)
_B28 = np.uint64(28)
_LOW_BYTE = np.uint64(0xFF)


@njit_released
def _build_tables(
    bits: np.ndarray,
    rows: int,
    cols: int,
    inf_bits: int,
    row_bits: np.ndarray,
    row_bytes: np.ndarray,
    col_bits: np.ndarray,
    scratch: np.ndarray,
    flags: np.ndarray,
) -> tuple[int, int]:
    """Fill the tables of :func:`jps_tables` (zeros) and scan the values, in one pass.

    ``bits`` is the grid's float64 values read as int64 (flat). Returns, as
    :func:`~navkit.planning.grid._limits._scan_cost_bits`, the smallest
    pattern and the largest one other than ``inf_bits`` (-1 if none): the
    values' check. ``row_bytes`` is the uint8 view of ``row_bits``;
    ``scratch`` (uint64) holds a bit row's cells as bytes in its first ``8 *
    (W - 2)`` words, then a 64-word block for the transposition; ``flags``
    is its uint8 view.

    Each row's cells go through the bytes of ``flags`` (byte ``p``: padded
    column ``p``; bytes 0 and past ``cols`` stay 0): a byte store per cell
    vectorises with the scan. Then each 8 of them (one scratch word) become
    one byte of the row table: bit 0 of byte j moves to bit j of the low
    byte in three shift-ors, each doubling the run of gathered bits (1, 2,
    4, 8; the bytes hold 0 or 1, so no other bit lands there; not a
    multiplication, whose wraparound warns with the JIT disabled). Bit
    ``p`` of a word being bit ``p & 7`` of its byte ``p >> 3`` is
    little-endian byte order, that of every platform numba supports (x86-64,
    aarch64, ppc64le). Or-ing each cell's bit into its word (a shift by the
    cell's position) took 0.11 ms for a 512 x 512 grid, packing whole words
    from the bytes 0.10 ms and compiled 0.02 s slower, this 0.094 ms.
    The loops index slices (a row of the grid, of the flags, of the row
    table) by their range's counters, which LLVM knows are not negative, so
    it drops numba's wraparound tests; with signed indices into the whole
    arrays those kept the loop scalar (0.19 ms). (Unsigned indices, as in
    the scans, vectorise too but compile about 0.03 s slower.)
    """
    hw = ((cols + 2 + 63) >> 6) + 2
    words = hw - 2
    cells = flags[1 : cols + 1]
    lo = bits[0]
    hi = -1
    for r in range(rows):
        row = bits[r * cols : (r + 1) * cols]
        for c in range(cols):
            v = row[c]
            # Selects, not the min/max builtins (see _scan_cost_bits).
            lo = v if v < lo else lo
            w = v if v != inf_bits else -1
            hi = w if w > hi else hi
            cells[c] = v != inf_bits
        out = row_bytes[8 * ((r + 1) * hw + 1) : 8 * ((r + 1) * hw + 1 + words)]
        for i in range(8 * words):
            x = scratch[i]
            x |= x >> _B7
            x |= x >> _B14
            x |= x >> _B28
            out[i] = x & _LOW_BYTE
    _columns(row_bits, rows, cols, col_bits, scratch[8 * (hw - 2) :])
    return lo, hi


@njit_helper
def _columns(
    row_bits: np.ndarray,
    rows: int,
    cols: int,
    col_bits: np.ndarray,
    block: np.ndarray,
) -> None:
    """Fill the column bit table ``col_bits`` (zeros) of :func:`jps_tables` from the row table.

    Transposes 64 x 64 bit blocks in the scratch ``block`` of 64 words.
    """
    hw = ((cols + 2 + 63) >> 6) + 2
    vw = ((rows + 2 + 63) >> 6) + 2
    for qb in range((rows + 2 + 63) >> 6):
        for pb in range((cols + 2 + 63) >> 6):
            every = _ALL
            some = np.uint64(0)
            for i in range(64):
                q = 64 * qb + i
                word = row_bits[q * hw + pb + 1] if q < rows + 2 else np.uint64(0)
                block[i] = word
                every &= word
                some |= word
            if some == 0:
                continue  # all blocked: the column words stay 0
            if every != _ALL:
                _transpose64(block)  # else all free: every column word is all ones
            left = cols + 2 - 64 * pb  # not min(): a builtin overload to compile
            for j in range(64 if left > 64 else left):
                col_bits[(64 * pb + j) * vw + qb + 1] = block[j]


@_helper_not_inlined
def _free(bits: np.ndarray, nw: int, q: KernelInt, p: KernelInt) -> bool:
    """Whether padded cell (q, p) is traversable, from the bit rows ``bits`` of ``nw`` words."""
    return bool((bits[np.uint64(q * nw + (p >> 6) + 1)] >> np.uint64(p & 63)) & _ONE)


@_helper_inlined
def _scan_line(
    bits: np.ndarray,
    nw: int,
    line: KernelInt,
    p: KernelInt,
    target: KernelInt,
    step: KernelInt,
    cut: np.bool_,
) -> KernelInt:
    """Jump from position ``p`` of ``line`` in direction ``step`` (1 or -1).

    Returns the position of the first jump point after ``p``, or ``target``
    when it comes first (``target`` is -1 when the goal is not on this line),
    or -1 when a blocked cell comes first. A jump point is a cell with a
    forced side neighbour: without corner cutting (``cut`` False), a free
    side cell whose cell behind is blocked; with it, a blocked side cell
    whose cell ahead is free (see :mod:`navkit.planning.grid._jps_cut_kernels`).
    Compiled into each caller, where ``step`` and ``cut`` are constants.
    """
    base = line * nw
    x0 = p + step
    w = (x0 >> 6) + 1
    mask = _ALL << np.uint64(x0 & 63) if step > 0 else _ALL >> np.uint64(63 - (x0 & 63))
    while True:
        b = bits[np.uint64(base + w)]
        stops = ~b
        for side in (base - nw, base + nw):
            s = bits[np.uint64(side + w)]
            # Bit i of each: the side cell i - 1 and the side cell i + 1.
            before = (s << _ONE) | (bits[np.uint64(side + w - 1)] >> _B63)
            after = (s >> _ONE) | (bits[np.uint64(side + w + 1)] << _B63)
            if cut:
                stops |= ~s & (after if step > 0 else before)
            else:
                stops |= s & ~(before if step > 0 else after)
        stops &= mask
        if stops != 0:
            break
        mask = _ALL
        w += step
    bit = np.int64(_ctz(stops)) if step > 0 else 63 - np.int64(_clz(stops))
    x = ((w - 1) << 6) + bit
    if (p < target <= x) if step > 0 else (x <= target < p):
        return target
    return x if (b >> np.uint64(bit)) & _ONE else -1


@_helper_not_inlined
def _scan_forward(
    bits: np.ndarray, nw: int, line: KernelInt, p: KernelInt, target: KernelInt
) -> KernelInt:
    """:func:`_scan_line` towards larger positions, without corner cutting."""
    return _scan_line(bits, nw, line, p, target, np.int64(1), np.bool_(False))


@_helper_not_inlined
def _scan_backward(
    bits: np.ndarray, nw: int, line: KernelInt, p: KernelInt, target: KernelInt
) -> KernelInt:
    """:func:`_scan_line` towards smaller positions, without corner cutting."""
    return _scan_line(bits, nw, line, p, target, np.int64(-1), np.bool_(False))


@njit_helper
def _jump_diagonal(
    row_bits: np.ndarray,
    hw: int,
    col_bits: np.ndarray,
    vw: int,
    q: KernelInt,
    p: KernelInt,
    dr: int,
    dc: int,
    gq: int,
    gp: int,
) -> KernelInt:
    """Number of diagonal steps (dr, dc) from padded (q, p) to the next jump point, or -1."""
    k = 0
    while True:
        nq = q + dr
        np_ = p + dc
        if not (
            _free(row_bits, hw, nq, np_)
            and _free(row_bits, hw, nq, p)
            and _free(row_bits, hw, q, np_)
        ):
            return -1
        q = nq
        p = np_
        k += 1
        if q == gq and p == gp:
            return k
        # Either straight component reaching a jump point makes this one.
        on_row = gp if q == gq else -1
        if dc > 0:
            if _scan_forward(row_bits, hw, q, p, on_row) >= 0:
                return k
        elif _scan_backward(row_bits, hw, q, p, on_row) >= 0:
            return k
        on_col = gq if p == gp else -1
        if dr > 0:
            if _scan_forward(col_bits, vw, p, q, on_col) >= 0:
                return k
        elif _scan_backward(col_bits, vw, p, q, on_col) >= 0:
            return k


@_helper_inlined
def _successor_directions(
    row_bits: np.ndarray, hw: int, q: KernelInt, p: KernelInt, d: KernelInt
) -> KernelInt:
    """Bit set of the directions (0-7) to scan from padded (q, p) reached by move ``d``.

    ``d`` is -1 at the start (every direction). Inlined (review 48): it runs
    at every expansion and every corridor corner, and the call cost about
    7 % of a search on ``maze512-1-0``; first use compiles no slower within
    the noise (it is typed once either way).
    """
    if d < 0:
        return 0xFF
    if d >= 4:
        # Diagonal arrival: its two straight components and itself.
        vertical = 0 if d < 6 else 1
        horizontal = 2 if d == 4 or d == 6 else 3
        return (1 << vertical) | (1 << horizontal) | (1 << d)
    out = 1 << d
    if d >= 2:
        # Horizontal arrival: a side is forced when the side cell is free and
        # the side cell behind it is blocked.
        back = p + 1 if d == 2 else p - 1
        if _free(row_bits, hw, q - 1, p) and not _free(row_bits, hw, q - 1, back):
            out |= (1 << 0) | (1 << (4 if d == 2 else 5))
        if _free(row_bits, hw, q + 1, p) and not _free(row_bits, hw, q + 1, back):
            out |= (1 << 1) | (1 << (6 if d == 2 else 7))
    else:
        back = q + 1 if d == 0 else q - 1
        if _free(row_bits, hw, q, p - 1) and not _free(row_bits, hw, back, p - 1):
            out |= (1 << 2) | (1 << (4 if d == 0 else 6))
        if _free(row_bits, hw, q, p + 1) and not _free(row_bits, hw, back, p + 1):
            out |= (1 << 3) | (1 << (5 if d == 0 else 7))
    return out


@njit_helper
def _heap_push(heap: np.ndarray, n: KernelInt, f: float, key: float) -> None:
    """Add (f, key) to the 4-ary min-heap of ``n`` entries in ``heap`` (room for one more).

    Its indices, like :func:`_heap_replace_top`'s, are unsigned: numba adds no
    negative-index wraparound code (see Indices in
    :mod:`navkit.planning.grid._astar_kernels`; review 23).
    """
    i = n
    while i > 0:
        up = (i - 1) >> 2
        uf = heap[np.uint64(2 * up)]
        uk = heap[np.uint64(2 * up + 1)]
        if f < uf or (f == uf and key < uk):
            heap[np.uint64(2 * i)] = uf
            heap[np.uint64(2 * i + 1)] = uk
            i = up
        else:
            break
    heap[np.uint64(2 * i)] = f
    heap[np.uint64(2 * i + 1)] = key


@njit_helper
def _heap_replace_top(heap: np.ndarray, last: KernelInt, f: float, key: float) -> KernelInt:
    """Replace the smallest of the entries ``0 .. last`` by (f, key); return its node.

    One walk down from the root, stopping where (f, key) fits. A pop is this
    with (f, key) the last entry and ``last`` one less.
    """
    top = node_of(heap[1])
    i: KernelInt = 0
    while True:
        best, bf, bk = smallest_child(heap, 0, i, last + 1)
        # The lexicographic test, written out (see _search_heap._bits_precede).
        if best < 0 or not ((bf < f) | ((bf == f) & (bk < key))):
            break
        heap[np.uint64(2 * i)] = bf
        heap[np.uint64(2 * i + 1)] = bk
        i = best
    heap[np.uint64(2 * i)] = f
    heap[np.uint64(2 * i + 1)] = key
    return top


@_helper_inlined
def _straight(
    row_bits: np.ndarray,
    hw: int,
    col_bits: np.ndarray,
    vw: int,
    q: KernelInt,
    p: KernelInt,
    k: int,
    gq: int,
    gp: int,
) -> KernelInt:
    """Padded position along its line of the next jump point from (q, p) in straight direction k.

    -1 when a blocked cell comes first. ``(gq, gp)`` is the padded goal.
    """
    # np.int64(-1), not -1: numba typed that branch as Literal[int](-1) on Python
    # 3.12 and 3.13 (numpy 2.5), a second compilation of each scan.
    if k == 3:
        return _scan_forward(row_bits, hw, q, p, gp if q == gq else np.int64(-1))
    if k == 2:
        return _scan_backward(row_bits, hw, q, p, gp if q == gq else np.int64(-1))
    if k == 1:
        return _scan_forward(col_bits, vw, p, q, gq if p == gp else np.int64(-1))
    return _scan_backward(col_bits, vw, p, q, gq if p == gp else np.int64(-1))


@_helper_inlined
def _reach(
    blocks: np.ndarray,
    g: np.ndarray,
    meta: np.ndarray,
    stamp: int,
    v: KernelInt,
    new_g: float,
    parent: KernelInt,
    k: int,
) -> bool:
    """Record that node ``v`` is reached at cost ``new_g`` from ``parent`` by a move in direction k.

    Returns False (nothing written) when ``v`` is closed or already open at
    no higher cost; otherwise marks it open and writes its record.
    """
    b = 3 * (v >> 6)
    bit = np.int64(1) << np.int64(v & 63)
    if blocks[b] != stamp:
        blocks[b] = stamp
        blocks[b + 1] = bit
        blocks[b + 2] = 0
    elif blocks[b + 2] & bit:
        return False  # closed
    elif blocks[b + 1] & bit:
        if new_g >= g[2 * v]:
            return False  # open at no higher cost
    else:
        blocks[b + 1] |= bit
    g[2 * v] = new_g
    meta[4 * v + 2] = parent
    meta[4 * v + 3] = k
    return True


@njit_helper
def _follow_corridor(
    row_bits: np.ndarray,
    hw: int,
    col_bits: np.ndarray,
    vw: int,
    cols: int,
    goal: int,
    gq: int,
    gp: int,
    blocks: np.ndarray,
    g: np.ndarray,
    meta: np.ndarray,
    stamp: int,
    v: KernelInt,
    q: KernelInt,
    p: KernelInt,
    k: int,
) -> tuple[KernelInt, KernelInt, KernelInt]:
    """Pass through jump points that have one way on; return the node to queue, or -1.

    ``v`` was just reached by the straight move ``k`` (its record written).
    While the cell ahead of it is blocked and exactly one side is forced, the
    only successor of ``v`` is the straight scan along that side (its
    diagonal turns pass beside the blocked cell ahead): that scan runs at
    once and its jump point is recorded with ``v`` as parent, instead of
    queueing ``v`` to be expanded later, the corners of one-cell corridors
    cost no queue operations. ``v`` stays open, not closed: reached again at
    a lower cost it is queued and expanded as usual, which re-derives its
    successor, so the search stays exact (it is A* on a graph whose edges
    are these chains). Returns -1 when the chain ends in a dead end or at a
    node already reached at no higher cost.

    ``(q, p)`` is ``v``'s padded cell and ``(gq, gp)`` the goal's; the node
    returned comes with its padded cell. Tracked along the chain rather
    than found from the node (a division by ``cols`` per corner, about 15
    cycles of latency on the way to the next bit test: review 48).
    """
    while v != goal:
        if _free(row_bits, hw, q + _DR[k], p + _DC[k]):
            break
        turns = _successor_directions(row_bits, hw, q, p, k) & 15 & ~(1 << k)
        if turns == 0 or turns & (turns - 1):
            break
        k = 0 if turns == 1 else 1 if turns == 2 else 2 if turns == 4 else 3
        x = _straight(row_bits, hw, col_bits, vw, q, p, k, gq, gp)
        if x < 0:
            return np.int64(-1), q, p
        if k >= 2:
            w = v + (x - p)
            steps = abs(x - p)
            p = x
        else:
            w = v + (x - q) * cols
            steps = abs(x - q)
            q = x
        if not _reach(blocks, g, meta, stamp, w, g[2 * v] + steps, v, k):
            return np.int64(-1), q, p
        v = w
    return v, q, p


@njit_released
def jps_search(
    row_bits: np.ndarray,
    col_bits: np.ndarray,
    rows: int,
    cols: int,
    start: int,
    goal: int,
    g: np.ndarray,
    meta: np.ndarray,
    blocks: np.ndarray,
    heap: np.ndarray,
    stamp: int,
) -> tuple[int, int, int, int]:
    """A* over jump points from ``start`` to ``goal``, in cell lengths.

    Parameters
    ----------
    row_bits, col_bits
        Tables from :func:`jps_tables` of a grid whose traversable cells all
        cost the same. ``start`` and ``goal`` must be traversable.
    rows, cols : int
        Grid shape.
    start, goal : int
        Flat indices ``r * cols + c``.
    g : (2 * rows * cols,) float64
        Node records, 16 bytes each so one cache line holds a node's state:
        ``g[2 * v]`` is the cost from ``start``; ``meta``, an int32 view of
        the same memory, holds the parent node at ``4 * v + 2`` and the
        direction of the move from it (0-7, -1 at ``start``) at ``4 * v + 3``.
        Only read where ``blocks`` says this search wrote them.
    meta : (4 * rows * cols,) int32
        The int32 view of ``g``.
    blocks : (3 * ceil(rows * cols / 64),) int64
        Which nodes this search reached, kept apart from the records so the
        test reads a small, cache-resident array: for the 64 nodes
        ``64 b .. 64 b + 63``, ``blocks[3 b]`` is the stamp of the search that
        last wrote the block and ``blocks[3 b + 1]`` / ``blocks[3 b + 2]`` the
        bits of its open / closed nodes (stale unless the stamp is this one).
    heap : (2 * capacity,) float64
        Scratch for the queue: (f, tie key) pairs, lazy deletion (a node is
        queued again when its cost improves; stale entries are skipped).
        Receives the path when the goal is reached (see ``cells``).
    stamp : int
        This search's stamp, larger than every stamp in ``blocks``.

    Returns
    -------
    expanded : int
        Number of jump points expanded (closed).
    found : int
        1 when ``goal`` was reached: then ``g[2 * goal]`` is its path length
        in cells and the parents link it back to ``start`` (-1) through jump
        points joined by straight or diagonal lines, and ``heap[: 2 *
        cells]`` holds every cell ``(row, col)`` of the path (see
        :func:`_trace`). 0 when it is unreachable; -1 when ``heap`` filled
        up, -2 when the path did not fit in it (``cells`` cells): search
        again with a larger one and a fresh stamp.
    cells : int
        Number of cells on the path (0 unless found).
    diagonal : int
        How many of its steps are diagonal: its length in cells is
        ``cells - 1 - diagonal + sqrt(2) * diagonal``.
    """
    hw, vw, gr, gc = _begin(rows, cols, start, goal, g, meta)
    # Ties to 1/16 cell unless rows + cols >= 2**17 (see _search_heap).
    tie_res = tie_resolution(rows, cols, FLOAT_TIE_LIMIT)
    gq = gr + 1
    gp = gc + 1
    n: KernelInt = np.int64(0)  # np.int64: a literal 0 would compile _heap_push twice
    expanded = 0
    u: KernelInt = start
    next_v: KernelInt
    while u != goal:
        r, c, gu, d = _expand(blocks, stamp, u, cols, g, meta)
        expanded += 1
        q = r + 1
        p = c + 1
        dirs = _successor_directions(row_bits, hw, q, p, d)
        # The best successor is kept out of the heap and expanded next when it
        # precedes the heap's top (often, in corridors): a push and a pop saved.
        # (np.int64: a literal -1 would compile _offer twice.)
        next_f, next_key, next_v = np.inf, np.inf, np.int64(-1)
        for k in range(8):
            if not (dirs >> k) & 1:
                continue
            dr = _DR[k]
            dc = _DC[k]
            if k < 4:
                # Straight scans: along the bit row (W, E) or column (N, S).
                x = _straight(row_bits, hw, col_bits, vw, q, p, k, gq, gp)
                if x < 0:
                    continue
                vr, vc, steps = _line_end(r, c, q, p, k, x)
                new_g = gu + steps
            else:
                # The first diagonal step is tested here: in narrow corridors it
                # is usually blocked, and the call would cost more than the test.
                if not (
                    _free(row_bits, hw, q + dr, p + dc)
                    and _free(row_bits, hw, q + dr, p)
                    and _free(row_bits, hw, q, p + dc)
                ):
                    continue
                steps = _jump_diagonal(row_bits, hw, col_bits, vw, q, p, dr, dc, gq, gp)
                if steps < 0:
                    continue
                vr = r + steps * dr
                vc = c + steps * dc
                new_g = gu + SQRT2 * steps
            v = vr * cols + vc
            if not _reach(blocks, g, meta, stamp, v, new_g, u, k):
                continue
            if k < 4 and v != goal and not _free(row_bits, hw, vr + 1 + dr, vc + 1 + dc):
                # Blocked ahead: maybe a corridor corner with one way on.
                w, wq, wp = _follow_corridor(
                    row_bits, hw, col_bits, vw, cols, goal, gq, gp,
                    blocks, g, meta, stamp, v, vr + 1, vc + 1, k,
                )  # fmt: skip
                if w < 0:
                    continue
                if w != v:
                    v = w
                    vr = wq - 1
                    vc = wp - 1
                    new_g = g[2 * v]
            n, next_f, next_key, next_v = _offer(
                heap, n, next_f, next_key, next_v, v, vr, vc, new_g, gr, gc, tie_res
            )
            if n < 0:
                return expanded, -1, 0, 0
        u, n = _next_node(heap, n, next_f, next_key, next_v, blocks)
        if u < 0:
            return expanded, 0, 0, 0
    return _finish(expanded + 1, meta, cols, goal, heap)


@_helper_inlined
def _begin(
    rows: int, cols: int, start: int, goal: int, g: np.ndarray, meta: np.ndarray
) -> tuple[int, int, int, int]:
    """Start a search: record ``start``; (row words, column words, goal row, goal column).

    The word counts are those of the bit rows and bit columns of
    :func:`jps_tables`.
    """
    g[2 * start] = 0.0
    meta[4 * start + 2] = -1
    meta[4 * start + 3] = -1
    gr = goal // cols
    return ((cols + 2 + 63) >> 6) + 2, ((rows + 2 + 63) >> 6) + 2, gr, goal - gr * cols


@_helper_inlined
def _expand(
    blocks: np.ndarray, stamp: int, u: KernelInt, cols: int, g: np.ndarray, meta: np.ndarray
) -> tuple[KernelInt, KernelInt, float, KernelInt]:
    """Close node ``u``: (its row, column, cost from the start, direction it was reached by).

    Sets its bit in its block's closed word, resetting a block last written
    by another search.
    """
    b = 3 * (u >> 6)
    if blocks[b] != stamp:
        blocks[b] = stamp
        blocks[b + 1] = 0
        blocks[b + 2] = 0
    blocks[b + 2] |= np.int64(1) << np.int64(u & 63)
    r = u // cols
    return r, u - r * cols, g[2 * u], np.int64(meta[4 * u + 3])


@_helper_inlined
def _line_end(
    r: KernelInt, c: KernelInt, q: KernelInt, p: KernelInt, k: int, x: KernelInt
) -> tuple[KernelInt, KernelInt, KernelInt]:
    """Cell (row, col) at padded position ``x`` of the straight line k through (r, c); steps."""
    # mypy infers abs() of an ``int | np.int64`` as ``object``.
    if k >= 2:
        return r, x - 1, abs(x - p)  # type: ignore[return-value]
    return x - 1, c, abs(x - q)  # type: ignore[return-value]


@_helper_inlined
def _offer(
    heap: np.ndarray,
    n: KernelInt,
    next_f: float,
    next_key: float,
    next_v: KernelInt,
    v: KernelInt,
    vr: KernelInt,
    vc: KernelInt,
    new_g: float,
    gr: int,
    gc: int,
    tie_res: float,
) -> tuple[KernelInt, float, float, KernelInt]:
    """Queue node ``v`` = (vr, vc), reached at cost ``new_g``, for expansion.

    ``(next_f, next_key, next_v)`` is the best successor of the node being
    expanded so far, held out of the heap of ``n`` entries (``next_v`` -1:
    none yet); of it and ``v`` the better one is held, the other pushed.
    f is queued with its lowest ``F_TIE_BITS`` bits cleared below
    ``F_BAND_COSTS`` (see Ties in f in the module notes). Ties in f go to
    the smaller h, to ``1 / tie_res`` cells (from
    :func:`~navkit.planning.grid._search_heap.tie_resolution`), then node id.
    Returns the new heap size (-1 when the heap is full) and held successor.
    """
    # mypy infers abs() of an ``int | np.int64`` as ``object``.
    adr: KernelInt = abs(vr - gr)  # type: ignore[assignment]
    adc: KernelInt = abs(vc - gc)  # type: ignore[assignment]
    # Selects, not the min/max builtins (compiled as overloads of their own).
    h = (adr if adr > adc else adc) + _OCTILE_EXTRA * (adc if adr > adc else adr)
    # f less its lowest F_TIE_BITS bits below F_BAND_COSTS (cells), as A*
    # queues it: f within 2**-40 of itself (one value rounded differently)
    # ties, and the tie key decides.
    f = new_g + h
    if f < F_BAND_COSTS:
        f = _f64_from_bits(_f64_bits(f) & F_BAND)
    key = tie_key(h, v, tie_res)
    if f < next_f or (f == next_f and key < next_key):
        f, next_f = next_f, f
        key, next_key = next_key, key
        v, next_v = next_v, v
        if v < 0:
            return n, next_f, next_key, next_v
    if 2 * n == heap.size:
        return -1, next_f, next_key, next_v
    _heap_push(heap, n, f, key)
    return n + 1, next_f, next_key, next_v


@_helper_inlined
def _next_node(
    heap: np.ndarray,
    n: KernelInt,
    next_f: float,
    next_key: float,
    next_v: KernelInt,
    blocks: np.ndarray,
) -> tuple[KernelInt, KernelInt]:
    """The next node to expand and the new heap size; node -1 when the queue is empty.

    The held successor ``next_v`` (see :func:`_offer`) when it precedes the
    heap's top; otherwise the heap's first entry of a node still open (entries
    of nodes closed since they were queued are dropped).
    """
    if next_v >= 0:
        if n == 0 or next_f < heap[0] or (next_f == heap[0] and next_key < heap[1]):
            return next_v, n
        # Queue it and take the top in one walk down from the root.
        u = _heap_replace_top(heap, n - 1, next_f, next_key)
        if not blocks[3 * (u >> 6) + 2] & (np.int64(1) << np.int64(u & 63)):
            return u, n
    while n > 0:
        n -= 1
        # The last entry takes the top's place (or the top is the only one).
        u = _heap_replace_top(heap, n - 1, heap[2 * n], heap[2 * n + 1]) if n else node_of(heap[1])
        if not blocks[3 * (u >> 6) + 2] & (np.int64(1) << np.int64(u & 63)):
            return u, n
    return -1, n


@_helper_inlined
def _finish(
    expanded: int, meta: np.ndarray, cols: int, goal: int, heap: np.ndarray
) -> tuple[int, int, int, int]:
    """The search kernels' result once ``goal`` is reached: as :func:`jps_search` returns it."""
    cells, diagonal = _trace(meta, cols, goal, heap)
    return expanded, 1 if cells <= heap.size >> 1 else -2, cells, diagonal


@njit_helper
def _trace(meta: np.ndarray, cols: int, goal: int, out: np.ndarray) -> tuple[int, int]:
    """Write every cell of the path to ``goal`` into ``out``; (cell count, diagonal steps).

    Follows the parent jump points written by :func:`jps_search` (in ``meta``)
    and fills in the cells of the straight or diagonal line between each pair,
    so consecutive cells are 8-neighbours: ``out[2 * i]``, ``out[2 * i + 1]``
    is the row and column of the i-th cell from the search source. Writes
    nothing when ``out`` is too small (the count says how large it must be).
    Done in the search kernel rather than a kernel of its own: a kernel that
    allocates the path costs a quarter of a second of first-use compilation.
    """
    k = 1
    v = goal
    while meta[4 * v + 2] >= 0:
        u = meta[4 * v + 2]
        ur = u // cols
        vr = v // cols
        dr = abs(vr - ur)
        dc = abs((v - vr * cols) - (u - ur * cols))
        k += dr if dr > dc else dc
        v = u
    if 2 * k > out.size:
        return k, 0
    n_diag = 0
    i = k - 1
    v = goal
    r: KernelInt = v // cols
    c: KernelInt = v - r * cols
    out[2 * i] = r
    out[2 * i + 1] = c
    while meta[4 * v + 2] >= 0:
        u = meta[4 * v + 2]
        ur = u // cols
        uc = u - ur * cols
        sr = np.int64(ur > r) - np.int64(ur < r)
        sc = np.int64(uc > c) - np.int64(uc < c)
        diagonal = sr != 0 and sc != 0
        while r != ur or c != uc:
            r += sr
            c += sc
            i -= 1
            out[2 * i] = r
            out[2 * i + 1] = c
            if diagonal:
                n_diag += 1
        v = u
    return k, n_diag
