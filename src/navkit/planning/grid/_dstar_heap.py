"""Indexed 4-ary min-heap with arbitrary key changes, for D* Lite (private).

Field D* (D* Lite keys) raises, lowers and removes queued keys, so it needs this
general heap; the monotone searches (A*, Dijkstra) use the leaner heap of
:mod:`navkit.planning.grid._search_heap`. Slot i's children are 4i+1..4i+4
(a shallower tree than a binary heap: fewer cache misses per pop), and the
sifts move a hole instead of swapping. It lives in preallocated arrays so
kernels never allocate Python objects in their loops:

``nodes`` (capacity,) int64
    Node id stored at each heap slot.
``keys`` (capacity, 2) float64
    Priority of each slot, compared lexicographically (k1, then k2); D* Lite
    uses its two-part key (min(g, rhs) + h, min(g, rhs)). Offset in its
    allocation so that the four children of every slot share one 64-byte
    cache line (as the A* heap's entries).
``pos`` (n_nodes,) int64, strided
    Heap slot of every node, or -1 when the node is not queued. This index makes
    decrease-key, increase-key and removal O(log n), as D* Lite needs. It is
    column :data:`POS` of the node records made by :func:`node_records` (read
    as int64), next to the node's D* Lite values ``g`` and ``rhs``.
``size`` (1,) int64
    Number of queued nodes (an array so kernels can update it in place).

Capacity equal to the number of nodes is always enough because a node is queued
at most once.

Node records. A search reads ``rhs`` and ``g`` of a neighbour and then its heap
slot, and every sift writes the slot of each node it moves: with the three in
separate arrays that was three cache misses where one now suffices (the
frontier of a 1024² search spans more than the L2 cache). On the 1024²
benchmark maps the search of a fresh Field D* plan took about 5 % less time
than with only ``g`` and ``rhs`` packed, and 16 % less than with three arrays
and the former sift-down (together with the pop below and the aligned keys;
the whole fresh plan 9-13 % less). The price is paid by repairs: after a
block mid-path on the random 20 % map a repair took 8-12 % longer than with
``g``/``rhs`` pairs and a separate slot array (rooms: about 1 %), and neither
Floyd's pop nor the aligned keys account for it (each reverted alone: no
change). A repair works where the fresh search passed long before, out of
the L2 cache, where bytes per node count (likely cause; no perf counters):
32-byte records (a padding column) made fresh plans 4-6 % slower and this
repair 1-2 % (one run, near the noise). For the same
reason the cell costs stay in ``pad``: as a fourth record column (the cost of
the cell whose top-left corner the node is) fresh plans took 0.5-7 % longer
(review 15, interleaved timings in one process).

Popping the top (dequeuing any node) uses Floyd's method: the hole goes down
along the least children to a leaf, the least of four children found by a
two-round tournament without branches, then the last element goes up from
there. A sift-down that compares each level's least child with the moving
key as well mispredicted a branch at nearly every level; the moving
element, the heap's last, nearly always belongs at the bottom. A raised key
(repairs only) keeps the compare and stops where it fits: placed from a leaf,
repairs after a change mid-path took about 10 % longer.

Kernel view (review 18): the search kernels get ``keys`` flat (slot i's key at
``2 i`` and ``2 i + 1``) and the slots as :func:`flat_positions` (node s's
slot at ``RECORD * s``), both C-contiguous views of the same memory, so a slot's
address is a shift or a ``lea`` instead of a multiplication by a run-time
stride, and slot and node indices are masked with :data:`NN`, which drops
numba's wraparound of negative indices (three instructions before each load)
from the address arithmetic. In the pop's descent these sat on the chain of
dependent loads (keys, then the winner's index, then its key): with the
index arithmetic gone a fresh 1024² plan took about 10 % less time,
bit-identical (the same comparisons, so the same heap and expansion order).
The tournament indices must stay unmasked: masked, LLVM turned the selects
into branches (about 50 % mispredicted) and fresh plans took 15-20 % longer.

Prefetch (review 20). A dequeue (a search's pop of the top) prefetches, at
each level of its descent, the keys of the next level's four candidate
families (the hole's 16 grandchildren: four 64-byte lines, one per family)
before the tournament picks the child to follow, so the next level's loads
need not wait for the L2 cache: the heap of a 1024² search holds about 2000
keys (30-60 KiB, beyond the 48 KiB L1 cache with the records and cells the
search reads meanwhile), and the pop's descent was about 40 % of a fresh
plan's time (sampled with ``perf record -e cpu-clock``). Bit-identical (a hint
changes nothing). With the one-pass records of :func:`clear_records`, fresh
1024² plans ÷ A* went 3.23 -> 3.13 (random 20 %), 2.94 -> 2.87 (rooms),
2.40 -> 2.39 (random 35 %), medians of 3 alternating benchmark runs on a
loaded machine (about 2 % of it noise). Fresh searches only (``ahead``, the search's ``fresh``
flag; :func:`heap_update` passes False): always on, repairs took up to 7 %
longer (mid-path blocks on the random 20 % map), as with the records'
prefetch of review 19.
Tried and dropped: also prefetching the records of the four children (whose
slot a move writes), slower (loads of ``nodes`` on every level); a tournament
with all six cross comparisons (no reload of the winners' keys), far slower
(LLVM made branches of it).

Tournament (review 23). The descent's tournament first compares the four
children's first components alone, as two minimums and a comparison of
them, the winner being ``first`` plus an offset of 0-3 made of the three
outcomes; only a partial family (the last one) or an equality among the
three compared pairs takes the comparison of whole keys, with a missing
child standing in as a copy of the last one. Where the first components
differ the whole keys compare as they do, so the heap is the same, slot for
slot (``tests/planning/grid/test_review23_fd_heap_tournament.py`` checks it
against a model of whole-key comparisons, on keys that tie often). With
whole keys at every comparison, the x86 back end of LLVM turned the selects
that depend on the second components into branches (its conversion of
``cmov`` on a loop's critical path), three a level, each taken or not as
the keys fell: the samples piled up after them, and the descent was about
55 % of a fresh 1024² plan (``perf record -e cpu-clock``, no hardware
counters on the machine measured). Now the code has ``vminsd``, ``seta``
and ``cmov`` and one branch a level, nearly never taken: the whole keys were
compared at 0.16 % (random 20 %), 0.58 % (random 35 %) and 0.12 % (rooms) of
the 4.1-5.0 million levels a fresh 1024² plan descends. Fresh 1024² plans ÷
A* went 4.71 -> 2.44 (random 20 %), 3.31 -> 1.80 (random 35 %) and 4.40 ->
2.21 (rooms), medians of 5 alternating benchmark runs, bit-identical (the
same expansions, paths and costs). A first version that compared first
components alone but kept the clamped children's index arithmetic
(``first + second * (c1 - first)``) and reloaded the winners' keys gained
half as much (a fresh random 20 % plan 21 % faster, not 45 %): LLVM still
made branches of those selects.

Integer tournament (review 48). A full family's first components are
compared as their bit patterns, unsigned integers (``f64_bits`` of
:mod:`navkit.planning.grid._float_bits`, an LLVM bitcast), which order as
the float64 values do from +0.0 to +inf: integer compares and
``cmov`` (one cycle each) instead of ``vucomisd``/``vminsd`` (three and
four) on the descent's chain of dependent loads. D* Lite's keys are sums
of non-negative terms, never NaN; a family with a sign bit set (a negative
key, or -0.0, equal to +0.0 as a float but not as bits; only the tests'
heaps hold them) takes the float comparison of whole keys as a tie does, so
the heap is the same, slot for slot, for every key but NaN
(``tests/planning/grid/test_review48_fdstar_bits_tournament.py``). Fresh
1024² plans ÷ A*: 2.89 -> 2.78 (random 20 %), 2.21 -> 2.11 (random 35 %),
2.69 -> 2.61 (rooms), medians of 6 alternating runs of 9 rounds, the same
expansions, paths and costs. NumPy's ``view`` of the keys as int64 in the
kernel ran as fast but compiled about 0.15-0.3 s longer at first use.

Compilation: every change of the heap goes through one function,
:func:`change` (D* Lite's ``UpdateVertex`` on the queue: queue, requeue
or dequeue a node; popping the top is dequeuing it), compiled once; the
search's pop of the top inlines it (LLVM) into
:func:`navkit.planning.grid._dstar_lite_kernels.settle`, everything else
calls it through :func:`heap_update`, never inlined (passing the four arrays
field by field: about 2-6 % of a fresh plan's time at the pop's site).
It replaced separately compiled sifts, slot writes and comparisons, inlined
(by numba or LLVM) into three operations that were themselves inlined into
every caller, so that the sift code was optimised five times over: Field D*'s
first use took about 0.3 s longer. The other exception is the hot path of a
search, the sift-up of a new or lowered key, which :func:`heap_lower` inlines
into its caller (through the call, searches were about 7 % slower); both use
the one sift-up loop :func:`_sift_up`, inlined by LLVM. Whether
a node is queued or dequeued is an argument computed at run time: a literal
``True``/``False`` argument compiles the function once per value. Key
comparisons are written out (``a0 < b0 or (a0 == b0 and a1 < b1)``) and so
is ``min()``: a function for either is compiled on its own.
:func:`heap_push`, :func:`heap_pop` and :func:`heap_remove` are for Python
callers (the tests; they pass the kernel view to one small kernel); the search
kernels call :func:`heap_update` themselves. :func:`heap_new`,
:func:`node_records` and :func:`flat_positions` are plain NumPy.
"""

