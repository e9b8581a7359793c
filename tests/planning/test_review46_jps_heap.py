"""Jump point search's own queue, operation by operation (review 46, JPSMUT).

:mod:`navkit.planning.grid._jps_kernels` keeps its open list in a 4-ary
min-heap of float64 (f, tie key) pairs of its own (:func:`_heap_push`,
:func:`_heap_replace_top`, which also pops, and the bookkeeping around them in
:func:`_offer` and :func:`_next_node`; the smallest child comes from
:func:`~navkit.planning.grid._search_heap.smallest_child`). Until this review
it was checked only through whole searches. A mutation review by hand (64
mutants of the sift loops, comparisons, tie-breaking, child and parent
arithmetic, the unsigned indices and the size bookkeeping) found the
searches' tests strong (48 killed, by JPS against A* and the JPS oracle of
review 26), but four mutants alive: the push loop run once more at the root
(``while i >= 0``: index -1 wraps to 2**64 - 2 and the push reads, and may
write, the 16 bytes before the heap; a glibc abort at best), the queue
reported full one entry early (the search then grows the queue and starts
again, the same paths at twice the work) and ties in f between the held
successor and a new one resolved the wrong way (``_next_node`` compares the
held one with the top, so the same order, but the push and pop the held
successor saves are spent). The other 12 are equivalent: ``<=`` for ``<``
between tie keys (equal keys are one node at one banded f, identical
entries), a child slot tested ``<= 0`` (it is -1 or >= 1), signed indices
for unsigned ones, node ids masked to 31 bits (grids are limited to
2**31 - 1 cells), the tournament for full families only from five children
on, a pop's walk seeing the moved entry's own stale copy. These tests call
the queue operations directly, through kernels of their own, on heaps
between guard values, against :mod:`heapq` with the same order (f, then the
tie key, which ends in the node id, so the order is total), and compare
whole searches with plain A* by their exact octile lengths (counts of
straight and diagonal steps, which equal lengths determine, as sqrt(2) is
irrational).
"""

from __future__ import annotations

import heapq
import math
from pathlib import Path
from typing import Any

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from navkit import NoPathError
from navkit._shared.jit import typed_njit
from navkit._shared.types import KernelInt
from navkit.mapping.io import read_movingai_map, read_movingai_scenarios
from navkit.planning import astar
from navkit.planning.grid import _jps_kernels as jk

Entry = tuple[float, float]
_TWO32 = float(2**32)


@typed_njit(cache=True)
def _push(heap: np.ndarray, n: KernelInt, f: float, key: float) -> None:
    jk._heap_push(heap, n, f, key)


@typed_njit(cache=True)
def _replace_top(heap: np.ndarray, last: KernelInt, f: float, key: float) -> KernelInt:
    return jk._heap_replace_top(heap, last, f, key)


@typed_njit(cache=True)
def _next(
    heap: np.ndarray,
    n: KernelInt,
    next_f: float,
    next_key: float,
    next_v: KernelInt,
    blocks: np.ndarray,
) -> tuple[KernelInt, KernelInt]:
    return jk._next_node(heap, n, next_f, next_key, next_v, blocks)


@typed_njit(cache=True)
def _offer(
    heap: np.ndarray,
    n: KernelInt,
    next_f: float,
    next_key: float,
    next_v: KernelInt,
    v: int,
    vr: int,
    vc: int,
    new_g: float,
    gr: int,
    gc: int,
    tie_res: float,
) -> tuple[KernelInt, float, float, KernelInt]:
    return jk._offer(heap, n, next_f, next_key, next_v, v, vr, vc, new_g, gr, gc, tie_res)


def key_of(tie: int, node: int) -> float:
    """A tie key as the searches make it: ``tie * 2**32 + node`` (see ``tie_key``)."""
    return tie * _TWO32 + node


def node(key: float) -> int:
    return int(key) & 0xFFFFFFFF


def entries(heap: np.ndarray, n: KernelInt) -> list[Entry]:
    return [(float(heap[2 * i]), float(heap[2 * i + 1])) for i in range(n)]


def assert_heap(heap: np.ndarray, n: KernelInt, ref: list[Entry]) -> None:
    """The first ``n`` slots hold exactly ``ref``'s entries, each no smaller than its parent,
    and nothing was written outside the heap."""
    assert_guards(heap)
    got = entries(heap, n)
    assert sorted(got) == sorted(ref)
    for i in range(1, n):
        assert got[(i - 1) >> 2] < got[i], (i, got)


