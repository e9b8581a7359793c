"""Jump point search's queue and node records: exact costs, whatever the scratch held.

The JPS kernels reuse one thread's node records from search to search (a
stamp per 64 cells says which ones this search wrote) and grow their queue
when it fills up. Issue 17 tried an indexed queue for them (each queued node
keeps its queue slot in its record, a node whose cost improves moves up in
place, as A*'s does); it did not pay off (review 15), but the risks it
checks stay those of any change to the queue or the records: a node a
search reaches for the first time must not trust what an earlier search
left in its record, and a queue scratch too small for the queue's header
must grow, not overrun. These tests search dense random maps, where queued
nodes are often improved, with scratch that is fresh, reused by earlier
searches, or filled with garbage, and check the costs against A* and the
paths for validity.
"""

from __future__ import annotations

import contextlib
from collections.abc import Iterator

import numpy as np
import pytest
from grid_oracle import assert_valid_path
from hypothesis import given, settings
from hypothesis import strategies as st

from hypothesis_twins import slow_twin
from navkit import NoPathError
from navkit.planning import AStarPlanner, astar
from navkit.planning.grid import _astar

Case = tuple[np.ndarray, tuple[int, int], tuple[int, int]]


@st.composite
def dense_maps(draw: st.DrawFn) -> Case:
    """A random map of one cost, 25-45 % blocked, 1-40 rows and 1-150 columns."""
    rows = draw(st.integers(1, 40))
    cols = draw(st.integers(1, 150))
    rng = np.random.default_rng(draw(st.integers(0, 2**32 - 1)))
    blocked = rng.random((rows, cols)) < draw(st.sampled_from([0.25, 0.3, 0.35, 0.4, 0.45]))
    cost = draw(st.sampled_from([1.0, 3.0]))
    costs = np.where(blocked, np.inf, cost)
    free = np.argwhere(~blocked)
    if free.shape[0] == 0:
        costs[0, 0] = cost
        free = np.array([[0, 0]])
    i = draw(st.integers(0, free.shape[0] - 1))
    j = draw(st.integers(0, free.shape[0] - 1))
    return costs, (int(free[i, 0]), int(free[i, 1])), (int(free[j, 0]), int(free[j, 1]))


@contextlib.contextmanager
def fresh_scratch() -> Iterator[None]:
    """This thread's JPS scratch replaced by a new one (records, stamps, queue) meanwhile."""
    saved = _astar._jps_scratch
    _astar._jps_scratch = _astar._JpsScratch()
    try:
        yield
    finally:
        _astar._jps_scratch = saved


def poison_scratch(rows: int, cols: int, seed: int) -> None:
    """Fill this thread's JPS records with garbage: slots that point anywhere in a queue."""
    _astar._jps_workspace(rows * cols)
    scratch = _astar._jps_scratch
    rng = np.random.default_rng(seed)
    scratch.meta[:] = rng.integers(-1, 64, scratch.meta.size, dtype=np.int32)


def connected_map(
    rng: np.random.Generator, shape: tuple[int, int], density: float, cells: list[tuple[int, int]]
) -> np.ndarray:
    """A random unit-cost map, ``density`` blocked, on which A* joins ``cells[0]`` to the rest."""
    while True:
        costs = np.where(rng.random(shape) < density, np.inf, 1.0)
        for cell in cells:
            costs[cell] = 1.0
        try:
            for cell in cells[1:]:
                astar(costs, cells[0], cell, method="astar")
        except NoPathError:
            continue
        return costs


def search(
    costs: np.ndarray, start: tuple[int, int], goal: tuple[int, int], cut: bool
) -> tuple[np.ndarray, float, int] | None:
    """(cells, cost, expanded) of JPS, or None when the goal is unreachable."""
    try:
        path = astar(costs, start, goal, method="jps", corner_cutting=cut)
    except NoPathError:
        return None
    return path.cells, path.cost, path.expanded