from __future__ import annotations

import mmap
import sys
from typing import Any

import numpy as np

from navkit._shared.jit import NO_REFCOUNT, bind_numba_names, typed_njit

# Compile options of this module's kernels, written again in each of the other Field
# D* kernel modules (the D* Lite, path and polyline kernels): numba's cache keys a
# kernel's code on its own file, so each module's options must change in that file
# (tests/planning/grid/test_review23_fd_kernel_options.py). Kernels called from
# Python need no cfunc wrapper (navkit never passes a kernel as a first-class
# function value); helpers called only from kernels need no Python wrapper either:
# each wrapper is compiled (and its LLVM optimised) with the kernel on first use.
# The numpy error model drops the zero-divisor checks (every division is guarded,
# so no result changes) and their exception code.
KERNEL_OPTIONS: dict[str, Any] = {**NO_REFCOUNT, "error_model": "numpy"}
HELPER_OPTIONS: dict[str, Any] = {**KERNEL_OPTIONS, "no_cpython_wrapper": True}
_kernel = typed_njit(**KERNEL_OPTIONS)
# heap_update stays a call also from LLVM-inlined callers (numba passes
# ``forceinline`` on to callees that leave it unset).
_helper = typed_njit(**HELPER_OPTIONS, forceinline=False)
# The search's hot path: compiled once and inlined by LLVM (numba's ``forceinline``).
_inlined = typed_njit(**HELPER_OPTIONS, forceinline=True)


