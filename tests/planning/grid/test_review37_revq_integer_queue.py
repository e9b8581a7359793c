"""A fresh-eyes review of A*'s integer queue (session 41, REVQ): its premises, proved or broken.

Session 40 made the ``rec_*`` heap of :mod:`navkit.planning.grid._search_heap`
compare integers: f as its IEEE 754 bits (which order as f does only for
finite or infinite f >= 0, never -0.0 or NaN), the tie key
``floor(16 h) << 32 | node``, the lexicographic test as
``f1 < f2 + (k1 < k2)`` (exact while ``f2 + 1`` does not wrap), f's bits from
an LLVM bitcast intrinsic, and a lowered neighbour that does not go next
re-queued by the top's removal. These tests check each premise from the
documented limits down to the queue's operations:

* the largest f the public limits allow (costs <= 1e12, weight <= 1e6, at
  most 2**31 - 1 cells) is finite with bits far below the "no candidate"
  sentinel, and the sentinel plus a carry does not wrap;
* the carry comparison is lexicographic over every f >= 0 the bits could hold
  (subnormals, the largest double next to inf with a carry, inf), and the
  bitcast is the exact bit pattern of every double;
* the kernel's re-queue (remove a slot, then replace the top) keeps the heap
  exact on heaps of two and three entries and when one node is re-queued
  twice in a row;
* searches on extreme grids (costs one ulp apart at 1 and at 1e12, the largest
  weight; plateaus of equal f; goals beyond 65,536 cells, where the tie key
  saturated until review 38) expand exactly what a textbook A* in the same arithmetic expands, and
  the heap Dijkstra's distance fields equal SciPy's bit for bit; a heuristic
  weight of -0.0 (accepted: -0.0 >= 0) searches as 0.0 does.
"""

from __future__ import annotations

import math
import struct
from typing import Any

import numpy as np
import pytest
from grid_oracle import scipy_costs_from
from hypothesis import example, given, settings
from hypothesis import strategies as st
from record_heap import entry, push, queued_node, remove, replace_top
from test_review14_astar_deferred_queue import textbook_astar

from navkit._shared.jit import bind_numba_names, typed_njit
from navkit.errors import NoPathError
from navkit.planning import AStarPlanner, astar
from navkit.planning.grid._astar_kernels import _NONE, SQRT2, _f64_bits_python
from navkit.planning.grid._limits import MAX_COST, MAX_HEURISTIC_WEIGHT, MAX_NODES
from navkit.planning.grid._search_heap import (
    FLOAT_TIE_LIMIT,
    HEAP_TIE_LIMIT,
    TIE_RESOLUTION,
    _bits_precede,
    aligned_heap,
    tie_key,
    tie_key_bits,
    tie_resolution,
)

_MAX_FINITE = float(np.finfo(np.float64).max)


def _bits(x: float) -> int:
    return int(struct.unpack("<Q", struct.pack("<d", x))[0])


# --- the limits leave the carry room ------------------------------------------------


def test_largest_f_the_limits_allow_leaves_room_for_the_carry() -> None:
    # Every f a search queues is g + scale * h with g at most the dearest simple
    # path (each of at most MAX_NODES cells entered once, a step at most
    # sqrt(2) * MAX_COST), scale = weight * smallest cost, h at most the octile
    # distance across a grid of MAX_NODES cells (< MAX_NODES). Raising a limit
    # far enough to break the queue's premise fails here.
    g_max = MAX_NODES * SQRT2 * MAX_COST
    f_max = g_max + MAX_HEURISTIC_WEIGHT * MAX_COST * float(MAX_NODES)
    assert math.isfinite(f_max)
    assert _bits(f_max) + 1 < int(_NONE)  # a carry onto any f stays below "none"
    assert int(_NONE) + 1 < 2**64  # a carry onto "none" itself does not wrap
    # The largest tie key (the largest tie of the longest grid at its resolution,
    # the largest node id) is below "none" too; jump point search's float tie
    # key of it is exact, below 2**53 (review 38: ties no longer saturate).
    h_max = float(MAX_NODES)  # above every h of a grid of MAX_NODES cells
    resolution = tie_resolution(1, MAX_NODES, HEAP_TIE_LIMIT)
    largest_key = int(tie_key_bits(h_max, MAX_NODES - 1, resolution))
    assert largest_key == (math.floor(resolution * h_max) << 32 | (MAX_NODES - 1)) < int(_NONE)
    resolution = tie_resolution(1, MAX_NODES, FLOAT_TIE_LIMIT)
    largest_float = tie_key(h_max, MAX_NODES - 1, resolution)
    assert largest_float == math.floor(resolution * h_max) * 2**32 + MAX_NODES - 1 < 2**53