_GUARD = 4  # float64s either side of a heap
# Read as an entry, the guard before the heap is larger than any (a parent read at
# a wrapped index -1 moves down) and the guard after it smaller (a child read past
# the end is chosen): a wrong index changes the heap, not only what it reads.
_BEFORE, _AFTER = 1e300, -1e300


def guarded(size: int) -> np.ndarray:
    """A heap of ``size`` float64 (NaN) inside guard values: :func:`assert_heap` checks
    that no operation wrote outside it (an index wrapped below 0, or one slot too far)."""
    buffer = np.full(size + 2 * _GUARD, np.nan)
    buffer[:_GUARD] = _BEFORE
    buffer[-_GUARD:] = _AFTER
    return buffer[_GUARD:-_GUARD]


def assert_guards(heap: np.ndarray) -> None:
    base = heap.base
    assert isinstance(base, np.ndarray)
    assert (base[:_GUARD] == _BEFORE).all() and (base[-_GUARD:] == _AFTER).all()


def closed_blocks(nodes: int, closed: set[int]) -> np.ndarray:
    """The ``blocks`` of a search whose closed nodes are ``closed`` (all that _next_node reads)."""
    blocks = np.zeros(3 * (nodes // 64 + 1), dtype=np.int64)
    for v in closed:
        blocks[3 * (v >> 6) + 2] |= np.int64(1) << np.int64(v & 63)
    return blocks


# An operation: ("push", f, tie), ("replace", f, tie) (a held successor that
# goes into the heap as the top leaves), ("pop",), ("held", f, tie) (a held
# successor given to _next_node, which may precede the top).
_ops = st.lists(
    st.one_of(
        st.tuples(st.just("push"), st.integers(0, 6), st.integers(0, 3)),
        st.tuples(st.just("replace"), st.integers(0, 6), st.integers(0, 3)),
        st.tuples(st.just("held"), st.integers(0, 6), st.integers(0, 3)),
        st.tuples(st.just("pop")),
    ),
    max_size=150,
)


def run_ops(ops: list[tuple[Any, ...]]) -> None:
    """Apply ``ops`` to the kernels' heap and to heapq; the same tops and entries at each step."""
    heap = guarded(2 * (len(ops) + 1))
    blocks = closed_blocks(len(ops) + 1, set())
    ref: list[Entry] = []
    n: KernelInt = 0
    for v, op in enumerate(ops):
        # f in halves of a cell: many equal f, ordered by the tie key.
        f = op[1] * 0.5 if len(op) > 1 else 0.0
        key = key_of(op[2], v) if len(op) > 1 else 0.0
        if op[0] == "push":
            _push(heap, n, f, key)
            heapq.heappush(ref, (f, key))
            n += 1
        elif op[0] == "replace" and n:
            top = _replace_top(heap, n - 1, f, key)
            assert top == node(heapq.heapreplace(ref, (f, key))[1])
        elif op[0] == "held":
            u, n = _next(heap, n, f, key, v, blocks)
            if ref and ref[0] < (f, key):
                assert u == node(heapq.heapreplace(ref, (f, key))[1])
            else:
                assert u == v
        elif op[0] == "pop" and n:
            u, n = _next(heap, n, 0.0, 0.0, -1, blocks)
            assert u == node(heapq.heappop(ref)[1])
        assert n == len(ref)
        assert_heap(heap, n, ref)
    while n:
        u, n = _next(heap, n, 0.0, 0.0, -1, blocks)
        assert u == node(heapq.heappop(ref)[1])
    assert _next(heap, 0, 0.0, 0.0, -1, blocks) == (-1, 0)


@settings(max_examples=120, deadline=None)
@given(ops=_ops)
def test_random_operations_match_heapq(ops: list[tuple[Any, ...]]) -> None:
    run_ops(ops)


@pytest.mark.slow
@settings(max_examples=3000, deadline=None)
@given(ops=_ops)
def test_random_operations_match_heapq_thoroughly(ops: list[tuple[Any, ...]]) -> None:
    run_ops(ops)


@pytest.mark.parametrize("size", [*range(1, 23), 85, 86, 341, 342])
@pytest.mark.parametrize("order", ["ascending", "descending", "shuffled", "ties"])
def test_push_then_pop_every_size_sorts(size: int, order: str) -> None:
    """Every size up to three full levels of four children and one past: the last
    family partly filled (the tournament's ``first + 3 < n`` edge) at each size."""
    rng = np.random.default_rng(size)
    fs = np.arange(size, dtype=np.float64)
    if order == "descending":
        fs = fs[::-1].copy()
    elif order == "shuffled":
        rng.shuffle(fs)
    elif order == "ties":
        fs = np.floor(fs / 3.0)
    ties = rng.integers(0, 3, size)
    heap = guarded(2 * size)
    ref: list[Entry] = []
    for v in range(size):
        _push(heap, v, float(fs[v]), key_of(int(ties[v]), v))
        ref.append((float(fs[v]), key_of(int(ties[v]), v)))
        assert_heap(heap, v + 1, ref)
    blocks = closed_blocks(size, set())
    got = []
    n: KernelInt = size
    while n:
        u, n = _next(heap, n, 0.0, 0.0, -1, blocks)
        got.append(u)
        assert_heap(heap, n, sorted(ref)[len(got) :])
    assert got == [node(k) for _, k in sorted(ref)]


@pytest.mark.parametrize("size", [1, 2, 4, 5, 6, 9, 21, 22])
def test_replace_top_puts_the_entry_where_it_fits(size: int) -> None:
    """Replacing the top by an entry smaller than all, between any two, or larger than
    all: the walk down stops in the right slot and keeps every other entry."""
    for rank in range(size + 1):
        heap = guarded(2 * size)
        ref = [(float(2 * v), key_of(1, v)) for v in range(size)]
        for v, (f, key) in enumerate(ref):
            _push(heap, v, f, key)
        # Between ranks rank - 1 and rank, and ties in f broken both ways.
        for f, tie in ((2.0 * rank - 1.0, 1), (2.0 * rank, 0), (2.0 * rank, 2)):
            h2 = guarded(2 * size)
            h2[:] = heap
            r2 = list(ref)
            heapq.heapify(r2)
            new = (f, key_of(tie, 1000))
            assert _replace_top(h2, size - 1, *new) == node(heapq.heapreplace(r2, new)[1])
            assert_heap(h2, size, r2)


def test_ties_in_f_go_to_the_smaller_key_both_ways() -> None:
    """Equal f: the smaller tie key first, whether it was pushed first or last."""
    for keys in ([key_of(0, 7), key_of(1, 3)], [key_of(1, 3), key_of(0, 7)]):
        heap = guarded(4)
        for n, key in enumerate(keys):
            _push(heap, n, 5.0, key)
        blocks = closed_blocks(8, set())
        assert _next(heap, 2, 0.0, 0.0, -1, blocks)[0] == 7
        assert _next(heap, 1, 0.0, 0.0, -1, blocks)[0] == 3


@pytest.mark.parametrize("held", [(4.0, 1, True), (5.0, 0, True), (5.0, 2, False), (6.0, 0, False)])
def test_a_held_successor_is_taken_only_when_it_precedes_the_top(
    held: tuple[float, int, bool],
) -> None:
    """Against a top (5.0, tie 1): smaller f or equal f and a smaller key go first,
    equal f and a larger key or a larger f go into the heap."""
    f, tie, first = held
    heap = guarded(8)
    _push(heap, 0, 5.0, key_of(1, 1))
    _push(heap, 1, 7.0, key_of(0, 2))
    blocks = closed_blocks(64, set())
    u, n = _next(heap, 2, f, key_of(tie, 9), 9, blocks)
    assert (u, n) == ((9, 2) if first else (1, 2))
    rest = [(5.0, key_of(1, 1)) if first else (f, key_of(tie, 9)), (7.0, key_of(0, 2))]
    assert_heap(heap, 2, rest)


@pytest.mark.parametrize("held", [False, True])
def test_closed_nodes_are_dropped_until_an_open_one(held: bool) -> None:
    """Stale entries (nodes closed since queued) are skipped, the count kept right, and
    an empty queue of stale entries gives -1; the held successor is never dropped."""
    rng = np.random.default_rng(46)
    size = 40
    fs = rng.integers(0, 10, size).astype(np.float64)
    heap = guarded(2 * size)
    for v in range(size):
        _push(heap, v, float(fs[v]), key_of(0, v))
    order = sorted(range(size), key=lambda v: (fs[v], v))
    closed = set(order[:7]) | set(order[9:20]) | set(order[21:])
    blocks = closed_blocks(size + 64, closed)
    next_f, next_key, next_v = (99.0, key_of(0, 60), 60) if held else (0.0, 0.0, -1)
    extra = int(held)  # the held one goes into the heap
    u, n = _next(heap, size, next_f, next_key, next_v, blocks)
    assert (u, n) == (order[7], size - 8 + extra)
    u, n = _next(heap, n, 0.0, 0.0, -1, blocks)
    assert (u, n) == (order[8], size - 9 + extra)
    u, n = _next(heap, n, 0.0, 0.0, -1, blocks)
    assert (u, n) == (order[20], size - 21 + extra)
    u, n = _next(heap, n, 0.0, 0.0, -1, blocks)
    if held:
        assert (u, n) == (60, 0)  # the held one went into the heap, open
    else:
        assert (u, n) == (-1, 0)


def test_offer_holds_the_best_and_pushes_the_rest_until_the_heap_is_full() -> None:
    """:func:`_offer` on a straight line to the goal (integer f, no banding effect):
    the best offer so far is held, the others pushed, ties to the smaller h then
    node; a push into a full heap gives -1, an offer that is only held does not."""
    capacity = 3
    heap = guarded(2 * capacity)
    gr, gc, res = 0, 100, 16.0
    n: KernelInt = 0
    next_v: KernelInt = -1
    next_f, next_key = math.inf, math.inf
    ref: list[Entry] = []
    held: Entry | None = None
    pushed: Entry | None
    # (node = column, g): f = g + 100 - column, h = 100 - column.
    offers = [(10, 5.0), (20, 30.0), (30, 2.0), (12, 3.0), (40, 40.0), (50, 50.0)]
    for i, (col, g) in enumerate(offers):
        h = 100 - col
        pushed = (g + h, h * res * _TWO32 + col)
        n, next_f, next_key, next_v = _offer(
            heap, n, next_f, next_key, next_v, col, 0, col, g, gr, gc, res
        )
        if held is None:
            held, pushed = pushed, None
        elif pushed < held:
            held, pushed = pushed, held
        assert (next_f, next_key, next_v) == (held[0], held[1], node(held[1]))
        if pushed is None:
            continue
        if len(ref) == capacity:
            assert (n, i) == (-1, 4)  # the fifth offer pushes the fourth entry
            break
        ref.append(pushed)
        assert n == len(ref)
        assert_heap(heap, n, ref)
    assert n == -1


@pytest.mark.parametrize("better_first", [True, False])
@pytest.mark.parametrize("by", ["h", "node"])
def test_offer_ties_in_f_hold_the_smaller_key(by: str, better_first: bool) -> None:
    """Two offers of one f: the one with the smaller tie key (smaller h, else smaller
    node) is held, whichever came first, and the other is pushed. (Holding the other
    one finds the same paths, as :func:`_next_node` compares the held one with the
    heap's top, but costs the push and pop the held successor is there to save.)"""
    # (v, vr, vc, g) towards the goal (0, 100): f = g + 100 - vc, h = 100 - vc.
    if by == "h":
        better, worse = (9, 0, 20, 15.0), (7, 0, 10, 5.0)  # f 95: h 80 against 90
    else:
        better, worse = (4, 0, 30, 5.0), (8, 0, 30, 5.0)  # f 75, h 70: node 4 against 8
    heap = guarded(4)
    state: tuple[KernelInt, float, float, KernelInt] = (0, math.inf, math.inf, -1)
    for v, vr, vc, g in (better, worse) if better_first else (worse, better):
        state = _offer(heap, state[0], state[1], state[2], state[3], v, vr, vc, g, 0, 100, 16.0)
    v, _, vc, g = worse
    assert state == (1, better[3] + 100 - better[2], key_of(16 * (100 - better[2]), better[0]),
                     better[0])  # fmt: skip
    assert entries(heap, 1) == [(g + 100 - vc, key_of(16 * (100 - vc), v))]


def test_offer_into_a_full_heap_only_to_be_held_succeeds() -> None:
    """The first offer of an expansion is only held: a full heap does not refuse it;
    the second pushes one of the two and is refused."""
    heap = guarded(2)
    _push(heap, 0, 50.0, key_of(0, 1))
    n, next_f, next_key, next_v = _offer(heap, 1, math.inf, math.inf, -1, 5, 0, 5, 9.0, 0, 0, 1.0)
    assert (n, next_f, next_key, next_v) == (1, 14.0, key_of(5, 5), 5)
    assert _offer(heap, 1, next_f, next_key, next_v, 3, 0, 3, 1.0, 0, 0, 1.0)[0] == -1
    assert _offer(heap, 1, next_f, next_key, next_v, 6, 0, 6, 20.0, 0, 0, 1.0)[0] == -1
    assert entries(heap, 1) == [(50.0, key_of(0, 1))]


# Whole searches: JPS against plain A*, by exact octile lengths.


def octile_steps(cells: np.ndarray) -> tuple[int, int]:
    """(straight, diagonal) steps of an 8-connected path of (row, col) cells."""
    steps = np.abs(np.diff(np.asarray(cells, dtype=np.int64), axis=0))
    assert steps.max(initial=1) == 1 and (steps.sum(axis=1) > 0).all()
    diagonal = int((steps.sum(axis=1) == 2).sum())
    return len(steps) - diagonal, diagonal


def both_searches(
    costs: np.ndarray, start: tuple[int, int], goal: tuple[int, int], cut: bool
) -> tuple[tuple[int, int], tuple[int, int]] | None:
    """(straight, diagonal) of JPS's and A*'s paths, or None when both find none."""
    try:
        want = octile_steps(astar(costs, start, goal, method="astar", corner_cutting=cut).cells)
    except NoPathError:
        with pytest.raises(NoPathError):
            astar(costs, start, goal, method="jps", corner_cutting=cut)
        return None
    path = astar(costs, start, goal, method="jps", corner_cutting=cut)
    got = octile_steps(path.cells)
    assert path.cost == pytest.approx(got[0] + math.sqrt(2.0) * got[1], rel=1e-12)
    return got, want


@pytest.mark.parametrize("cut", [False, True])
@pytest.mark.parametrize("seed", range(6))
def test_jps_paths_are_as_long_as_astars_on_random_grids(seed: int, cut: bool) -> None:
    rng = np.random.default_rng(4600 + seed)
    shape = (int(rng.integers(20, 90)), int(rng.integers(20, 90)))
    density = float(rng.choice([0.1, 0.25, 0.35]))
    costs = np.where(rng.random(shape) < density, np.inf, 1.0)
    free = np.argwhere(np.isfinite(costs))
    for _ in range(15):
        a, b = free[rng.integers(0, len(free), 2)]
        result = both_searches(costs, (int(a[0]), int(a[1])), (int(b[0]), int(b[1])), cut)
        if result is not None:
            assert result[0] == result[1]


_MAPS = [
    "dao/arena2",
    "dao/den011d",
    "maze/maze512-32-9",
    "room/8room_000",
    "random/random512-10-0",
]


@pytest.mark.parametrize("name", _MAPS)
def test_jps_paths_are_as_long_as_astars_on_movingai_maps(shared_data: Path, name: str) -> None:
    """The 6 longest problems and 6 of the rest of each map: the same numbers of
    straight and diagonal steps as A*, and the published optimum (8 decimals)."""
    base = shared_data / "movingai-grid-benchmarks" / name
    costs = read_movingai_map(base.with_name(base.name + ".map")).costs
    problems = read_movingai_scenarios(base.with_name(base.name + ".map.scen"))
    lengths = problems.optimal_lengths
    picks = [*np.argsort(lengths)[-6:], *np.random.default_rng(46).choice(len(lengths), 6)]
    for i in picks:
        start = tuple(int(x) for x in problems.start_cells[i])
        goal = tuple(int(x) for x in problems.goal_cells[i])
        result = both_searches(costs, start, goal, cut=False)  # type: ignore[arg-type]
        assert result is not None
        assert result[0] == result[1], (name, i)
        straight, diagonal = result[0]
        assert straight + math.sqrt(2.0) * diagonal == pytest.approx(lengths[i], abs=1e-6)
