"""Per-thread scratch arrays reused by the grid searches (private).

A search on an n-cell grid needs 16 bytes per cell of scratch memory (one packed
record per cell: cost-to-come, mark and parent, see
:func:`navkit.planning.grid._astar_kernels.grid_search`) plus its queue.
Allocating it on every call costs more than a short search itself (fresh pages
are zero-filled by the kernel on first touch), so each thread keeps one
workspace sized for the largest grid it has searched and reuses it. Nothing
needs clearing between searches: each record holds the stamp of the search that
last reached its cell; a search with stamp ``s`` treats a mark below ``s`` as
never reached, ``s`` as open and ``s + 1`` as closed, so advancing the stamp by
2 forgets the previous search in O(1), and the rest of a record is only read
where its mark says this search wrote it.

A search reads its answer from the workspace after its kernel returns, and a
signal handler can search in the same thread before it does: Python runs a
handler in the main thread between two bytecodes, and a signal arriving while
a kernel runs (they release the GIL) is handled as soon as it returns. So a
search checks, once it has read its answer, that no other took the workspace
meanwhile (:func:`used_meanwhile`: each search advances the stamp or replaces
the arrays), and otherwise searches again with arrays of its own (``own``).
"""

from __future__ import annotations

import threading

import numpy as np
from numpy.typing import NDArray

from navkit._shared.types import FloatArray
from navkit.planning.grid._search_heap import aligned_heap

# Marks are int32 shifted left by 4 (parent in the low bits); restart (with a
# full clear) well before overflow.
_STAMP_LIMIT = 2**27 - 4
# Initial queue capacity, entries (doubled whenever a search fills it).
_HEAP_ENTRIES = 4096


Workspace = tuple[
    FloatArray,  # rec: packed cell records, cost-to-come at 2 * v
    NDArray[np.int32],  # meta: int32 view of rec, mark and parent at 4 * v + 2, slot at 4 * v + 3
    NDArray[np.uint64],  # heap: (f, tie key) pairs of the 4-ary queue, as integers
    int,  # stamp: this search's open mark (closed is stamp + 1)
]
"""Scratch of one search, a plain tuple (built once per query, so kept as cheap
as possible): ``(rec, meta, heap, stamp)``, records for at least ``n`` cells."""


class _ThreadWorkspace(threading.local):
    """One thread's scratch arrays, grown to the largest grid it searched."""

    def __init__(self) -> None:
        self.capacity = 0
        self.stamp = 0
        self.rec = np.zeros(0, dtype=np.float64)
        self.meta = self.rec.view(np.int32)
        self.heap = aligned_heap(_HEAP_ENTRIES)


_local = _ThreadWorkspace()


def workspace(n: int, *, own: bool = False) -> Workspace:
    """Scratch arrays for a search over ``n`` cells with a fresh stamp.

    ``own``: new arrays, not this thread's (for a search made again because
    another one used the thread's before its answer was read).
    """
    if own:
        try:
            rec = np.zeros(2 * n, dtype=np.float64)
        except MemoryError as exc:
            raise MemoryError(scratch_text(n, 16)) from exc
        return rec, rec.view(np.int32), aligned_heap(_local.heap.size), 2
    ws = _local
    if n > ws.capacity:
        try:
            rec = np.zeros(2 * n, dtype=np.float64)
        except MemoryError as exc:
            raise MemoryError(scratch_text(n, 16)) from exc
        ws.rec = rec
        ws.meta = ws.rec.view(np.int32)
        ws.capacity = n
        ws.stamp = 0
    ws.stamp += 2
    if ws.stamp >= _STAMP_LIMIT:
        ws.meta[:] = 0
        ws.stamp = 2
    return ws.rec, ws.meta, ws.heap, ws.stamp


def used_meanwhile(rec: FloatArray, stamp: int) -> bool:
    """Whether another search took this thread's workspace since one given ``rec`` and ``stamp``.

    A signal handler's search in this thread, which may have overwritten the
    answer before its reader read it. Every search given the thread's
    workspace advances its stamp or replaces its arrays; a stamp that came back
    to the same value after a full clear would have passed 2**27 searches.
    """
    ws = _local
    return ws.rec is not rec or ws.stamp != stamp


def scratch_text(cells: int, bytes_per_cell: float) -> str:
    """The message of a MemoryError from a search's scratch arrays."""
    size = cells * bytes_per_cell / 2**20
    return (
        f"a grid search over {cells} cells needs {size:.4g} MiB of scratch "
        f"({bytes_per_cell:g} bytes a cell, kept per thread for later searches), "
        "which could not be allocated"
    )


def grow_heap(entries: int = 0) -> None:
    """Double this thread's queue capacity, to at least ``entries`` entries.

    A search filled it, or the path it writes there did not fit; the search
    runs again.
    """
    _local.heap = aligned_heap(max(_local.heap.size, entries))
