"""Indexed binary min-heap with arbitrary key changes, for D* Lite (private).

Field D* (D* Lite keys) raises, lowers and removes queued keys, so it needs this
general heap; the monotone searches (A*, Dijkstra) use the leaner 4-ary heap of
:mod:`navkit.planning.grid._search_heap`. It lives in four preallocated arrays so
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
"""

from __future__ import annotations

import numpy as np

from navkit._shared.jit import njit_cached, njit_inline
from navkit._shared.jit import njit_no_refcount as _njit_no_refcount


@njit_cached
def heap_new(n_nodes: int) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Allocate an empty heap able to hold every one of ``n_nodes`` node ids."""
    nodes = np.empty(n_nodes, dtype=np.int64)
    keys = np.empty((n_nodes, 2), dtype=np.float64)
    pos = np.full(n_nodes, -1, dtype=np.int64)
    size = np.zeros(1, dtype=np.int64)
    return nodes, keys, pos, size


@njit_inline
def _less(keys: np.ndarray, i: int, j: int) -> bool:
    if keys[i, 0] < keys[j, 0]:
        return True
    if keys[i, 0] > keys[j, 0]:
        return False
    return bool(keys[i, 1] < keys[j, 1])


@njit_inline
def _swap(nodes: np.ndarray, keys: np.ndarray, pos: np.ndarray, i: int, j: int) -> None:
    ni = nodes[i]
    nj = nodes[j]
    nodes[i] = nj
    nodes[j] = ni
    pos[nj] = i
    pos[ni] = j
    k0 = keys[i, 0]
    k1 = keys[i, 1]
    keys[i, 0] = keys[j, 0]
    keys[i, 1] = keys[j, 1]
    keys[j, 0] = k0
    keys[j, 1] = k1


@_njit_no_refcount
def _sift_up(nodes: np.ndarray, keys: np.ndarray, pos: np.ndarray, i: int) -> None:
    while i > 0:
        parent = (i - 1) >> 1
        if _less(keys, i, parent):
            _swap(nodes, keys, pos, i, parent)
            i = parent
        else:
            break


@_njit_no_refcount
def _sift_down(nodes: np.ndarray, keys: np.ndarray, pos: np.ndarray, i: int, n: int) -> None:
    while True:
        left = 2 * i + 1
        if left >= n:
            break
        best = left
        right = left + 1
        if right < n and _less(keys, right, left):
            best = right
        if _less(keys, best, i):
            _swap(nodes, keys, pos, i, best)
            i = best
        else:
            break


@_njit_no_refcount
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
        nodes[i] = node
        pos[node] = i
        keys[i, 0] = k1
        keys[i, 1] = k2
        _sift_up(nodes, keys, pos, i)
        return
    old0 = keys[i, 0]
    old1 = keys[i, 1]
    keys[i, 0] = k1
    keys[i, 1] = k2
    if k1 < old0 or (k1 == old0 and k2 < old1):
        _sift_up(nodes, keys, pos, i)
    else:
        _sift_down(nodes, keys, pos, i, size[0])


@_njit_no_refcount
def heap_pop(nodes: np.ndarray, keys: np.ndarray, pos: np.ndarray, size: np.ndarray) -> int:
    """Remove and return the node with the smallest key (the heap must not be empty)."""
    top = nodes[0]
    last = size[0] - 1
    size[0] = last
    if last > 0:
        _swap(nodes, keys, pos, 0, last)
        _sift_down(nodes, keys, pos, 0, last)
    pos[top] = -1
    return int(top)


@_njit_no_refcount
def heap_remove(
    nodes: np.ndarray, keys: np.ndarray, pos: np.ndarray, size: np.ndarray, node: int
) -> None:
    """Remove ``node`` from the heap if it is queued."""
    i = pos[node]
    if i < 0:
        return
    last = size[0] - 1
    size[0] = last
    if i != last:
        _swap(nodes, keys, pos, i, last)
        moved = nodes[i]
        # The element moved into slot i may belong higher or lower.
        _sift_up(nodes, keys, pos, i)
        _sift_down(nodes, keys, pos, pos[moved], last)
    pos[node] = -1