# --- the comparison and the bitcast over every double >= 0 --------------------------

non_negative = st.floats(0.0, math.inf, allow_nan=False, allow_subnormal=True)
keys = st.integers(0, 2**53)


@settings(max_examples=200, deadline=None)
@given(f1=non_negative, k1=keys, f2=non_negative, k2=keys, near=st.sampled_from([0, 1, 2]))
@example(f1=math.inf, k1=0, f2=_MAX_FINITE, k2=1, near=0)  # a carry onto the largest double
@example(f1=_MAX_FINITE, k1=0, f2=_MAX_FINITE, k2=1, near=0)
@example(f1=math.inf, k1=0, f2=math.inf, k2=1, near=0)
@example(f1=5e-324, k1=0, f2=0.0, k2=1, near=0)  # the smallest subnormal over zero
@example(f1=0.0, k1=0, f2=0.0, k2=1, near=0)
def test_carry_comparison_is_lexicographic_over_every_double_from_zero_to_inf(
    f1: float, k1: int, f2: float, k2: int, near: int
) -> None:
    if near == 1:  # f2 the next double up, where a carry reaches f1's bits exactly
        with np.errstate(over="ignore"):  # the largest double's next is inf
            f2 = float(np.nextafter(f1, math.inf))
    elif near == 2:
        f2 = f1
    got = _bits_precede(np.uint64(_bits(f1)), np.uint64(k1), np.uint64(_bits(f2)), np.uint64(k2))
    assert got == ((f1, k1) < (f2, k2))


# The intrinsic as the A* kernels bind it (NumPy's view with the JIT disabled).
f64_bits: Any = None
bind_numba_names(globals(), "navkit.planning.grid._float_bits",
                 python={"f64_bits": _f64_bits_python}, f64_bits="f64_bits")  # fmt: skip


@typed_njit(cache=True)
def _kernel_bits(values: np.ndarray, out: np.ndarray) -> None:
    for i in range(values.size):
        out[i] = f64_bits(values[i])


def test_bitcast_intrinsic_is_the_bit_pattern_of_every_double() -> None:
    # A bitcast, not a conversion: every class of double (the queue needs only
    # those >= 0, but a conversion would agree with the bits on none of the
    # fractional ones) keeps its exact pattern, its order among values >= 0
    # that of the numbers.
    rng = np.random.default_rng(37)
    specials = [0.0, -0.0, 5e-324, 2.2250738585072009e-308, 2.2250738585072014e-308, 0.5, 1.0,
                1.0 + 2**-52, 2.5, 1e12, 2.0**53 + 2, _MAX_FINITE, math.inf, -math.inf,
                -1.0, math.nan]  # fmt: skip
    random = rng.integers(0, 2**63, size=2000, dtype=np.uint64).view(np.float64)
    values = np.concatenate([np.array(specials), random])
    out = np.zeros(values.size, dtype=np.uint64)
    _kernel_bits(values, out)
    assert out.tolist() == values.view(np.uint64).tolist()
    # Sign bit clear: -0.0 == 0.0 but its bits are above every positive double's
    # (the queue never holds it: every f is g > 0 plus a product >= 0).
    non_negative = values[~np.signbit(values) & ~np.isnan(values)]
    bits = np.sort(non_negative).view(np.uint64)
    assert np.all(bits[1:] >= bits[:-1])
    assert _bits(-0.0) > _bits(math.inf)


