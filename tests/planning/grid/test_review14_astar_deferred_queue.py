"""A*'s deferred queue updates (issue 17): the same expansions as a textbook A*.

The kernel keeps the best neighbour an expansion improves out of the heap (a
queued one keeps its stale entry until it is expanded and removed from its
slot). These tests pin that this changes nothing a caller can see: the cells
expanded, their count and the path are those of a plain lazy-deletion heapq
A* that orders the queue by the documented total order (f, then the tie key
of :func:`tie_key`); and the heap's slot removal keeps the heap and every
queued node's slot right.
"""

from __future__ import annotations

import heapq
import math

import numpy as np
from grid_oracle import scipy_costs_from, weighted_grids
from hypothesis import given, settings
from hypothesis import strategies as st
from record_heap import entry, pop, pop_all, push, queued_node, remove

from hypothesis_twins import slow_twin
from navkit.errors import NoPathError
from navkit.planning import astar
from navkit.planning.grid._search_heap import (
    F_BAND,
    F_BAND_COSTS,
    HEAP_TIE_LIMIT,
    TIE_RESOLUTION,
    aligned_heap,
    tie_key,
    tie_resolution,
)

SQRT2 = math.sqrt(2.0)
MOVES = ((-1, 0, 1.0), (1, 0, 1.0), (0, -1, 1.0), (0, 1, 1.0),
         (-1, -1, SQRT2), (-1, 1, SQRT2), (1, -1, SQRT2), (1, 1, SQRT2))  # fmt: skip


def banded(f: float, band_end: float) -> int:
    """A*'s queue key for f: its IEEE 754 bits less the lowest ``F_TIE_BITS`` (session 43).

    Only f below ``band_end`` (``F_BAND_COSTS`` times the smallest cell cost,
    review 40) is banded; f from there up is queued as its exact bits.
    """
    bits = int(np.float64(f).view(np.uint64))
    return bits & int(F_BAND) if bits < int(np.float64(band_end).view(np.uint64)) else bits


def textbook_astar(
    costs: np.ndarray,
    start: tuple[int, int],
    goal: tuple[int, int],
    eight: bool,
    corner_cutting: bool,
    weight: float,
) -> tuple[int, list[tuple[int, int]] | None]:
    """Lazy-deletion heapq A* in the kernel's arithmetic and queue order: (expanded, path).

    The same float operations in the same order as the kernel (move cost
    ``step * 0.5 * (c_u + c_v)``, octile or Manhattan h, ``f = g + scale * h``)
    so that the order of expansions can be compared exactly; f is queued as
    :func:`banded` (f within 2**-40 of itself ties, below ``F_BAND_COSTS``
    times the smallest cost).
    """
    rows, cols = costs.shape
    lowest = float(costs[np.isfinite(costs)].min())
    scale = weight * lowest
    band_end = F_BAND_COSTS * lowest
    gr, gc = goal

    def h(r: int, c: int) -> float:
        dr, dc = abs(r - gr), abs(c - gc)
        if eight:
            return max(dr, dc) + (SQRT2 - 1.0) * min(dr, dc)
        return float(dr + dc)

    g = {start: 0.0}
    parent: dict[tuple[int, int], tuple[int, int]] = {}
    closed: set[tuple[int, int]] = set()
    # The kernel's tie resolution for the grid (1/16 cell below 2**27 rows + cols).
    res = tie_resolution(rows, cols, HEAP_TIE_LIMIT)
    first = tie_key(h(*start), start[0] * cols + start[1], res)
    queue = [(banded(scale * h(*start), band_end), first, start)]
    expanded = 0
    while queue:
        _, _, u = heapq.heappop(queue)
        if u in closed:
            continue  # a stale entry: the cell's priority was lowered since
        closed.add(u)
        expanded += 1
        if u == goal:
            path = [u]
            while path[-1] in parent:
                path.append(parent[path[-1]])
            return expanded, path[::-1]
        r, c = u
        for dr, dc, step in MOVES if eight else MOVES[:4]:
            r2, c2 = r + dr, c + dc
            if not (0 <= r2 < rows and 0 <= c2 < cols) or (r2, c2) in closed:
                continue
            if costs[r2, c2] == np.inf:
                continue
            if (
                dr
                and dc
                and not corner_cutting
                and (costs[r + dr, c] == np.inf or costs[r, c + dc] == np.inf)
            ):
                continue
            new_g = g[u] + step * 0.5 * (float(costs[r, c]) + float(costs[r2, c2]))
            if new_g >= g.get((r2, c2), math.inf):
                continue
            g[(r2, c2)] = new_g
            parent[(r2, c2)] = u
            hv = h(r2, c2)
            f = banded(new_g + scale * hv, band_end)
            heapq.heappush(queue, (f, tie_key(hv, r2 * cols + c2, res), (r2, c2)))
    return expanded, None


