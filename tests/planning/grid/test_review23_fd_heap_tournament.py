"""The Field D* heap's pop compares first key components alone unless they tie.

Review 23 (issue 17): the tournament of a dequeue's descent compares the four
children's first components alone (branch-free minimums, the winner's offset
from the first child) and falls back to the comparison of whole keys for a
partial family or a tie of first components. The heap must stay the same heap,
slot for slot, as before: the Field D* searches expand nodes in its order. A
model of the former descent (whole keys compared at every level) is checked
against the kernel here after every operation, on keys drawn from a few values
(first components tie often, whole keys sometimes) and on heaps deep enough for
full families at several levels.
"""

from __future__ import annotations

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from hypothesis_twins import slow_twin
from navkit.planning.grid._dstar_heap import heap_new, heap_pop, heap_push, heap_remove

NODES = 300


def _before(a: tuple[float, float], b: tuple[float, float]) -> bool:
    return a[0] < b[0] or (a[0] == b[0] and a[1] < b[1])


class ModelHeap:
    """The heap of ``_dstar_heap.change`` as it was before review 23 (whole keys always)."""

    def __init__(self, capacity: int) -> None:
        self.nodes: list[int] = []
        self.keys: list[tuple[float, float]] = []
        self.pos = [-1] * capacity

    def _place(self, i: int, node: int, key: tuple[float, float]) -> None:
        self.nodes[i] = node
        self.keys[i] = key
        self.pos[node] = i

    def change(self, node: int, key: tuple[float, float], queued: bool) -> None:
        i = self.pos[node]
        n = len(self.nodes)
        if queued:
            if i < 0:
                i = n
                self.nodes.append(node)
                self.keys.append(key)
                n += 1
            descend = not (i > 0 and _before(key, self.keys[(i - 1) >> 2]))
        else:
            if i < 0:
                return
            self.pos[node] = -1
            n -= 1
            last_node, last_key = self.nodes.pop(), self.keys.pop()
            if i == n:
                return
            node, key = last_node, last_key
            descend = True
        while descend:
            first = 4 * i + 1
            if first >= n:
                break
            last = n - 1
            c1, c2, c3 = (min(first + k, last) for k in (1, 2, 3))
            left = c1 if _before(self.keys[c1], self.keys[first]) else first
            right = c3 if _before(self.keys[c3], self.keys[c2]) else c2
            best = right if _before(self.keys[right], self.keys[left]) else left
            if queued and not _before(self.keys[best], key):
                break
            self._place(i, self.nodes[best], self.keys[best])
            i = best
        while i > 0:
            parent = (i - 1) >> 2
            if not _before(key, self.keys[parent]):
                break
            self._place(i, self.nodes[parent], self.keys[parent])
            i = parent
        self._place(i, node, key)


values = st.sampled_from([0.0, 1.0, 1.5, 2.0, 2.5, 3.0, np.inf])
ops = st.lists(
    st.tuples(
        st.sampled_from(["push", "push", "push", "pop", "remove"]),
        st.integers(0, NODES - 1),
        values,
        values,
    ),
    min_size=50,
    max_size=600,
)


def _check(sequence: list[tuple[str, int, float, float]]) -> int:
    nodes, keys, pos, size = heap_new(NODES)
    model = ModelHeap(NODES)
    popped = 0
    for op, node, k0, k1 in sequence:
        if op == "push":
            heap_push(nodes, keys, pos, size, node, k0, k1)
            model.change(node, (k0, k1), True)
        elif op == "remove":
            heap_remove(nodes, keys, pos, size, node)
            model.change(node, (0.0, 0.0), False)
        elif size[0] > 0:
            top = model.nodes[0]
            assert heap_pop(nodes, keys, pos, size) == top
            model.change(top, (0.0, 0.0), False)
            popped += 1
        n = int(size[0])
        assert n == len(model.nodes)
        assert nodes[:n].tolist() == model.nodes
        assert [tuple(k) for k in keys[:n].tolist()] == model.keys
        assert pos.tolist() == model.pos
    return popped


@settings(max_examples=60, deadline=None)
@given(ops)
def test_pops_leave_the_heap_of_whole_key_comparisons(
    sequence: list[tuple[str, int, float, float]],
) -> None:
    _check(sequence)


test_pops_leave_the_heap_of_whole_key_comparisons_thoroughly = slow_twin(
    test_pops_leave_the_heap_of_whole_key_comparisons, max_examples=400
)


def test_a_deep_heap_with_tied_first_components_drains_in_model_order() -> None:
    # 300 nodes pushed with first components from three values (ties at every
    # level), then drained: every pop descends through full families.
    rng = np.random.default_rng(23)
    sequence = [("push", node, float(rng.integers(0, 3)), float(rng.integers(0, 50)))
                for node in rng.permutation(NODES)]  # fmt: skip
    sequence += [("pop", 0, 0.0, 0.0)] * NODES
    assert _check(sequence) == NODES