# A software prefetch (``llvm.prefetch``, see :mod:`navkit.planning.grid._prefetch`),
# bound when numba loads (importing this module must not import numba).
_prefetch: Any = None


def _no_prefetch(arr: Any, idx: Any) -> None:
    """``_prefetch`` when the JIT is disabled: nothing to do."""


bind_numba_names(globals(), "navkit.planning.grid._prefetch",
                 python={"_prefetch": _no_prefetch}, _prefetch="prefetch")  # fmt: skip

# The bits of a float64 as a uint64 (an LLVM bitcast, see
# navkit.planning.grid._float_bits), bound when numba loads as ``_prefetch`` is.
_f64_bits: Any = None


def _f64_bits_python(x: float) -> np.uint64:
    """``_f64_bits`` when the JIT is disabled: NumPy's view of the scalar."""
    return np.float64(x).view(np.uint64)


bind_numba_names(globals(), "navkit.planning.grid._float_bits",
                 python={"_f64_bits": _f64_bits_python}, _f64_bits="f64_bits")  # fmt: skip

# The sign bit of a float64's bits: keys with it set take the float comparison.
_SIGN = np.uint64(1 << 63)


# Columns of a node record (float64): D* Lite's g and rhs, then the node's heap
# slot, stored as int64 (read through an int64 view of the records).
G = 0
RHS = 1
POS = 2
RECORD = 3
# Mask of the non-negative int64 values: ``x & NN`` is ``x`` for a slot or node id
# (never negative), and tells LLVM so: numba's wraparound of a negative index
# (three instructions before each load, on the heap's critical path) then drops
# out, and the mask itself folds into the address scaling (bits 62-63 shift out).
NN = (1 << 62) - 1
# Keys entry of slot 0 within its 64-byte line: slot 1, the first child of the
# root, then starts a line (16-byte keys), and so do the children of every slot.
_KEYS_OFFSET = 48


