"""Indexed 4-ary min-heap with arbitrary key changes, for D* Lite (private).

Field D* (D* Lite keys) raises, lowers and removes queued keys, so it needs this
general heap; the monotone searches (A*, Dijkstra) use the leaner heap of
:mod:`navkit.planning.grid._search_heap`. Slot i's children are 4i+1..4i+4
(a shallower tree than a binary heap: fewer cache misses per pop), and the
sifts move a hole instead of swapping. It lives in four preallocated arrays so
kernels never allocate Python objects in their loops:

``nodes`` (capacity,) int64
    Node id stored at each heap slot.
``keys`` (capacity, 2) float64
    Priority of each slot, compared lexicographically (k1, then k2); D* Lite
    uses its two-part key (min(g, rhs) + h, min(g, rhs)).
``pos`` (n_nodes,) int64
    Heap slot of every node, or -1 when the node is not queued. This index makes
    decrease-key, increase-key and removal O(log n), as D* Lite needs.
``size`` (1,) int64
    Number of queued nodes (an array so kernels can update it in place).

Capacity equal to the number of nodes is always enough because a node is queued
at most once.

Compilation: every change of the heap goes through one compiled function,
:func:`heap_update` (D* Lite's ``UpdateVertex`` on the queue: queue, requeue
or dequeue a node; popping the top is dequeuing it), called and never inlined.
It replaced separately compiled sifts, slot writes and comparisons, inlined
(by numba or LLVM) into three operations that were themselves inlined into
every caller, so that the sift code was optimised five times over: Field D*'s
first use took about 0.3 s longer. The one exception is the hot path of a
search, the sift-up of a new or lowered key, which :func:`heap_lower` inlines
into its caller (through the call, searches were about 7 % slower); both use
the one sift-up loop :func:`_sift_up`, inlined by LLVM. Whether
a node is queued or dequeued is an argument computed at run time: a literal
``True``/``False`` argument compiles the function once per value. Key
comparisons are written out (``a0 < b0 or (a0 == b0 and a1 < b1)``) and so
is ``min()``: a function for either is compiled on its own.
:func:`heap_push`, :func:`heap_pop` and :func:`heap_remove` are kernels for
Python callers (the tests); the search kernels call :func:`heap_update`
themselves. :func:`heap_new` is plain NumPy.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from navkit._shared.jit import NO_REFCOUNT, typed_njit

# Compile options of the Field D* kernel modules (this one and the D* Lite, path and
# polyline kernels). Kernels called from Python need no cfunc wrapper (navkit never
# passes a kernel as a first-class function value); helpers called only from kernels
# need no Python wrapper either: each wrapper is compiled (and its LLVM optimised) with
# the kernel on first use. The numpy error model drops the zero-divisor checks (every
# division is guarded, so no result changes) and their exception code.
KERNEL_OPTIONS: dict[str, Any] = {**NO_REFCOUNT, "error_model": "numpy"}
HELPER_OPTIONS: dict[str, Any] = {**KERNEL_OPTIONS, "no_cpython_wrapper": True}
_kernel = typed_njit(**KERNEL_OPTIONS)
# heap_update stays a call also from LLVM-inlined callers (numba passes
# ``forceinline`` on to callees that leave it unset).
_helper = typed_njit(**HELPER_OPTIONS, forceinline=False)
# The search's hot path: compiled once and inlined by LLVM (numba's ``forceinline``).
_inlined = typed_njit(**HELPER_OPTIONS, forceinline=True)


def heap_new(n_nodes: int) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Allocate an empty heap able to hold every one of ``n_nodes`` node ids."""
    n_nodes = int(n_nodes)
    nodes = np.empty(n_nodes, dtype=np.int64)
    keys = np.empty((n_nodes, 2), dtype=np.float64)
    pos = np.full(n_nodes, -1, dtype=np.int64)
    size = np.zeros(1, dtype=np.int64)
    return nodes, keys, pos, size


