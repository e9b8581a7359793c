"""The grid searches' per-thread scratch (review 44, MUTANT19's surviving mutants).

* Marks are int32 stamps shifted left by 4, so a closed mark ``stamp + 1``
  must stay below ``2**27``. The stamp restart was tested relative to the
  module's own ``_STAMP_LIMIT``: a limit of ``2**27 + 4`` survived, because a
  search whose marks overflowed failed as if its queue were full and was
  retried, with a doubled queue, under the next stamps until the restart
  (same path, more memory, three searches for one). The bound is checked here
  against the int32 layout itself, search by search.
* A thread's first search allocates its records: a workspace that started
  with a capacity of 1 handed a one-cell grid's search an empty array.
* The MemoryError of the A* scratch says 16 bytes a cell (mutants saying 17,
  or dropping the raise, survived).
* A JPS search interrupted by a signal handler's search that grew the
  thread's records (restarting the stamp) is told so by the records alone:
  without that clause it returned the handler's path.
"""

from __future__ import annotations

import itertools
import signal
import threading
from typing import Any

import numpy as np
import pytest

from navkit.planning.grid import AStarPlanner, _astar, astar
from navkit.planning.grid import _workspace as workspace

# The largest stamp whose closed mark (stamp + 1) << 4 fits an int32.
_LAST_FITTING_STAMP = 2**27 - 2


def _grid() -> np.ndarray:
    rng = np.random.default_rng(44)
    grid = np.where(rng.random((30, 40)) < 0.2, np.inf, 1.0 + 999.0 * rng.random((30, 40)))
    grid[0, 0] = grid[-1, -1] = 1.0
    return grid


def test_every_search_near_the_stamp_limit_marks_within_int32(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    grid = _grid()
    planner = AStarPlanner(grid)
    monkeypatch.setattr(workspace, "_local", workspace._ThreadWorkspace())
    expected = planner.plan((0, 0), (29, 39))
    field = planner.distance_field((29, 39))
    queue = workspace._local.heap.size
    monkeypatch.setattr(workspace._local, "stamp", _LAST_FITTING_STAMP - 10)
    stamps = [workspace._local.stamp]
    for _ in range(5):
        path = planner.plan((0, 0), (29, 39))
        stamps.append(workspace._local.stamp)
        assert path.cost == expected.cost and path.expanded == expected.expanded
        assert np.array_equal(path.cells, expected.cells)
        assert np.array_equal(planner.distance_field((29, 39)), field)
        stamps.append(workspace._local.stamp)
    for before, after in itertools.pairwise(stamps):
        # One search a query: the stamp advanced once, or restarted at 2.
        assert after == before + 2 or after == 2, stamps
        assert (after + 1) << 4 < 2**31, stamps
    assert 2 in stamps  # it restarted on the way
    # No search failed for a queue it did not need.
    assert workspace._local.heap.size == queue


@pytest.mark.parametrize("shape", [(1, 1), (1, 2)])
def test_a_threads_first_search_on_a_tiny_grid_gets_records(shape: tuple[int, int]) -> None:
    results: list[object] = []

    def search() -> None:
        try:
            costs = np.full(shape, 3.0)
            goal = (0, shape[1] - 1)
            results.append(astar(costs, (0, 0), goal).cost)
            results.append(AStarPlanner(costs).distance_field(goal).tolist())
        except Exception as exc:  # reported below, with its type
            results.append(exc)

    thread = threading.Thread(target=search)
    thread.start()
    thread.join()
    step = 3.0 * (shape[1] - 1)
    assert results == [step, [[step, 0.0][-shape[1] :]]], results


class _ZerosFail:
    """numpy as the workspace module sees it, but np.zeros raises MemoryError."""

    def __getattr__(self, name: str) -> object:
        return getattr(np, name)

    @staticmethod
    def zeros(*args: object, **kwargs: object) -> np.ndarray:
        raise MemoryError("simulated")


@pytest.mark.parametrize("own", [False, True])
def test_out_of_memory_the_message_says_16_bytes_a_cell(
    monkeypatch: pytest.MonkeyPatch, own: bool
) -> None:
    monkeypatch.setattr(workspace, "_local", workspace._ThreadWorkspace())
    monkeypatch.setattr(workspace, "np", _ZerosFail())
    expected = (
        "a grid search over 90000 cells needs 1.373 MiB of scratch (16 bytes a cell, "
        "kept per thread for later searches), which could not be allocated"
    )
    with pytest.raises(MemoryError) as caught:
        workspace.workspace(90000, own=own)
    assert str(caught.value) == expected
    if not own:
        with pytest.raises(MemoryError) as caught:
            AStarPlanner(np.ones((300, 300))).plan((0, 0), (299, 299))
        assert str(caught.value) == expected


@pytest.mark.skipif(not hasattr(signal, "SIGUSR1"), reason="needs SIGUSR1")
def test_a_jps_plan_interrupted_by_a_larger_grids_plan_is_its_own(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    # The handler's search grows the thread's JPS records, which restarts the
    # stamp: the interrupted search (the thread's first, stamp 1) sees its own
    # stamp and queue again, and only the records tell that another search ran.
    small = AStarPlanner(np.ones((10, 10)), method="jps")
    large = AStarPlanner(np.ones((40, 40)), method="jps")
    mine = small.plan((0, 0), (9, 4))
    theirs = large.plan((39, 0), (0, 39))
    monkeypatch.setattr(_astar, "_jps_scratch", _astar._JpsScratch())
    real = _astar.jps_search
    fired = [False]

    def signalled(*args: object) -> object:
        out = real(*args)
        if not fired[0]:
            fired[0] = True
            signal.raise_signal(signal.SIGUSR1)
        return out

    handled: list[Any] = []
    monkeypatch.setattr(_astar, "jps_search", signalled)
    previous = signal.signal(
        signal.SIGUSR1, lambda signum, frame: handled.append(large.plan((39, 0), (0, 39)))
    )
    try:
        got = small.plan((0, 0), (9, 4))
    finally:
        signal.signal(signal.SIGUSR1, previous)
    assert len(handled) == 1
    assert np.array_equal(got.points, mine.points) and got.cost == mine.cost
    assert all(np.array_equal(h.points, theirs.points) for h in handled)
