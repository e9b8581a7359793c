"""Field D* heap, kernel view (review 18): flat keys and slots over the same memory.

The search kernels take the heap's keys flat (slot i at ``2 i``, ``2 i + 1``)
and the slots as :func:`flat_positions` (node s's slot at ``RECORD * s``), views
of the arrays the planner's Python side reads and writes (``_reset`` queues the
sources, the repair bound reads the top key). These tests pin that the views
are views (no copy that would drift from the planner's arrays), that they
index what the Python side indexes, and that the heap run through them keeps
every node's slot in its record and pops in key order.
"""

from __future__ import annotations

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from hypothesis_twins import slow_twin
from navkit.planning import FieldDStar
from navkit.planning.grid._dstar_heap import (
    POS,
    RECORD,
    flat_positions,
    heap_pop,
    heap_push,
    node_records,
)


@settings(max_examples=60, deadline=None)
@given(n=st.integers(1, 300), picks=st.lists(st.integers(0, 299), max_size=20))
def test_flat_positions_is_the_slot_column_of_the_records(n: int, picks: list[int]) -> None:
    records, (_, _, pos, _) = node_records(n)
    flat = flat_positions(pos)
    assert flat.flags.c_contiguous and flat.flags.writeable
    assert flat.dtype == np.int64
    assert np.shares_memory(flat, records)
    assert flat.shape == (RECORD * (n - 1) + 1,)
    for s in (p % n for p in picks):
        flat[RECORD * s] = 1000 + s
        assert pos[s] == 1000 + s
        assert records.view(np.int64)[s, POS] == 1000 + s
    # The neighbours' g and rhs are untouched (only slot entries were written).
    assert np.isinf(records[:, :POS]).all()


test_flat_positions_is_the_slot_column_of_the_records_thoroughly = slow_twin(
    test_flat_positions_is_the_slot_column_of_the_records, max_examples=400
)


def test_the_state_tuple_holds_views_of_the_planners_heap() -> None:
    planner = FieldDStar(np.ones((7, 9)))
    planner.plan((0, 0), (7, 9))
    _, vals, nodes, keys, pos, size, _, _ = planner._state()
    h_nodes, h_keys, h_pos, h_size = planner._heap
    assert nodes is h_nodes and size is h_size
    assert keys.ndim == 1 and np.shares_memory(keys, h_keys)
    assert keys.ctypes.data == h_keys.ctypes.data
    assert np.shares_memory(pos, planner._vals) and np.shares_memory(vals, planner._vals)
    # The same entries, read through either view.
    n = int(h_size[0])
    assert n > 0
    np.testing.assert_array_equal(keys[: 2 * n].reshape(n, 2), h_keys[:n])
    np.testing.assert_array_equal(pos[::RECORD], h_pos)


@settings(max_examples=80, deadline=None)
@given(
    ops=st.lists(
        st.tuples(st.integers(0, 11), st.integers(0, 4), st.integers(0, 4)), max_size=40
    )
)
def test_heap_through_the_kernel_view_pops_in_key_order(ops: list[tuple[int, int, int]]) -> None:
    # Small integer keys: ties in both parts are common (as on uniform costs).
    records, (nodes, keys, pos, size) = node_records(12)
    queued: dict[int, tuple[float, float]] = {}
    for node, k0, k1 in ops:
        heap_push(nodes, keys, pos, size, node, float(k0), float(k1))
        queued[node] = (float(k0), float(k1))
        assert int(size[0]) == len(queued)
        # Every queued node's slot (read from the records) holds it and its key.
        for q, key in queued.items():
            slot = int(records.view(np.int64)[q, POS])
            assert nodes[slot] == q and tuple(keys[slot]) == key
    drained = [queued[heap_pop(nodes, keys, pos, size)] for _ in range(len(queued))]
    assert drained == sorted(queued.values())
    assert (pos == -1).all()


test_heap_through_the_kernel_view_pops_in_key_order_thoroughly = slow_twin(
    test_heap_through_the_kernel_view_pops_in_key_order, max_examples=400
)
