"""The A* record heap's kernel-only operations, callable from tests (shared helper).

The ``rec_*`` functions of :mod:`navkit.planning.grid._search_heap` have no
Python wrapper; these kernels of the tests' own call them, and :func:`push`
and :func:`pop_all` apply a test's reference dictionary ``{node: (f, key)}``.
The heap is A*'s own (uint64, from ``aligned_heap``); the tests' priorities
are floats (f >= 0, :func:`~navkit.planning.grid._search_heap.tie_key`),
which the kernels pass on in the heap's integer form, as A* does (session
40), and :func:`entry` reads a slot back as floats.
"""

from __future__ import annotations

import numpy as np

from navkit._shared.jit import typed_njit
from navkit.planning.grid._search_heap import (
    REC_BASE,
    rec_pop,
    rec_remove,
    rec_replace_top,
    rec_sift_up,
)


@typed_njit(cache=True)
def sift_up(heap: np.ndarray, meta: np.ndarray, i: int, f: float, key: float) -> None:
    rec_sift_up(heap, meta, i, np.float64(f).view(np.uint64), np.uint64(key))


@typed_njit(cache=True)
def replace_top(heap: np.ndarray, meta: np.ndarray, n: int, f: float, key: float) -> int:
    return rec_replace_top(heap, meta, n, np.float64(f).view(np.uint64), np.uint64(key))


@typed_njit(cache=True)
def pop(heap: np.ndarray, meta: np.ndarray, n: int) -> int:
    return rec_pop(heap, meta, n)


@typed_njit(cache=True)
def remove(heap: np.ndarray, meta: np.ndarray, n: int, i: int) -> None:
    rec_remove(heap, meta, n, i)


def entry(heap: np.ndarray, slot: int) -> tuple[float, float]:
    """The priority (f, tie key) in ``slot`` as floats (the heap holds their uint64 form)."""
    f = heap[2 * (slot + REC_BASE) : 2 * (slot + REC_BASE) + 1].view(np.float64)[0]
    return float(f), float(heap[2 * (slot + REC_BASE) + 1])


def queued_node(heap: np.ndarray, slot: int) -> int:
    """The node whose entry is in ``slot``."""
    return int(heap[2 * (slot + REC_BASE) + 1]) & 0xFFFFFFFF


def push(
    heap: np.ndarray, meta: np.ndarray, ref: dict[int, tuple[float, float]], node: int,
    new: tuple[float, float],
) -> None:  # fmt: skip
    """Queue ``node`` at ``new`` = (f, key), or lower its priority (decrease-key only)."""
    if node in ref:
        if new >= ref[node]:
            return
        sift_up(heap, meta, int(meta[4 * node + 3]), *new)
    else:
        sift_up(heap, meta, len(ref), *new)
    ref[node] = new


def pop_all(heap: np.ndarray, meta: np.ndarray, ref: dict[int, tuple[float, float]]) -> None:
    """Pop every queued node, asserting each is the reference's least."""
    while ref:
        best = min(ref, key=ref.__getitem__)
        assert pop(heap, meta, len(ref)) == best
        del ref[best]
