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

Compilation: :func:`heap_new` is plain NumPy (nothing to compile); the sifts are
compiled once each and called (never inlined) by the three inlined operations,
whose arguments keep one type set (int64 slots, never literal constants) so no
kernel is compiled twice. The comparisons and slot writes (:func:`_below`,
:func:`_put`) are compiled once and inlined by LLVM; the three operations stay
inlined by numba (measured: as LLVM-inlined functions of their own the first
use took about 0.2 s longer).
"""

from __future__ import annotations

from typing import Any

import numpy as np

from navkit._shared.jit import NO_REFCOUNT, typed_njit
from navkit._shared.jit import njit_inline_no_refcount as _njit_inline_no_refcount

# Compile options of the Field D* kernel modules (this one and the D* Lite, path and
# polyline kernels). Kernels called from Python need no cfunc wrapper (navkit never
# passes a kernel as a first-class function value); helpers called only from kernels
# need no Python wrapper either: each wrapper is compiled (and its LLVM optimised) with
# the kernel on first use. The numpy error model drops the zero-divisor checks (every
# division is guarded, so no result changes) and their exception code.
KERNEL_OPTIONS: dict[str, Any] = {**NO_REFCOUNT, "error_model": "numpy"}
HELPER_OPTIONS: dict[str, Any] = {**KERNEL_OPTIONS, "no_cpython_wrapper": True}
# The sifts stay calls also from LLVM-inlined callers (numba passes ``forceinline``
# on to callees that leave it unset).
_helper = typed_njit(**HELPER_OPTIONS, forceinline=False)
# The two tiny helpers used at several sites (ten in all, counting the copies of the
# inlined operations) are compiled once and inlined by LLVM: numba's IR inlining
# translated and typed them again at every site.
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
def _below(a0: float, a1: float, b0: float, b1: float) -> bool:
    """Whether key (a0, a1) is lexicographically below key (b0, b1)."""
    return a0 < b0 or (a0 == b0 and a1 < b1)


@_inlined
def _put(
    nodes: np.ndarray, keys: np.ndarray, pos: np.ndarray, i: int, node: int, k0: float, k1: float
) -> None:
    """Store ``node`` with key (k0, k1) in slot ``i``."""
    nodes[i] = node
    pos[node] = i
    keys[i, 0] = k0
    keys[i, 1] = k1


@_helper
def _sift_up(
    nodes: np.ndarray, keys: np.ndarray, pos: np.ndarray, i: int, node: int, k0: float, k1: float
) -> None:
    """Place ``node`` with key (k0, k1) at hole ``i`` or above it."""
    while i > 0:
        parent = (i - 1) >> 2
        p0 = keys[parent, 0]
        p1 = keys[parent, 1]
        if not _below(k0, k1, p0, p1):
            break
        _put(nodes, keys, pos, i, nodes[parent], p0, p1)
        i = parent
    _put(nodes, keys, pos, i, node, k0, k1)


@_helper
def _sift_down(
    nodes: np.ndarray,
    keys: np.ndarray,
    pos: np.ndarray,
    i: int,
    n: int,
    node: int,
    k0: float,
    k1: float,
) -> None:
    """Place ``node`` with key (k0, k1) at hole ``i`` or below it (heap of size n)."""
    while True:
        first = 4 * i + 1
        if first >= n:
            break
        best = first
        b0 = keys[first, 0]
        b1 = keys[first, 1]
        last = min(first + 4, n)
        for child in range(first + 1, last):
            c0 = keys[child, 0]
            c1 = keys[child, 1]
            if _below(c0, c1, b0, b1):
                best = child
                b0 = c0
                b1 = c1
        if not _below(b0, b1, k0, k1):
            break
        _put(nodes, keys, pos, i, nodes[best], b0, b1)
        i = best
    _put(nodes, keys, pos, i, node, k0, k1)


@_njit_inline_no_refcount
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
    i = pos[node]
    if i < 0:
        i = size[0]
        size[0] = i + 1
        _sift_up(nodes, keys, pos, i, node, k1, k2)
        return
    if _below(k1, k2, keys[i, 0], keys[i, 1]):
        _sift_up(nodes, keys, pos, i, node, k1, k2)
    else:
        _sift_down(nodes, keys, pos, i, size[0], node, k1, k2)


@_njit_inline_no_refcount
def heap_pop(nodes: np.ndarray, keys: np.ndarray, pos: np.ndarray, size: np.ndarray) -> int:
    """Remove and return the node with the smallest key (the heap must not be empty)."""
    top = nodes[0]
    last = size[0] - 1
    size[0] = last
    if last > 0:
        # The root slot as a variable: a literal 0 would compile a second _sift_down.
        root = last - last
        _sift_down(nodes, keys, pos, root, last, nodes[last], keys[last, 0], keys[last, 1])
    pos[top] = -1
    return int(top)


@_njit_inline_no_refcount
def heap_remove(
    nodes: np.ndarray, keys: np.ndarray, pos: np.ndarray, size: np.ndarray, node: int
) -> None:
    """Remove ``node`` from the heap if it is queued."""
    i = pos[node]
    if i < 0:
        return
    last = size[0] - 1
    size[0] = last
    pos[node] = -1
    if i != last:
        # The last element fills slot i; it may belong higher or lower.
        moved = nodes[last]
        m0 = keys[last, 0]
        m1 = keys[last, 1]
        if i > 0 and _below(m0, m1, keys[(i - 1) >> 2, 0], keys[(i - 1) >> 2, 1]):
            _sift_up(nodes, keys, pos, i, moved, m0, m1)
        else:
            _sift_down(nodes, keys, pos, i, last, moved, m0, m1)
