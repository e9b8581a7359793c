"""Review 50 (MUTANT30): the heaps' tournaments keep the first of wholly equal entries.

Review 50 (ASTARCOLD) wrote the lexicographic comparison out at each of the
tournament's three comparisons, in ``smallest_child`` (the jump point
search's float64 queue) and ``_smallest_bits`` (A*'s uint64 ``rec_*`` heap).
Two mutants that let the later of two entries equal in f AND key win one
comparison (``<=`` on the keys) survived the suite, or were caught only by a
random draw: review 23's property test draws such full ties rarely. Here
each comparison meets a full tie in the pair that wins: the first child of
the least entries is chosen, for both queues.
"""

from __future__ import annotations

import numpy as np
import pytest

from navkit._shared.jit import typed_njit
from navkit.planning.grid._search_heap import REC_BASE, _smallest_bits, smallest_child


@typed_njit(cache=True)
def _float_child(heap: np.ndarray, b: int, i: int, n: int) -> tuple[int, float, float]:
    return smallest_child(heap, b, i, n)


@typed_njit(cache=True)
def _bits_child(heap: np.ndarray, b: int, i: int, n: int) -> tuple[int, np.uint64, np.uint64]:
    return _smallest_bits(heap, b, i, n)


#: Children's f (each with the same key), the child that must win (0-3): a full tie
#: in the first pair, in the second pair, and between the pairs' winners.
CASES = [
    ((1, 1, 5, 5), 0),
    ((5, 5, 1, 1), 2),
    ((1, 5, 1, 5), 0),
    ((5, 1, 5, 1), 1),
    ((1, 1, 1, 1), 0),
]


@pytest.mark.parametrize(("fs", "win"), CASES)
@pytest.mark.parametrize("queue", ["float", "bits"])
def test_the_first_of_wholly_equal_least_children_wins(
    queue: str, fs: tuple[int, ...], win: int
) -> None:
    for i in (0, 1):  # the root's children (slots 1-4) and slot 1's (5-8)
        n = 4 * i + 5
        first = 4 * i + 1
        if queue == "float":
            b = 0
            heap = np.full(2 * n + 8, np.nan)
            heap[: 2 * n] = 9.0
        else:
            b = 2 * REC_BASE
            heap = np.full(b + 2 * n + 8, 9, dtype=np.uint64)
        for j, f in enumerate(fs):
            heap[b + 2 * (first + j)] = f
            heap[b + 2 * (first + j) + 1] = 3
        before = heap.copy()
        choose = _float_child if queue == "float" else _bits_child
        slot, f, key = choose(heap, b, i, n)
        assert (slot, int(f), int(key)) == (first + win, fs[win], 3)
        np.testing.assert_array_equal(heap, before)
