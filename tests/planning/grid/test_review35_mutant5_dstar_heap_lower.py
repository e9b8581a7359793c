"""D* Lite heap's inlined ``heap_lower`` against a reference model (review 35, mutation testing).

``heap_lower`` (queue a node, or lower its key; refuse a rise) is the search's
hot path and has no Python wrapper, so the heap tests through ``heap_push``
never ran it: a mutant storing the second key component one slot too low
survived the Field D* tests (that component only breaks ties). A test kernel
calls it here, and after every call the heap is checked directly against a
dictionary model: every slot holds its node's exact key, every node's
position points at its slot, and every parent's key is at most its
children's (4-ary, whole keys compared); the drain is in model order.
"""

from __future__ import annotations

import numpy as np
import pytest

from navkit._shared.jit import typed_njit
from navkit.planning.grid._dstar_heap import (
    flat_positions,
    heap_lower,
    heap_new,
    heap_pop,
)


@typed_njit(cache=True)
def _lower(
    nodes: np.ndarray,
    keys: np.ndarray,
    pos: np.ndarray,
    size: np.ndarray,
    node: int,
    k0: float,
    k1: float,
) -> bool:
    return heap_lower(nodes, keys, pos, size, node, k0, k1)


def _check(nodes: np.ndarray, keys: np.ndarray, pos: np.ndarray, size: np.ndarray,
           model: dict[int, tuple[float, float]], n_nodes: int) -> None:  # fmt: skip
    n = int(size[0])
    assert n == len(model)
    flat = keys.reshape(-1)
    slots = positions_of(pos, n_nodes)
    for s in range(n):
        node = int(nodes[s])
        assert (float(flat[2 * s]), float(flat[2 * s + 1])) == model[node]
        assert slots[node] == s
        if s > 0:
            p = (s - 1) // 4
            assert (flat[2 * p], flat[2 * p + 1]) <= (flat[2 * s], flat[2 * s + 1])
    for node in range(n_nodes):
        if node not in model:
            assert slots[node] < 0


def positions_of(pos: np.ndarray, n_nodes: int) -> list[int]:
    return [int(v) for v in np.asarray(pos)[:n_nodes]]


@pytest.mark.parametrize("seed", range(8))
def test_heap_lower_keeps_exact_keys_slots_and_order(seed: int) -> None:
    rng = np.random.default_rng(seed)
    n_nodes = 40
    nodes, keys, pos, size = heap_new(n_nodes)
    flat_keys = keys.reshape(-1)
    flat_pos = flat_positions(pos)
    model: dict[int, tuple[float, float]] = {}
    for _ in range(300):
        node = int(rng.integers(0, n_nodes))
        # Few first components: ties, decided by the second, are common.
        key = (float(rng.integers(0, 6)), float(rng.integers(0, 50)))
        lowered = node not in model or key < model[node]
        got = _lower(nodes, flat_keys, flat_pos, size, node, key[0], key[1])
        assert got == lowered
        if lowered:
            model[node] = key
        _check(nodes, keys, pos, size, model, n_nodes)
    order = sorted(model, key=model.__getitem__)
    drained = [heap_pop(nodes, keys, pos, size) for _ in range(len(order))]
    assert [model[v] for v in drained] == [model[v] for v in order]
    assert int(size[0]) == 0
