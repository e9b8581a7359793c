"""Per-thread scratch arrays reused by the grid searches (private).

A search on an n-cell grid needs 33 bytes per cell of scratch memory
(costs-to-come, parents, node marks and the indexed heap). Allocating it on every
call costs more than a short search itself (fresh pages are zero-filled by the
kernel on first touch), so each thread keeps one workspace sized for the largest
grid it has searched and reuses it. Nothing needs clearing between searches:

* ``mark`` holds a stamp per cell; a search with stamp ``s`` treats ``mark < s``
  as never reached, ``s`` as open and ``s + 1`` as closed, so advancing the stamp
  by 2 forgets the previous search in O(1);
* ``g`` and ``parent`` are only read where ``mark`` says this search wrote them;
* the heap's ``pos`` is -1 for every cell between searches (the kernel un-queues
  what is left in the heap before returning).
"""

from __future__ import annotations

import threading

import numpy as np
from numpy.typing import NDArray

from navkit._shared.types import FloatArray
from navkit.planning.grid._search_heap import search_heap_new

# Stamps live in uint32; restart (with a full clear) well before overflow.
_STAMP_LIMIT = 2**32 - 4


Workspace = tuple[
    FloatArray,  # g: cost from the source
    NDArray[np.int8],  # parent: direction index of the move that reached a cell
    NDArray[np.uint32],  # mark: stamp of the search that last reached a cell
    FloatArray,  # heap: (f, tie key) pairs of the 4-ary heap
    NDArray[np.int32],  # pos: heap slot of every cell, -1 when not queued
    NDArray[np.int64],  # size: number of queued cells, shape (1,)
    int,  # stamp: this search's open mark (closed is stamp + 1)
]
"""Scratch arrays of one search, a plain tuple (built once per query, so kept
as cheap as possible): ``(g, parent, mark, heap, pos, size, stamp)``, each array
with at least ``n`` cells."""


class _ThreadWorkspace(threading.local):
    """One thread's scratch arrays, grown to the largest grid it searched."""

    def __init__(self) -> None:
        self.capacity = 0
        self.stamp = 0
        self.arrays: tuple[np.ndarray, ...] = ()


_local = _ThreadWorkspace()


def workspace(n: int) -> Workspace:
    """Scratch arrays for a search over ``n`` cells with a fresh stamp."""
    ws = _local
    if n > ws.capacity:
        heap, pos, size = search_heap_new(n)
        ws.arrays = (
            np.empty(n, dtype=np.float64),
            np.empty(n, dtype=np.int8),
            np.zeros(n, dtype=np.uint32),
            heap,
            pos,
            size,
        )
        ws.capacity = n
        ws.stamp = 0
    ws.stamp += 2
    if ws.stamp >= _STAMP_LIMIT:
        ws.arrays[2][:] = 0
        ws.stamp = 2
    g, parent, mark, heap, pos, size = ws.arrays
    return g, parent, mark, heap, pos, size, ws.stamp
