"""The A* record heap's kernel-only operations, callable from tests (shared helper).

The ``rec_*`` functions of :mod:`navkit.planning.grid._search_heap` have no
Python wrapper; these kernels of the tests' own call them, and :func:`push`
and :func:`pop_all` apply a test's reference dictionary ``{node: (f, key)}``.
"""

from __future__ import annotations

import numpy as np

from navkit._shared.jit import typed_njit
from navkit.planning.grid._search_heap import (
    rec_pop,
    rec_remove,
    rec_replace_top,
    rec_sift_up,
)


@typed_njit(cache=True)
def sift_up(heap: np.ndarray, meta: np.ndarray, i: int, f: float, key: float) -> None:
    rec_sift_up(heap, meta, i, f, key)


@typed_njit(cache=True)
def replace_top(heap: np.ndarray, meta: np.ndarray, n: int, f: float, key: float) -> int:
    return rec_replace_top(heap, meta, n, f, key)


@typed_njit(cache=True)
def pop(heap: np.ndarray, meta: np.ndarray, n: int) -> int:
    return rec_pop(heap, meta, n)


@typed_njit(cache=True)
def remove(heap: np.ndarray, meta: np.ndarray, n: int, i: int) -> None:
    rec_remove(heap, meta, n, i)


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