@settings(max_examples=60, deadline=None)
@given(
    case=weighted_grids(max_side=12, p_blocked=0.3),
    eight=st.booleans(),
    corner_cutting=st.booleans(),
    weight=st.sampled_from([0.0, 0.5, 1.0, 1.5, 3.0]),
)
def test_same_expansions_and_path_as_textbook_astar(
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
        try:
            astar(costs, start, goal, **options)  # type: ignore[arg-type]
        except NoPathError as exc:
            assert exc.expanded == expected_expanded
        else:
            raise AssertionError("astar found a path the reference did not")
        return
    path = astar(costs, start, goal, **options)  # type: ignore[arg-type]
    assert path.expanded == expected_expanded
    assert path.cells.tolist() == [list(cell) for cell in expected_path]
    if weight <= 1.0:
        optimum = scipy_costs_from(costs, goal, 8 if eight else 4, corner_cutting)[start]
        assert math.isclose(path.cost, optimum, rel_tol=1e-12)


test_same_expansions_and_path_as_textbook_astar_thoroughly = slow_twin(
    test_same_expansions_and_path_as_textbook_astar, max_examples=400
)


def test_uniform_room_with_ties_expands_as_textbook_astar() -> None:
    # Open uniform space is where lowered priorities are most often expanded
    # next (a plateau of equal f): the deferred update path runs constantly.
    costs = np.ones((40, 50))
    costs[10:30, 20] = np.inf
    costs[20, 5:45] = np.inf
    costs[20, 24:27] = 1.0
    for corner_cutting in (True, False):
        expanded, cells = textbook_astar(costs, (0, 0), (39, 49), True, corner_cutting, 1.0)
        path = astar(costs, (0, 0), (39, 49), corner_cutting=corner_cutting)
        assert path.expanded == expanded
        assert cells is not None
        assert path.cells.tolist() == [list(cell) for cell in cells]


heap_ops = st.lists(
    st.tuples(
        st.sampled_from(["push", "push", "push", "push", "remove", "remove", "pop"]),
        st.integers(0, 149),
        st.integers(0, 20).map(float),
        st.integers(0, 3).map(float),
    ),
    min_size=20,
    max_size=300,
)


@settings(max_examples=60, deadline=None)
@given(heap_ops)
def test_removing_any_slot_keeps_heap_and_slots(
    sequence: list[tuple[str, int, float, float]],
) -> None:
    heap = aligned_heap(150)
    meta = np.zeros(4 * 150, dtype=np.int32)
    ref: dict[int, tuple[float, float]] = {}
    for op, node, f, tie in sequence:
        new = (f, tie_key(tie, node, TIE_RESOLUTION))
        if op == "push":
            push(heap, meta, ref, node, new)
        elif op == "remove" and ref:
            # Remove a node chosen by the drawn id among those queued.
            victim = sorted(ref)[node % len(ref)]
            remove(heap, meta, len(ref), int(meta[4 * victim + 3]))
            del ref[victim]
        elif op == "pop" and ref:
            best = min(ref, key=ref.__getitem__)
            assert pop(heap, meta, len(ref)) == best
            del ref[best]
        n = len(ref)
        entries = [entry(heap, i) for i in range(n)]
        assert sorted(entries) == sorted(ref.values())
        for i in range(1, n):  # the heap property
            assert entries[(i - 1) // 4] <= entries[i]
        for v in ref:  # every queued node knows its slot
            assert queued_node(heap, int(meta[4 * v + 3])) == v
    pop_all(heap, meta, ref)


test_removing_any_slot_keeps_heap_and_slots_thoroughly = slow_twin(
    test_removing_any_slot_keeps_heap_and_slots, max_examples=400
)
