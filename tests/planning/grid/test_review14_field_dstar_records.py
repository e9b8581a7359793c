"""Field D* node records (review 14): g, rhs and the heap slot share one record per node.

The D* Lite values and the heap's slot index live side by side (issue 17: one cache
line per node read instead of three), so ``FieldDStar._g``, ``_rhs`` and the heap's
``pos`` are views of one array; the heap pops with Floyd's method. These tests pin
what the layout must keep: copies rebuild the views on their own records, the heap
stays a heap after any queue, requeue or removal, and the key rows are aligned.
"""

from __future__ import annotations

import copy
import pickle
from collections.abc import Callable
from typing import Any

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from hypothesis_twins import slow_twin
from navkit.planning import FieldDStar
from navkit.planning.grid._dstar_heap import (
    POS,
    RECORD,
    heap_pop,
    heap_push,
    heap_remove,
    node_records,
)

COPIES: list[Callable[[Any], Any]] = [
    copy.copy,
    copy.deepcopy,
    lambda obj: pickle.loads(pickle.dumps(obj)),
]
COPY_IDS = ["copy", "deepcopy", "pickle"]


def _costs() -> np.ndarray:
    rng = np.random.default_rng(14)
    costs = rng.uniform(1.0, 3.0, (16, 18))
    costs[rng.random((16, 18)) < 0.2] = np.inf
    costs[0, 0] = costs[-1, -1] = 1.0
    return costs


def _views_of_own_records(planner: FieldDStar) -> bool:
    records = planner._vals
    return all(
        np.shares_memory(view, records) for view in (planner._g, planner._rhs, planner._heap[2])
    )


@pytest.mark.parametrize("clone", COPIES, ids=COPY_IDS)
def test_copies_keep_g_rhs_and_slots_on_their_own_records(clone: Callable[[Any], Any]) -> None:
    # copy and pickle copy each array on its own: without rebuilding the views, the
    # copy's kernels would write its records while its Python side read stale g/rhs
    # arrays (the reported path cost, the repair's key range) and stale heap slots.
    costs = _costs()
    planner = FieldDStar(costs)
    planner.plan((0, 0), (16, 18))
    twin = clone(planner)
    assert _views_of_own_records(twin)
    assert not np.shares_memory(twin._vals, planner._vals)
    cells = [(8, 9), (8, 10), (9, 9)]
    twin.update_costs(cells, np.inf)
    got = twin.replan((2, 1))
    changed = costs.copy()
    for cell in cells:
        changed[cell] = np.inf
    expected = FieldDStar(changed).plan((2, 1), (16, 18))
    np.testing.assert_array_equal(got.points, expected.points)
    assert got.cost == expected.cost
    # The Python view reads what the kernels wrote.
    np.testing.assert_array_equal(twin._g, twin._vals.reshape(-1)[::RECORD])
    # The original is untouched by the copy's changes and still repairs exactly.
    assert _views_of_own_records(planner)
    fresh = FieldDStar(costs).plan((0, 0), (16, 18))
    np.testing.assert_array_equal(planner.replan().points, fresh.points)


def test_new_records_are_unvisited_and_unqueued() -> None:
    records, (nodes, keys, pos, size) = node_records(37)
    assert records.shape == (37, RECORD)
    assert np.all(records[:, :POS] == np.inf)
    assert np.all(pos == -1) and size[0] == 0
    assert np.shares_memory(pos, records)
    assert nodes.shape == (37,) and keys.shape == (37, 2)
    # Slot 1, the root's first child, starts a 64-byte line, and so do the four
    # children 4i+1..4i+4 of every slot i (16-byte key rows).
    assert (keys.ctypes.data + keys.strides[0]) % 64 == 0


def _check_heap(nodes: np.ndarray, keys: np.ndarray, pos: np.ndarray, n: int) -> None:
    for slot in range(n):
        assert pos[nodes[slot]] == slot
        if slot:
            parent = (slot - 1) // 4
            assert tuple(keys[parent]) <= tuple(keys[slot])
    assert np.count_nonzero(pos >= 0) == n


# Few distinct key values: ties in the first key (decided by the second) and exact
# ties of both are common, as in D* Lite's keys on uniform costs.
KEY = st.integers(0, 6).map(float)
OPS = st.lists(
    st.tuples(st.sampled_from(["push", "pop", "remove"]), st.integers(0, 40), KEY, KEY),
    max_size=300,
)


@settings(max_examples=60, deadline=None)
@given(OPS)
def test_every_queue_requeue_and_removal_leaves_a_heap(
    sequence: list[tuple[str, int, float, float]],
) -> None:
    # Floyd's descent places a dequeued slot's replacement, and a raised key, from a
    # leaf upwards: a replacement that belongs above the removed node's slot (a
    # removal from the middle) must still end up there.
    _, (nodes, keys, pos, size) = node_records(41)
    queued: dict[int, tuple[float, float]] = {}
    for op, node, k0, k1 in sequence:
        if op == "push":
            heap_push(nodes, keys, pos, size, node, k0, k1)
            queued[node] = (k0, k1)
        elif op == "remove":
            heap_remove(nodes, keys, pos, size, node)
            queued.pop(node, None)
        elif queued:
            least = min(queued.values())
            assert queued.pop(heap_pop(nodes, keys, pos, size)) == least
        assert size[0] == len(queued)
        _check_heap(nodes, keys, pos, int(size[0]))
        for node_id, key in queued.items():
            assert tuple(keys[pos[node_id]]) == key


test_every_queue_requeue_and_removal_leaves_a_heap_thoroughly = slow_twin(
    test_every_queue_requeue_and_removal_leaves_a_heap, max_examples=300
)
