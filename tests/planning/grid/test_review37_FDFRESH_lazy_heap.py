"""Field D* (review 37, FDFRESH): a new planner's heap in pages zeroed on first touch.

A search writes only the first few thousand slots of its heap (``nodes`` and
``keys``, 24 bytes a node: 25 MB for a 1024² grid). They were ``np.zeros``:
lazily zeroed pages where ``malloc`` maps them afresh, but after a planner as
large had been freed glibc served them from its heap and ``calloc`` wrote every
byte, about 2.5 ms of each new 1024² planner (a third of its construction).
``_lazy_zeros`` maps large ones as anonymous pages of their own. They must be
zeros, writeable, the keys aligned as before, and a planner on them must plan,
pickle and copy exactly as one on plain ``np.zeros``. The padded costs are
written in one pass (border, then the costs): the border must stay ``inf``.
"""

from __future__ import annotations

import copy
import mmap
import pickle

import numpy as np
import pytest

from navkit.planning import FieldDStar
from navkit.planning.grid import _dstar_heap
from navkit.planning.grid._dstar_heap import _KEYS_OFFSET, node_records

# Looked up here so that the first test fails, rather than the module, on code before them.
_LAZY_BYTES: int = getattr(_dstar_heap, "_LAZY_BYTES", 1 << 20)
_lazy_zeros = getattr(_dstar_heap, "_lazy_zeros", None)
# The mapping's type (a test below replaces the module's ``mmap.mmap``).
_MMAP = mmap.mmap
# A grid whose heap arrays (8 and 16 bytes a node) are both past _LAZY_BYTES.
_SIDE = 400


def _mapped(arr: np.ndarray) -> bool:
    """Whether ``arr``'s memory is an anonymous mapping of its own (an mmap at its base)."""
    base = arr
    while isinstance(base, np.ndarray) and base.base is not None:
        base = base.base
    if isinstance(base, memoryview):
        base = base.obj
    return isinstance(base, _MMAP)


def _costs(seed: int) -> np.ndarray:
    rng = np.random.default_rng(seed)
    costs = rng.uniform(1.0, 4.0, size=(_SIDE, _SIDE))
    costs[rng.random((_SIDE, _SIDE)) < 0.2] = np.inf
    costs[:2, :2] = costs[-2:, -2:] = 1.0
    return costs


def test_large_heap_arrays_are_lazy_zero_pages() -> None:
    n = (_SIDE + 1) ** 2
    assert 8 * n >= _LAZY_BYTES
    _, (nodes, keys, _, size) = node_records(n)
    for arr in (nodes, keys):
        assert _mapped(arr), "the heap should be pages of its own, zeroed on first touch"
        assert arr.flags.writeable and arr.flags.c_contiguous
        assert not arr.view(np.int64).any()
    assert nodes.shape == (n,) and nodes.dtype == np.int64
    assert keys.shape == (n, 2) and keys.dtype == np.float64
    assert keys.ctypes.data % 64 == _KEYS_OFFSET
    assert size.tolist() == [0]


@pytest.mark.parametrize("count", [0, 1, 7, _LAZY_BYTES // 8 - 1])
def test_small_zeros_stay_plain(count: int) -> None:
    out = _lazy_zeros(count, np.int64)
    assert out.shape == (count,) and out.dtype == np.int64 and out.flags.writeable
    assert not _mapped(out) and not out.any()


def test_lazy_zeros_are_writeable_pages() -> None:
    out = _lazy_zeros(_LAZY_BYTES // 8 + 3, np.float64)
    assert _mapped(out) and not out.any()
    out[-1] = 2.5
    out[0] = -1.0
    assert out[-1] == 2.5 and out[0] == -1.0 and np.count_nonzero(out) == 2


def test_a_failed_mapping_falls_back_to_plain_zeros(monkeypatch: pytest.MonkeyPatch) -> None:
    def refuse(*args: object, **kwargs: object) -> None:
        raise OSError(12, "Cannot allocate memory")

    monkeypatch.setattr(_dstar_heap.mmap, "mmap", refuse)
    out = _lazy_zeros(_LAZY_BYTES // 8 + 1, np.int64)
    assert not _mapped(out) and out.flags.writeable and not out.any()
    planner = FieldDStar(np.ones((_SIDE, _SIDE)))
    assert not _mapped(planner._heap[0]) and not _mapped(planner._heap[1])
    assert planner.plan((0, 0), (_SIDE, _SIDE)).cost == pytest.approx(_SIDE * np.sqrt(2.0))


def test_planner_on_lazy_heap_matches_plain_zeros(monkeypatch: pytest.MonkeyPatch) -> None:
    costs = _costs(37)
    lazy = FieldDStar(costs)
    assert _mapped(lazy._heap[1]) and _mapped(lazy._heap[0])
    with monkeypatch.context() as m:
        m.setattr(_dstar_heap, "_LAZY_BYTES", 1 << 62)
        plain = FieldDStar(costs)
    assert not _mapped(plain._heap[1]) and not _mapped(plain._heap[0])
    ends = ((0, 0), (_SIDE, _SIDE))
    a, b = lazy.plan(*ends), plain.plan(*ends)
    np.testing.assert_array_equal(a.points, b.points)
    assert a.cost == b.cost and a.expanded == b.expanded
    # The same heap, slot for slot, and the same pickle, byte for byte.
    np.testing.assert_array_equal(lazy._heap[0], plain._heap[0])
    np.testing.assert_array_equal(lazy._heap[1].view(np.int64), plain._heap[1].view(np.int64))
    assert pickle.dumps(lazy) == pickle.dumps(plain)
    # A copy replans as the original.
    blocked = costs.copy()
    cell = tuple(int(v) for v in np.floor(a.points[len(a.points) // 2] + 0.5))
    blocked[cell] = np.inf
    twin = copy.deepcopy(lazy)
    for planner in (lazy, twin, plain):
        planner.update_costs(cell, np.inf)
    r = [p.replan((0, 0)) for p in (lazy, twin, plain)]
    for other in r[1:]:
        np.testing.assert_array_equal(other.points, r[0].points)
        assert other.cost == r[0].cost
    fresh = FieldDStar(blocked).plan(*ends)
    np.testing.assert_array_equal(fresh.points, r[0].points)


def test_padded_costs_border_is_inf() -> None:
    costs = _costs(5)[:37, :23]
    planner = FieldDStar(costs)
    pad = planner._pad.reshape(39, 25)
    assert np.all(pad[0] == np.inf) and np.all(pad[-1] == np.inf)
    assert np.all(pad[:, 0] == np.inf) and np.all(pad[:, -1] == np.inf)
    np.testing.assert_array_equal(pad[1:-1, 1:-1], costs)