@settings(max_examples=60, deadline=None)
@given(case=dense_maps(), cut=st.booleans(), seed=st.integers(0, 2**16))
def test_garbage_in_reused_records_changes_nothing(case: Case, cut: bool, seed: int) -> None:
    costs, start, goal = case
    rows, cols = costs.shape
    with fresh_scratch():
        fresh = search(costs, start, goal, cut)
        poison_scratch(rows, cols, seed)
        poisoned = search(costs, start, goal, cut)
    reference = None
    with contextlib.suppress(NoPathError):
        reference = astar(costs, start, goal, corner_cutting=cut, method="astar").cost
    if reference is None:
        assert fresh is None and poisoned is None
        return
    assert fresh is not None and poisoned is not None
    np.testing.assert_array_equal(poisoned[0], fresh[0])
    assert poisoned[1:] == fresh[1:]
    assert fresh[1] == pytest.approx(reference, rel=1e-12)
    cost, _ = assert_valid_path(costs, fresh[0], start, goal, corner_cutting=cut)
    assert cost == pytest.approx(reference, rel=1e-12)


test_garbage_in_reused_records_changes_nothing_thoroughly = slow_twin(
    test_garbage_in_reused_records_changes_nothing, max_examples=600
)


@pytest.mark.parametrize("cut", [False, True])
def test_many_queries_through_one_scratch_match_fresh_searches(
    cut: bool, monkeypatch: pytest.MonkeyPatch
) -> None:
    # Each search leaves the queue slots of the nodes it queued in the shared
    # records; the next one, on another map of the same size, must ignore them.
    rng = np.random.default_rng(15)
    ends = [(0, 0), (89, 129), (45, 65)]
    maps = [connected_map(rng, (90, 130), d, ends) for d in (0.2, 0.35, 0.4, 0.3)]
    queries = [((0, 0), (89, 129)), ((89, 129), (0, 0)), ((45, 65), (0, 0)), ((0, 0), (45, 65))]
    shared = []
    for costs in maps:
        planner = AStarPlanner(costs, method="jps", corner_cutting=cut)
        for start, goal in queries:
            shared.append(planner.plan(start, goal))
    i = 0
    for costs in maps:
        for start, goal in queries:
            monkeypatch.setattr(_astar, "_jps_scratch", _astar._JpsScratch())
            alone = astar(costs, start, goal, method="jps", corner_cutting=cut)
            np.testing.assert_array_equal(shared[i].cells, alone.cells)
            assert (shared[i].cost, shared[i].expanded) == (alone.cost, alone.expanded)
            assert alone.cost == pytest.approx(
                astar(costs, start, goal, corner_cutting=cut).cost, rel=1e-12
            )
            i += 1


@pytest.mark.parametrize("cut", [False, True])
@pytest.mark.parametrize("size", [2, 6, 8, 10])
def test_a_tiny_queue_scratch_grows_to_the_same_path(
    cut: bool, size: int, monkeypatch: pytest.MonkeyPatch
) -> None:
    # Scratch for at most a few queue entries (none, had the queue a header of
    # a few entries, as the rec_* heap of _search_heap has): it must grow, not
    # overrun, and the path must not change.
    costs = connected_map(np.random.default_rng(4), (60, 70), 0.35, [(0, 0), (59, 69)])
    planner = AStarPlanner(costs, method="jps", corner_cutting=cut)
    expected = planner.plan((0, 0), (59, 69))
    monkeypatch.setattr(_astar, "_jps_scratch", _astar._JpsScratch())
    _astar._jps_scratch.heap = np.empty(size, dtype=np.float64)
    again = planner.plan((0, 0), (59, 69))
    assert _astar._jps_scratch.heap.size > size
    np.testing.assert_array_equal(again.cells, expected.cells)
    assert (again.cost, again.expanded) == (expected.cost, expected.expanded)