def positions(records: np.ndarray) -> np.ndarray:
    """The heap slots (column :data:`POS`, int64, a strided view) of ``records``."""
    pos: np.ndarray = records.view(np.int64)[:, POS]
    return pos


def flat_positions(pos: np.ndarray) -> np.ndarray:
    """The heap slots as the kernels take them: node s's slot at ``RECORD * s``.

    ``pos`` is the slot column of node records (:func:`positions`); the result is
    the contiguous int64 view of the records from that column of the first node
    to the last (no copy): indexing it costs no multiplication by a stride.
    """
    n = pos.shape[0]
    flat: np.ndarray = np.lib.stride_tricks.as_strided(
        pos, shape=(RECORD * (n - 1) + 1 if n else 0,), strides=(8,)
    )
    return flat


def _blank_block(count: int) -> np.ndarray:
    """``count`` blank records (g = rhs = inf, slot -1), flat and read-only."""
    blank = np.full(RECORD, np.inf)
    blank[POS : POS + 1].view(np.int64)[0] = -1
    block = np.tile(blank, count)
    block.flags.writeable = False
    return block


# What :func:`clear_records` copies along the records: 4096 blank records (96 KiB,
# which stays in the L2 cache while it is copied).
_BLANK_BLOCK = _blank_block(4096)


def clear_records(records: np.ndarray) -> None:
    """Set every record of ``records`` (C-contiguous) to g = rhs = inf, unqueued (slot -1).

    One pass over the memory: a block of blank records copied along it. A fill
    of g and rhs with inf followed by a strided fill of the slot column with -1
    wrote every line twice and took more than twice as long on the records of
    a 1025² grid of nodes (25 MB: about 7.3 -> 3.3 ms, about 1.5 % of a fresh
    1024² plan; review 20).
    """
    block = _BLANK_BLOCK
    flat = records.reshape(-1, copy=False)  # raises rather than fill a copy
    size = block.shape[0]
    whole = flat.shape[0] // size * size
    flat[:whole].reshape(-1, size)[:] = block
    flat[whole:] = block[: flat.shape[0] - whole]


def clear_box(records: np.ndarray, ncols: int, rows: tuple[int, int], cols: tuple[int, int]) -> int:
    """Blank the records of the nodes in rows ``rows`` and columns ``cols`` (inclusive).

    ``records`` (C-contiguous) are those of a grid of nodes ``ncols`` wide (node
    ``(i, j)`` at ``i * ncols + j``). A box as wide as half the grid or wider
    blanks its rows whole (:func:`clear_records`, one pass: the contiguous
    memory is faster to write than the box alone); a narrower one copies its
    width of :data:`_BLANK_BLOCK` into each row (one strided copy). Returns
    the number of records blanked.
    """
    top, bottom = rows
    left, right = cols
    if bottom < top or right < left:
        return 0
    span = right - left + 1
    size = _BLANK_BLOCK.shape[0] // RECORD
    if 2 * span >= ncols or span > size:
        clear_records(records[top * ncols : (bottom + 1) * ncols])
        return (bottom - top + 1) * ncols
    box = records.reshape(-1, ncols * RECORD, copy=False)[top : bottom + 1]
    box[:, RECORD * left : RECORD * (right + 1)] = _BLANK_BLOCK[: RECORD * span]
    return (bottom - top + 1) * span


# Zeros of at least this many bytes are mapped pages of their own (_lazy_zeros).
_LAZY_BYTES = 1 << 20


def _anonymous_pages(nbytes: int) -> mmap.mmap:
    """``nbytes`` of zeroed anonymous pages, copy-on-write in a forked child.

    As ``malloc``'d memory is: ``mmap.mmap(-1, n)`` alone maps shared pages on
    POSIX. Windows cannot fork, and its anonymous mappings are the process's own.
    """
    # Both branches under the platform check (not an early return): mypy skips the
    # other platform's branch, where it reported the statement after the return as
    # unreachable (``mypy --platform win32``; MAP_PRIVATE is not in Windows' stubs).
    if sys.platform == "win32":
        return mmap.mmap(-1, nbytes)
    else:
        return mmap.mmap(-1, nbytes, flags=mmap.MAP_PRIVATE | mmap.MAP_ANONYMOUS)