@_inlined
def _sift_up(
    nodes: np.ndarray, keys: np.ndarray, pos: np.ndarray, i: int, k0: float, k1: float
) -> int:
    """Move the ancestors of hole ``i`` whose keys are above (k0, k1) down; the final hole.

    The one sift-up of :func:`heap_update` and :func:`heap_lower` (compiled once,
    inlined by LLVM into both); the caller stores its node at the returned slot.
    """
    while i > 0:
        parent = (i - 1) >> 2
        p0 = keys[parent, 0]
        p1 = keys[parent, 1]
        if not (k0 < p0 or (k0 == p0 and k1 < p1)):
            break
        moved = nodes[parent]
        nodes[i] = moved
        pos[moved] = i
        keys[i, 0] = p0
        keys[i, 1] = p1
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

    Queuing a queued node changes its key; dequeuing the node in slot 0 pops
    the top. Either way one element (the node, or the last one filling the
    node's slot) is placed at a hole ``i``: above it if its key is below the
    key of i's parent, else at i or below it. For a key change this matches
    comparing the new key with the old one (the parent's key is not above the
    old key, which is not above the children's).

    """
    i = pos[node]
    n = size[0]
    if queued:
        if i < 0:
            i = n
            n += 1
            size[0] = n
    else:
        if i < 0:
            return
        n -= 1
        size[0] = n
        pos[node] = -1
        if i == n:
            return
        # The last element fills slot i; it may belong higher or lower.
        node = nodes[n]
        k0 = keys[n, 0]
        k1 = keys[n, 1]
    parent = (i - 1) >> 2
    if i > 0 and (k0 < keys[parent, 0] or (k0 == keys[parent, 0] and k1 < keys[parent, 1])):
        i = _sift_up(nodes, keys, pos, i, k0, k1)
    else:
        # Sift down: move the least child up into the hole while it is below the key.
        while True:
            first = 4 * i + 1
            if first >= n:
                break
            best = first
            b0 = keys[first, 0]
            b1 = keys[first, 1]
            last = first + 4
            if n < last:
                last = n
            for child in range(first + 1, last):
                c0 = keys[child, 0]
                c1 = keys[child, 1]
                if c0 < b0 or (c0 == b0 and c1 < b1):
                    best = child
                    b0 = c0
                    b1 = c1
            if not (b0 < k0 or (b0 == k0 and b1 < k1)):
                break
            moved = nodes[best]
            nodes[i] = moved
            pos[moved] = i
            keys[i, 0] = b0
            keys[i, 1] = b1
            i = best
    nodes[i] = node
    pos[node] = i
    keys[i, 0] = k0
    keys[i, 1] = k1


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
    i = pos[node]
    if i < 0:
        i = size[0]
        size[0] = i + 1
    elif not (k0 < keys[i, 0] or (k0 == keys[i, 0] and k1 < keys[i, 1])):
        return False
    i = _sift_up(nodes, keys, pos, i, k0, k1)
    nodes[i] = node
    pos[node] = i
    keys[i, 0] = k0
    keys[i, 1] = k1
    return True


@_kernel
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
    heap_update(nodes, keys, pos, size, node, k1, k2, node >= 0)  # node >= 0: True


@_kernel
def heap_pop(nodes: np.ndarray, keys: np.ndarray, pos: np.ndarray, size: np.ndarray) -> int:
    """Remove and return the node with the smallest key (the heap must not be empty)."""
    top: int = nodes[0]
    heap_update(nodes, keys, pos, size, top, 0.0, 0.0, top < 0)  # top < 0: False
    return top


@_kernel
def heap_remove(
    nodes: np.ndarray, keys: np.ndarray, pos: np.ndarray, size: np.ndarray, node: int
) -> None:
    """Remove ``node`` from the heap if it is queued."""
    heap_update(nodes, keys, pos, size, node, 0.0, 0.0, node < 0)  # node < 0: False
