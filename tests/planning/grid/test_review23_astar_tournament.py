"""The A* and JPS queues' step down picks the first least child, with unsigned indices.

Review 23 (issue 17): the A* search and its queue index their arrays with
``np.uint64`` (no negative-index wraparound code), and
:func:`navkit.planning.grid._search_heap.smallest_child`, the step down of
every A* pop and replace-top and of the jump point search's queue, was tried
in other forms (keys selected along with the slots). Whatever its form, its
choice must stay the same, slot for slot: the least (f, tie key) pair, the
first of equal ones, both searches expanding in the queue's order. A model
(the first slot holding the least pair) is checked here against the kernel on
keys drawn from a few values, so that first components tie often and whole
keys sometimes, for full and partial families and both queue layouts (the
``rec_*`` heap's offset and the jump point search's offset 0). The A* and
JPS searches on the 1024² benchmark maps gave the same expansions, paths and
costs before and after.
"""

from __future__ import annotations

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from hypothesis_twins import slow_twin
from navkit._shared.jit import typed_njit
from navkit.planning.grid._search_heap import REC_BASE, smallest_child


@typed_njit(cache=True)
def _smallest_child(heap: np.ndarray, b: int, i: int, n: int) -> tuple[int, float, float]:
    return smallest_child(heap, b, i, n)


def _model(heap: np.ndarray, b: int, i: int, n: int) -> tuple[int, float, float]:
    """The first of slot i's children (among ``n`` entries) holding the least (f, key)."""
    best = -1
    for j in range(4 * i + 1, min(4 * i + 5, n)):
        pair = (heap[b + 2 * j], heap[b + 2 * j + 1])
        if best < 0 or pair < (heap[b + 2 * best], heap[b + 2 * best + 1]):
            best = j
    if best < 0:
        return -1, 0.0, 0.0
    return best, float(heap[b + 2 * best]), float(heap[b + 2 * best + 1])


@st.composite
def families(draw: st.DrawFn) -> tuple[np.ndarray, int, int, int]:
    """A heap array of ``n`` entries from a few values, an offset and a slot to step down from."""
    n = draw(st.integers(1, 90))
    b = draw(st.sampled_from([0, 2 * REC_BASE]))
    values = st.sampled_from([0.0, 1.0, 1.5, 2.0, np.inf])
    keys = st.sampled_from([0.0, 3.0, 2.0**32 + 5.0, 7.0 * 2.0**32])
    pairs = draw(st.lists(st.tuples(values, keys), min_size=n, max_size=n))
    heap = np.full(b + 2 * n + 8, np.nan)  # entries past n are never read as children
    for j, (f, key) in enumerate(pairs):
        heap[b + 2 * j] = f
        heap[b + 2 * j + 1] = key
    i = draw(st.integers(0, max(0, (n - 2) // 4 + 1)))
    return heap, b, i, n


@settings(max_examples=300, deadline=None)
@given(families())
def test_smallest_child_is_the_first_least_child(case: tuple[np.ndarray, int, int, int]) -> None:
    heap, b, i, n = case
    before = heap.copy()
    assert _smallest_child(heap, b, i, n) == _model(heap, b, i, n)
    np.testing.assert_array_equal(heap, before)


test_smallest_child_is_the_first_least_child_thoroughly = slow_twin(
    test_smallest_child_is_the_first_least_child, max_examples=1500
)


def test_full_family_winner_in_every_position() -> None:
    # Each child in turn the least (the others larger by f, or equal f and larger
    # key), and the first of tied equal pairs wins: each of the selects is used.
    for b in (0, 2 * REC_BASE):
        for win in range(4):
            for tie_f in (False, True):
                heap = np.zeros(b + 2 * 5)
                for j in range(1, 5):
                    heap[b + 2 * j] = 1.0 if tie_f or j == win + 1 else 2.0
                    heap[b + 2 * j + 1] = 5.0 if j == win + 1 else 10.0 - j
                assert _smallest_child(heap, b, 0, 5) == (win + 1, 1.0, 5.0)
        heap = np.zeros(b + 2 * 5)
        heap[b + 2 :] = 4.0  # four equal pairs: the first child
        assert _smallest_child(heap, b, 0, 5) == (1, 4.0, 4.0)
