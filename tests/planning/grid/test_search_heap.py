"""The A*/Dijkstra 4-ary heap against a sorted reference (hypothesis)."""

from __future__ import annotations

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from navkit.planning.grid._search_heap import (
    clear,
    node_of,
    pop,
    precedes_top,
    push,
    search_heap_new,
    tie_key,
)

N_NODES = 300

ops = st.lists(
    st.tuples(
        st.sampled_from(["push", "push", "pop"]),
        st.integers(0, N_NODES - 1),
        # Few distinct f values so ties are common and the tie key matters.
        st.integers(0, 12).map(float),
        st.floats(0, 5000, allow_nan=False),
    ),
    max_size=600,
)


@settings(max_examples=150, deadline=None)
@given(ops)
def test_heap_pops_in_priority_order(sequence: list[tuple[str, int, float, float]]) -> None:
    heap, pos, size = search_heap_new(N_NODES)
    ref: dict[int, tuple[float, float]] = {}  # node -> (f, tie key)
    for op, node, f, tie in sequence:
        if op == "push":
            new = (f, tie_key(tie, node))
            # A* and Dijkstra only lower a queued priority.
            if node in ref:
                new = min(new, ref[node])
            push(heap, pos, size, new[0], new[1])
            ref[node] = new
        elif ref:
            best = min(ref, key=lambda n: ref[n])
            assert precedes_top(heap, size, ref[best][0], ref[best][1] - 1.0)
            assert not precedes_top(heap, size, ref[best][0], ref[best][1])
            assert pop(heap, pos, size) == best
            del ref[best]
        assert size[0] == len(ref)
        queued = np.flatnonzero(pos[:N_NODES] >= 0)
        assert set(queued.tolist()) == set(ref)
        for n in queued:
            assert node_of(heap[2 * pos[n] + 1]) == n
    if sequence and len(ref) > 1:
        clear(heap, pos, size)
        assert size[0] == 0
        assert (pos == -1).all()
        assert precedes_top(heap, size, 1e300, 0.0)


@given(st.integers(0, 2**32 - 1), st.floats(0, 1e9, allow_nan=False))
def test_tie_key_packs_node_exactly(node: int, tie: float) -> None:
    key = tie_key(tie, node)
    assert node_of(key) == node
    assert key < 2.0**53  # exactly representable, so comparisons are exact
    assert float(int(key)) == key


def test_tie_key_orders_by_tie_then_node() -> None:
    assert tie_key(1.0, 5) < tie_key(1.25, 0)
    assert tie_key(1.0, 4) < tie_key(1.0, 5)
    # Below the 1/16 resolution the node id decides; beyond 65535 cells it saturates.
    assert tie_key(1.0, 4) > tie_key(1.01, 3)
    assert tie_key(1e6, 7) == tie_key(1e7, 7)