def _lazy_zeros(count: int, dtype: type[np.generic]) -> np.ndarray:
    """``count`` zeros of ``dtype``; a large array in pages zeroed on first touch.

    A search touches only the first few thousand slots of its heap (16 and 8
    bytes a node: 25 MB for a 1024² grid). ``np.zeros`` gets such pages zeroed
    lazily only where ``malloc`` maps them afresh; after a planner as large
    was freed, glibc serves them from its heap and ``calloc`` writes every byte
    (about 2.5 ms a 1024² planner). An anonymous mapping is always lazy. Where
    the mapping fails (``OSError``: no memory, or the process's limit of
    mappings), ``np.zeros`` (a ``MemoryError`` if there is no memory at all).
    The mapping is private where the system can fork: ``mmap.mmap(-1, n)``
    alone maps shared pages there, which a forked child's searches would
    write into its parent's planner.
    """
    nbytes = count * np.dtype(dtype).itemsize
    if nbytes >= _LAZY_BYTES:
        try:
            pages = _anonymous_pages(nbytes)
        except OSError:
            pass
        else:
            out: np.ndarray = np.frombuffer(pages, dtype=dtype, count=count)
            return out
    return np.zeros(count, dtype=dtype)


def node_records(n_nodes: int) -> tuple[np.ndarray, tuple[np.ndarray, ...]]:
    """Records of ``n_nodes`` nodes (g = rhs = inf, unqueued) and an empty heap on them.

    Returns ``(records, (nodes, keys, pos, size))``: ``records`` (n_nodes,
    :data:`RECORD`) float64 with ``g`` in column :data:`G`, ``rhs`` in
    :data:`RHS`, and ``pos``, the heap's slot index, the int64 view of column
    :data:`POS` (:func:`positions`).
    """
    n_nodes = int(n_nodes)
    records = np.empty((n_nodes, RECORD))
    clear_records(records)
    pos = positions(records)
    # Zeros, not np.empty, though a search reads only the slots it wrote: the
    # unused ones are pickled with the planner, and would carry leftover process
    # memory into it (equal planners pickling to different bytes).
    raw = _lazy_zeros(2 * n_nodes + 8, np.float64)
    skip = (_KEYS_OFFSET - raw.ctypes.data % 64) % 64 // 8
    keys = raw[skip : skip + 2 * n_nodes].reshape(n_nodes, 2)
    nodes = _lazy_zeros(n_nodes, np.int64)
    size = np.zeros(1, dtype=np.int64)
    return records, (nodes, keys, pos, size)


def heap_new(n_nodes: int) -> tuple[np.ndarray, ...]:
    """Allocate an empty heap able to hold every one of ``n_nodes`` node ids.

    Its ``pos`` is the slot column of fresh node records (:func:`node_records`).
    """
    return node_records(n_nodes)[1]


@_inlined
def _sift_up(
    nodes: np.ndarray, keys: np.ndarray, pos: np.ndarray, i: int, k0: float, k1: float
) -> int:
    """Move the ancestors of hole ``i`` whose keys are above (k0, k1) down; the final hole.

    The one sift-up of :func:`heap_update` and :func:`heap_lower` (compiled once,
    inlined by LLVM into both); the caller stores its node at the returned slot.
    ``keys`` is flat (slot i's key at ``2 i``, ``2 i + 1``).
    """
    while i > 0:
        parent = (i - 1) >> 2
        p0 = keys[2 * parent]
        p1 = keys[2 * parent + 1]
        if not (k0 < p0 or (k0 == p0 and k1 < p1)):
            break
        moved = nodes[parent]
        nodes[i] = moved
        pos[RECORD * moved & NN] = i
        keys[2 * i] = p0
        keys[2 * i + 1] = p1
        i = parent
    return i


@_helper
def heap_update(
    nodes: np.ndarray,
    keys: np.ndarray,
    pos: np.ndarray,
    size: np.ndarray,
    node: int,
    k0: float,
    k1: float,
    queued: bool,
) -> None:
    """Queue ``node`` with key (k0, k1) if ``queued``, else dequeue it (if queued).

    :func:`change`, called: every change of the heap but the two hot ones of a
    search (the pop of the top and the sift-up of a lowered key).
    """
    # ``ahead`` False, but not a literal (that would compile change() once more).
    change(nodes, keys, pos, size, node, k0, k1, queued, queued != queued)


