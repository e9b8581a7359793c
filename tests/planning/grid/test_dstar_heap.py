"""The shared indexed heap against a sorted reference (hypothesis)."""

from __future__ import annotations

from hypothesis import given, settings
from hypothesis import strategies as st

from hypothesis_twins import slow_twin
from navkit.planning.grid._dstar_heap import heap_new, heap_pop, heap_push, heap_remove

ops = st.lists(
    st.tuples(
        st.sampled_from(["push", "pop", "remove"]),
        st.integers(0, 19),
        st.floats(-100, 100),
        st.floats(-100, 100),
    ),
    max_size=200,
)


@settings(max_examples=50, deadline=None)
@given(ops)
def test_heap_matches_reference(sequence: list[tuple[str, int, float, float]]) -> None:
    nodes, keys, pos, size = heap_new(20)
    ref: dict[int, tuple[float, float]] = {}
    for op, node, k1, k2 in sequence:
        if op == "push":
            heap_push(nodes, keys, pos, size, node, k1, k2)
            ref[node] = (k1, k2)
        elif op == "remove":
            heap_remove(nodes, keys, pos, size, node)
            ref.pop(node, None)
        elif ref:
            best = min(ref.values())
            got = heap_pop(nodes, keys, pos, size)
            assert ref[got] == best
            del ref[got]
        assert size[0] == len(ref)
        for n in range(20):
            assert (pos[n] >= 0) == (n in ref)
    drained = []
    while size[0] > 0:
        drained.append(ref.pop(heap_pop(nodes, keys, pos, size)))
    assert drained == sorted(drained)
    assert not ref


test_heap_matches_reference_thoroughly = slow_twin(test_heap_matches_reference, max_examples=200)
