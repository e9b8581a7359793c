"""A*'s queue in integer form (session 40, issue 17): the same order, exact entries.

The ``rec_*`` heap of :mod:`navkit.planning.grid._search_heap` holds f as its
IEEE 754 bits and the tie key as an integer, and compares them as integers
(the tie keys' comparison a carry: ``f1 < f2 + (k1 < k2)``). These tests pin
that the order is the documented (f, tie key) order of floats, that every
entry keeps its exact bits through the heap's walks (a float64 anywhere on
the way would round the bits of f), and that a queued cell whose cost fell
by less than f's rounding (so that its new priority equals its old entry's,
the heap's top) is expanded next, as a textbook A* expands it.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from record_heap import entry, pop, pop_all, push, queued_node, remove, replace_top
from test_review14_astar_deferred_queue import textbook_astar

from navkit.planning import astar
from navkit.planning.grid._search_heap import TIE_RESOLUTION, aligned_heap, tie_key

# f values with fractions, some a few ulps apart (where rounding the bits of
# f to a float64's 53 bits would merge or reorder them).
_BASES = (0.0, 1.0, 2.5, 1544.1231585774822, 3.0e6 + 0.125)
f_values = st.builds(
    lambda base, ulps: float(np.nextafter(base, math.inf)) if ulps == 1 else base + ulps * 2.0**-40,
    st.sampled_from(_BASES),
    st.integers(0, 3),
)
heap_ops = st.lists(
    st.tuples(
        st.sampled_from(["push", "push", "push", "pop", "replace", "remove"]),
        st.integers(0, 99),
        f_values,
        st.integers(0, 3).map(float),
    ),
    min_size=10,
    max_size=250,
)


@settings(max_examples=60, deadline=None)
@given(heap_ops)
def test_heap_keeps_exact_entries_in_float_order(
    sequence: list[tuple[str, int, float, float]],
) -> None:
    heap = aligned_heap(100)
    meta = np.zeros(4 * 100, dtype=np.int32)
    ref: dict[int, tuple[float, float]] = {}
    for op, node, f, tie in sequence:
        new = (f, tie_key(tie, node, TIE_RESOLUTION))
        if op == "push":
            push(heap, meta, ref, node, new)
        elif op == "replace" and ref and node not in ref:
            best = min(ref, key=ref.__getitem__)
            assert replace_top(heap, meta, len(ref), *new) == best
            del ref[best]
            ref[node] = new
        elif op == "remove" and ref:
            victim = sorted(ref)[node % len(ref)]
            remove(heap, meta, len(ref), int(meta[4 * victim + 3]))
            del ref[victim]
        elif op == "pop" and ref:
            best = min(ref, key=ref.__getitem__)
            assert pop(heap, meta, len(ref)) == best
            del ref[best]
        entries = [entry(heap, i) for i in range(len(ref))]
        # The very values queued, bit for bit, in heap order.
        assert sorted(entries) == sorted(ref.values())
        for i in range(1, len(entries)):
            assert entries[(i - 1) // 4] <= entries[i]
        for v in ref:
            assert queued_node(heap, int(meta[4 * v + 3])) == v
    pop_all(heap, meta, ref)


@settings(max_examples=200, deadline=None)
@given(
    # Up to the float key's limit at 1/16 cell (16 tie < 2**21: exact below 2**53).
    tie=st.floats(0.0, 2.0**17, allow_nan=False, exclude_max=True),
    node=st.integers(0, 2**32 - 1),
)
def test_integer_tie_key_is_the_float_tie_key(tie: float, node: int) -> None:
    from navkit.planning.grid._search_heap import tie_key_bits

    assert int(tie_key_bits(tie, node, TIE_RESOLUTION)) == int(tie_key(tie, node, TIE_RESOLUTION))


finite_f = st.floats(0.0, 1e15, allow_nan=False, allow_infinity=False)
keys = st.integers(0, 2**52 - 1)


@settings(max_examples=300, deadline=None)
@given(f1=finite_f, k1=keys, f2=finite_f, k2=keys, near=st.booleans())
def test_carry_comparison_is_lexicographic(
    f1: float, k1: int, f2: float, k2: int, near: bool
) -> None:
    from navkit.planning.grid._search_heap import _bits_precede

    if near:  # equal or adjacent f values, where the tie keys decide
        f2 = f1 if k1 % 2 else float(np.nextafter(f1, math.inf))
    bits = np.array([f1, f2]).view(np.uint64)
    got = _bits_precede(bits[0], np.uint64(k1), bits[1], np.uint64(k2))
    assert got == ((f1, k1) < (f2, k2))


# Grids on which a queued cell's cost falls by less than the rounding of its f
# (costs near 5e11 differing by 1e-4), so that its new priority is its old
# entry's, the heap's top: it must go next. Found by a search over random
# grids; a kernel that tested for a strictly smaller priority there expanded
# another cell first (one expansion more on the second and third).
_OFFSETS = [
    [[2, 3, 2, None, None], [3, 0, 0, 1, 3], [0, None, 3, 2, 2], [1, 3, None, 2, 2],
     [2, 0, 2, 3, 2]],
    [[None, None, None, 0, None, 0], [None, 0, None, 1, 3, 0], [3, 0, 1, None, 1, 0],
     [1, 1, 0, 2, 1, 2], [2, 0, 1, 1, 3, 2]],
    [[3, 2, 3, 2, 0, 3, None], [1, None, None, 3, 1, 1, None]],
]  # fmt: skip
_CASES = [((4, 2), (0, 2), True), ((0, 5), (3, 3), False), ((1, 5), (1, 0), True)]


def _large_costs(offsets: list[list[int | None]]) -> np.ndarray:
    return np.array(
        [[np.inf if k is None else 5e11 + k * 1e-4 for k in row] for row in offsets]
    )


@pytest.mark.parametrize("case", range(len(_CASES)))
def test_candidate_equal_to_its_own_entry_goes_next(case: int) -> None:
    costs = _large_costs(_OFFSETS[case])
    start, goal, corner_cutting = _CASES[case]
    expanded, cells = textbook_astar(costs, start, goal, True, corner_cutting, 1.0)
    path = astar(costs, start, goal, corner_cutting=corner_cutting)
    assert cells is not None
    assert path.expanded == expanded
    assert path.cells.tolist() == [list(cell) for cell in cells]


@settings(max_examples=60, deadline=None)
@given(
    seed=st.integers(0, 2**32 - 1),
    shape=st.tuples(st.integers(2, 9), st.integers(2, 9)),
    corner_cutting=st.booleans(),
)
def test_large_cost_grids_expand_as_textbook_astar(
    seed: int, shape: tuple[int, int], corner_cutting: bool
) -> None:
    rng = np.random.default_rng(seed)
    costs = 5e11 + rng.integers(0, 4, size=shape) * 1e-4
    costs[rng.random(shape) < 0.2] = np.inf
    free = np.argwhere(np.isfinite(costs))
    if len(free) < 2:
        return
    i, j = rng.choice(len(free), 2, replace=False)
    start = (int(free[i, 0]), int(free[i, 1]))
    goal = (int(free[j, 0]), int(free[j, 1]))
    expanded, cells = textbook_astar(costs, start, goal, True, corner_cutting, 1.0)
    if cells is None:
        return
    path = astar(costs, start, goal, corner_cutting=corner_cutting)
    assert path.expanded == expanded
    assert path.cells.tolist() == [list(cell) for cell in cells]