@_inlined
def change(
    nodes: np.ndarray,
    keys: np.ndarray,
    pos: np.ndarray,
    size: np.ndarray,
    node: int,
    k0: float,
    k1: float,
    queued: bool,
    ahead: bool,
) -> None:
    """Queue ``node`` with key (k0, k1) if ``queued``, else dequeue it (if queued).

    ``ahead``: a dequeue prefetches the keys of each next level (fresh
    searches; see Prefetch in the module notes). Queuing a queued node
    changes its key; dequeuing the node in slot 0 pops the top. A queued
    node is placed at a hole ``i`` (its slot, or a new one at the end): above
    it if its key is below the key of i's parent, else at i or below it. For
    a key change this matches comparing the new key with the old one (the
    parent's key is not above the old key, which is not
    above the children's). A dequeued node's slot is filled by Floyd's
    method (see the module notes), in the same descent loop. ``keys`` is
    flat (slot i's key at ``2 i``, ``2 i + 1``).
    """
    i = pos[RECORD * node & NN]
    n = size[0]
    descend = True
    if queued:
        if i < 0:
            i = n
            n += 1
            size[0] = n
        parent = ((i - 1) >> 2) & NN
        descend = not (
            i > 0
            and (k0 < keys[2 * parent] or (k0 == keys[2 * parent] and k1 < keys[2 * parent + 1]))
        )
    else:
        if i < 0:
            return
        n -= 1
        size[0] = n
        pos[RECORD * node & NN] = -1
        if i == n:
            return
        # The last element fills the hole; it may belong higher or lower.
        node = nodes[n & NN]
        k0 = keys[2 * n & NN]
        k1 = keys[(2 * n + 1) & NN]
    # Down from the hole along the least children: to a leaf for a dequeue (Floyd's
    # method; the sift-up below then places the last element, also above slot i
    # when the dequeued node was not the top), only while a child is below a
    # requeued key (a raised key, in repairs, mostly stays near its slot).
    # Slots are masked with NN (non-negative, so numba's wraparound of negative
    # indices drops out of the address arithmetic; see the module notes). Not the
    # tournament's indices below: LLVM then made their selects branches.
    i = i & NN
    while descend:
        first = 4 * i + 1
        if first >= n:
            break
        # The least of the (up to four) children by a two-round tournament, ties
        # to the first: on first components alone for a full family, unless two
        # compared ones are equal; else on whole keys (see Tournament in the
        # module notes). (A bool in integer arithmetic counts 0 or 1; int() of it
        # would compile numba's int() overload too.) The first components
        # of a full family are compared as their bits, see Integer tournament.
        if ahead and not queued:
            # The keys of the hole's grandchildren, the next level's families: four
            # lines (slots 4 first + 1 .. 4 first + 16), fetched while this level's
            # tournament runs (see Prefetch in the module notes).
            grand = 8 * first + 2
            _prefetch(keys, grand)
            _prefetch(keys, grand + 8)
            _prefetch(keys, grand + 16)
            _prefetch(keys, grand + 24)
        last = n - 1
        tie = first + 3 > last
        if not tie:
            # A full family: its four first components, compared alone (no second
            # component, no index arithmetic: the winner's offset from ``first``).
            a_bits = _f64_bits(keys[2 * first])
            b_bits = _f64_bits(keys[2 * first + 2])
            c_bits = _f64_bits(keys[2 * first + 4])
            d_bits = _f64_bits(keys[2 * first + 6])
            second = b_bits < a_bits
            fourth = d_bits < c_bits
            l_bits = b_bits if second else a_bits
            r_bits = d_bits if fourth else c_bits
            right_wins = r_bits < l_bits
            best = first + 2 * right_wins + (fourth if right_wins else second)
            # A sign bit set (a negative key or -0.0, which the bits misorder) is a tie.
            tie = (
                ((a_bits | b_bits | c_bits | d_bits) >= _SIGN)
                | (b_bits == a_bits)
                | (d_bits == c_bits)
                | (r_bits == l_bits)
            )
        if tie:
            # A partial family, or first components tied (rare): the second ones
            # decide; a missing child stands in as a copy of the last one.
            c1 = first + 1 if first + 1 < last else last
            c2 = first + 2 if first + 2 < last else last
            c3 = first + 3 if first + 3 < last else last
            a0 = keys[2 * first]
            b0 = keys[2 * c1]
            c0 = keys[2 * c2]
            d0 = keys[2 * c3]
            second = (b0 < a0) | ((b0 == a0) & (keys[2 * c1 + 1] < keys[2 * first + 1]))
            fourth = (d0 < c0) | ((d0 == c0) & (keys[2 * c3 + 1] < keys[2 * c2 + 1]))
            left = first + second * (c1 - first)
            right = c2 + fourth * (c3 - c2)
            l0 = keys[2 * left]
            r0 = keys[2 * right]
            right_wins = (r0 < l0) | ((r0 == l0) & (keys[2 * right + 1] < keys[2 * left + 1]))
            best = left + right_wins * (right - left)
        b0 = keys[2 * best]
        b1 = keys[2 * best + 1]
        if queued and not (b0 < k0 or (b0 == k0 and b1 < k1)):
            break
        moved = nodes[best]
        nodes[i] = moved
        pos[RECORD * moved & NN] = i
        keys[2 * i] = b0
        keys[2 * i + 1] = b1
        i = best
    i = _sift_up(nodes, keys, pos, i, k0, k1)
    nodes[i] = node
    pos[RECORD * node & NN] = i
    keys[2 * i] = k0
    keys[2 * i + 1] = k1