# --- the kernel's re-queue on small heaps and twice in a row -------------------------


def _check_heap(heap: np.ndarray, meta: np.ndarray, ref: dict[int, tuple[float, float]]) -> None:
    entries = [entry(heap, i) for i in range(len(ref))]
    assert sorted(entries) == sorted(ref.values())
    for i in range(1, len(entries)):
        assert entries[(i - 1) // 4] <= entries[i]
    for v in ref:
        assert queued_node(heap, int(meta[4 * v + 3])) == v


def _requeue(
    heap: np.ndarray, meta: np.ndarray, ref: dict[int, tuple[float, float]], node: int,
    new: tuple[float, float],
) -> int:  # fmt: skip
    """The kernel's path for a queued candidate that does not go next; returns the top."""
    remove(heap, meta, len(ref), int(meta[4 * node + 3]))
    del ref[node]
    top = replace_top(heap, meta, len(ref), *new)
    best = min(ref, key=ref.__getitem__)
    assert top == best
    del ref[best]
    ref[node] = new
    _check_heap(heap, meta, ref)
    return top


requeue_cases = st.tuples(
    st.lists(
        st.tuples(st.integers(0, 3).map(float), st.integers(0, 2).map(float)),
        min_size=2,
        max_size=3,
    ),
    st.integers(0, 2),
    st.integers(0, 3).map(float),
)


@settings(max_examples=150, deadline=None)
@given(requeue_cases, st.booleans())
def test_requeue_on_heaps_of_two_and_three_entries(
    case: tuple[list[tuple[float, float]], int, float], twice: bool
) -> None:
    # Entries: (f, tie) per node 0, 1, (2); the candidate is a queued node that
    # is not the top, lowered to f (<= its own) by at most its old value, so it
    # does not precede the top (the kernel expands it next otherwise).
    priorities, pick, drop = case
    heap = aligned_heap(8)
    meta = np.zeros(4 * 8, dtype=np.int32)
    ref: dict[int, tuple[float, float]] = {}
    for node, (f, tie) in enumerate(priorities):
        push(heap, meta, ref, node, (f, tie_key(tie, node, TIE_RESOLUTION)))
    top = min(ref, key=ref.__getitem__)
    others = [v for v in ref if v != top]
    node = others[pick % len(others)]
    f, key = ref[node]
    new = (max(ref[top][0], f - drop), key)
    if new < ref[top]:
        return  # it would go next: the kernel removes it without a re-queue
    _requeue(heap, meta, ref, node, new)
    top = min(ref, key=ref.__getitem__)
    if twice and node != top:
        # The same cell lowered again by the next expansion (by less than f's
        # rounding here: the same priority), still not first.
        _requeue(heap, meta, ref, node, new)


@settings(max_examples=60, deadline=None)
@given(
    st.lists(
        st.tuples(st.integers(0, 40), st.integers(0, 12).map(float)), min_size=3, max_size=120
    ),
    st.lists(st.tuples(st.integers(0, 200), st.integers(0, 6)), min_size=1, max_size=30),
)
def test_repeated_requeues_of_the_same_cells_keep_heap_and_slots(
    pushes: list[tuple[int, float]], lowers: list[tuple[int, int]]
) -> None:
    heap = aligned_heap(64)
    meta = np.zeros(4 * 64, dtype=np.int32)
    ref: dict[int, tuple[float, float]] = {}
    for node, f in pushes:
        push(heap, meta, ref, node, (f, tie_key(node % 3, node, TIE_RESOLUTION)))
    for pick, drop in lowers:
        if len(ref) < 2:
            break
        top = min(ref, key=ref.__getitem__)
        others = sorted(v for v in ref if v != top)
        node = others[pick % len(others)]
        f, key = ref[node]
        new = (max(f - drop, ref[top][0]), key)
        if new < ref[top]:
            continue  # it would go next: the kernel removes it without a re-queue
        _requeue(heap, meta, ref, node, new)


# --- searches on extreme grids against a textbook A* ---------------------------------


@st.composite
def extreme_grids(draw: st.DrawFn) -> tuple[np.ndarray, tuple[int, int], tuple[int, int]]:
    """Costs a few ulps apart at 1 or at the largest cost, or a plateau of one cost."""
    rows = draw(st.integers(1, 10))
    cols = draw(st.integers(1, 10))
    rng = np.random.default_rng(draw(st.integers(0, 2**32 - 1)))
    kind = draw(st.sampled_from(["ulps at 1", "ulps at max", "plateau", "two costs"]))
    k = rng.integers(0, 4, size=(rows, cols))
    if kind == "ulps at 1":
        costs = 1.0 + k * 2.0**-52
    elif kind == "ulps at max":
        costs = MAX_COST - k * 2.0**-13  # ulp(1e12) = 2**-13: a few ulps apart
    elif kind == "plateau":
        costs = np.full((rows, cols), draw(st.sampled_from([1.0, 3.0, MAX_COST])))
    else:
        costs = np.where(k < 2, 1.0, MAX_COST)
    costs[rng.random((rows, cols)) < draw(st.sampled_from([0.0, 0.2, 0.4]))] = np.inf
    free = np.argwhere(np.isfinite(costs))
    if free.shape[0] == 0:
        costs[0, 0] = 1.0
        free = np.array([[0, 0]])
    i = draw(st.integers(0, free.shape[0] - 1))
    j = draw(st.integers(0, free.shape[0] - 1))
    return costs, (int(free[i, 0]), int(free[i, 1])), (int(free[j, 0]), int(free[j, 1]))


# Cells of 1 behind cells of the largest cost: f passes F_BAND_COSTS times the
# smallest cost, where the kernel stops banding f (review 40); found by CI
# (session 44) when the textbook's queue still banded every f.
_BEHIND_DEAR_CELLS = np.array(
    [[MAX_COST] * 3 + [1.0] * 6,
     [MAX_COST] * 9,
     [MAX_COST, MAX_COST, 1.0, MAX_COST, MAX_COST, 1.0, 1.0, MAX_COST, MAX_COST],
     [1.0, MAX_COST, MAX_COST, MAX_COST, 1.0, 1.0, MAX_COST, 1.0, MAX_COST]]
)  # fmt: skip


@settings(max_examples=150, deadline=None)
@given(
    case=extreme_grids(),
    eight=st.booleans(),
    corner_cutting=st.booleans(),
    weight=st.sampled_from([0.0, 1.0, 2.0, MAX_HEURISTIC_WEIGHT]),
)
@example(case=(_BEHIND_DEAR_CELLS, (0, 0), (0, 4)), eight=False, corner_cutting=False, weight=0.0)
def test_extreme_grids_expand_as_textbook_astar(
    case: tuple[np.ndarray, tuple[int, int], tuple[int, int]],
    eight: bool,
    corner_cutting: bool,
    weight: float,
) -> None:
    costs, start, goal = case
    expected_expanded, expected_path = textbook_astar(
        costs, start, goal, eight, corner_cutting, weight
    )
    options = {"connectivity": 8 if eight else 4, "corner_cutting": corner_cutting,
               "heuristic_weight": weight}  # fmt: skip
    if expected_path is None:
        with pytest.raises(NoPathError) as info:
            astar(costs, start, goal, **options)  # type: ignore[arg-type]
        assert info.value.expanded == expected_expanded
        return
    path = astar(costs, start, goal, **options)  # type: ignore[arg-type]
    assert path.expanded == expected_expanded
    assert path.cells.tolist() == [list(cell) for cell in expected_path]
    if weight <= 1.0:
        optimum = scipy_costs_from(costs, start, 8 if eight else 4, corner_cutting)[goal]
        assert math.isclose(path.cost, optimum, rel_tol=1e-12)


@settings(max_examples=30, deadline=None)
@given(case=extreme_grids(), eight=st.booleans())
def test_negative_zero_weight_queues_no_negative_zero(
    case: tuple[np.ndarray, tuple[int, int], tuple[int, int]], eight: bool
) -> None:
    # heuristic_weight=-0.0 passes the range check (-0.0 >= 0) and makes the
    # heuristic's scale -0.0; every queued f is still g > 0 plus -0.0, i.e. g:
    # the search is Dijkstra's, as with 0.0, never a -0.0 above every f's bits.
    costs, start, goal = case
    connectivity = 8 if eight else 4
    try:
        plain = astar(costs, start, goal, connectivity=connectivity, heuristic_weight=0.0)
    except NoPathError as exc:
        with pytest.raises(NoPathError) as info:
            astar(costs, start, goal, connectivity=connectivity, heuristic_weight=-0.0)
        assert info.value.expanded == exc.expanded
        return
    signed = astar(costs, start, goal, connectivity=connectivity, heuristic_weight=-0.0)
    assert signed.expanded == plain.expanded
    assert signed.cells.tolist() == plain.cells.tolist()
    assert _bits(signed.cost) == _bits(plain.cost)


@settings(max_examples=40, deadline=None)
@given(
    seed=st.integers(0, 2**32 - 1),
    shape=st.tuples(st.integers(1, 14), st.integers(1, 14)),
    eight=st.booleans(),
    corner_cutting=st.booleans(),
    spread=st.sampled_from([1e3, MAX_COST]),
)
def test_heap_distance_field_equals_scipy_bit_for_bit(
    seed: int, shape: tuple[int, int], eight: bool, corner_cutting: bool, spread: float
) -> None:
    # Costs spanning more than the bucket queue's range run the heap Dijkstra
    # of the A* kernel (goal -1, scale 0: every f a plain cost-to-come). Both it
    # and SciPy take the least of the same sums, summed in the same order from
    # the source, so the fields agree exactly.
    rng = np.random.default_rng(seed)
    costs = 1.0 + (spread - 1.0) * rng.random(shape) ** 4
    costs[rng.random(shape) < 0.25] = np.inf
    free = np.argwhere(np.isfinite(costs))
    if free.shape[0] == 0:
        return
    costs[tuple(free[rng.integers(free.shape[0])])] = spread  # too wide for buckets
    source = tuple(int(x) for x in free[rng.integers(free.shape[0])])
    connectivity = 8 if eight else 4
    planner = AStarPlanner(costs, connectivity=connectivity, corner_cutting=corner_cutting)
    field = planner.distance_field(source)  # type: ignore[arg-type]
    expected = scipy_costs_from(costs, source, connectivity, corner_cutting)  # type: ignore[arg-type]
    assert field.tobytes() == expected.tobytes()


@pytest.mark.parametrize("corner_cutting", [True, pytest.param(False, marks=pytest.mark.slow)])
def test_goal_beyond_the_old_tie_saturation_expands_as_textbook_astar(
    corner_cutting: bool,
) -> None:
    # The tie (16 h) saturated at 2**20 - 1, h = 65,536 cells, until review 38:
    # the first 4,000 columns here tied on it and went by node id alone. Now
    # they tie on h as every other cell does. A total order either way, the
    # textbook's too, and the path optimal.
    cols = 70_000
    costs = np.ones((2, cols))
    costs[0, 1000:cols:997] = np.inf
    start, goal = (0, 0), (1, cols - 1)
    resolution = tie_resolution(2, cols, HEAP_TIE_LIMIT)
    assert resolution == TIE_RESOLUTION
    nearer = int(tie_key_bits(cols - 4_001.0, 0, resolution)) >> 32
    assert nearer < int(tie_key_bits(cols - 4_000.0, 0, resolution)) >> 32
    expected_expanded, expected_path = textbook_astar(costs, start, goal, True, corner_cutting, 1.0)
    assert expected_path is not None
    path = astar(costs, start, goal, corner_cutting=corner_cutting)
    assert path.expanded == expected_expanded
    assert path.cells.tolist() == [list(cell) for cell in expected_path]
    assert path.cost == pytest.approx(cols - 2 + SQRT2, rel=1e-12)