@_inlined
def heap_lower(
    nodes: np.ndarray,
    keys: np.ndarray,
    pos: np.ndarray,
    size: np.ndarray,
    node: int,
    k0: float,
    k1: float,
) -> bool:
    """Queue ``node`` with key (k0, k1) unless it is queued with a lower key.

    The hot path of :func:`heap_update` (queuing), inlined by LLVM into its
    caller: a new node or a lowered key (nearly every case where a search
    lowers a value) sifts up here without a call (through the call, which
    passes the four arrays field by field, Field D* searched about 7 %
    slower). Returns False, changing nothing, when the key would rise: the
    caller then calls :func:`heap_update` (not called from here, so that its
    code is not linked into this function too).
    """
    i = pos[RECORD * node & NN]
    if i < 0:
        i = size[0]
        size[0] = i + 1
    elif not (k0 < keys[2 * i & NN] or (k0 == keys[2 * i & NN] and k1 < keys[(2 * i + 1) & NN])):
        return False
    i = _sift_up(nodes, keys, pos, i & NN, k0, k1)
    nodes[i] = node
    pos[RECORD * node & NN] = i
    keys[2 * i] = k0
    keys[2 * i + 1] = k1
    return True


@_kernel
def _heap_change(
    nodes: np.ndarray,
    keys: np.ndarray,
    pos: np.ndarray,
    size: np.ndarray,
    node: int,
    k0: float,
    k1: float,
    queued: bool,
) -> None:
    """:func:`heap_update` for Python callers (``keys`` flat)."""
    heap_update(nodes, keys, pos, size, node, k0, k1, queued)


def heap_push(
    nodes: np.ndarray,
    keys: np.ndarray,
    pos: np.ndarray,
    size: np.ndarray,
    node: int,
    k1: float,
    k2: float,
) -> None:
    """Queue ``node`` with key (k1, k2), or change its key if it is already queued."""
    flat = flat_positions(pos)
    _heap_change(nodes, keys.reshape(-1), flat, size, int(node), float(k1), float(k2), True)


def heap_pop(nodes: np.ndarray, keys: np.ndarray, pos: np.ndarray, size: np.ndarray) -> int:
    """Remove and return the node with the smallest key (the heap must not be empty)."""
    top = int(nodes[0])
    _heap_change(nodes, keys.reshape(-1), flat_positions(pos), size, top, 0.0, 0.0, False)
    return top


def heap_remove(
    nodes: np.ndarray, keys: np.ndarray, pos: np.ndarray, size: np.ndarray, node: int
) -> None:
    """Remove ``node`` from the heap if it is queued."""
    _heap_change(nodes, keys.reshape(-1), flat_positions(pos), size, int(node), 0.0, 0.0, False)
