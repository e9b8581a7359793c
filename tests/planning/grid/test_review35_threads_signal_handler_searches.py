"""A search made by a signal handler does not change the search it interrupted.

The grid searches keep their scratch memory per thread (the A* records and
queue, jump point search's, the JPS tables' bit rows) and read a search's
answer from it after the kernel returns. Python runs a signal handler in the
main thread between two bytecodes, and a signal arriving while a kernel runs
(they release the GIL) is handled as soon as it returns: a handler that
searched (a periodic ``signal.setitimer`` tick of a single-threaded robot
loop, a ``SIGUSR1`` "replan now") overwrote the scratch before the
interrupted search had read its path, which then came back as the handler's
path or its cost (with a 0.3 ms timer, 17,436 of 20,000 A* plans and 7,559
of 20,000 JPS plans were wrong). The interleaving is forced here: each
kernel is wrapped so that a signal is raised as it returns, and the handler
searches the same grid for another route (or builds another grid's JPS
tables).
"""

from __future__ import annotations

import signal
import sys
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from typing import Any

import numpy as np
import pytest

from navkit.planning import AStarPlanner, astar
from navkit.planning.grid import _astar, _jps_kernels

pytestmark = pytest.mark.skipif(
    sys.platform == "win32" or not hasattr(signal, "SIGUSR1"), reason="needs SIGUSR1"
)


def _grid(seed: int = 1, size: int = 40, wide: bool = False) -> np.ndarray:
    rng = np.random.default_rng(seed)
    costs = np.where(rng.random((size, size)) < 0.2, np.inf, 1.0)
    if wide:  # a cost range the bucket queue does not take: the heap search
        costs = np.where(np.isinf(costs), np.inf, 1.0 + 1e5 * rng.random((size, size)))
    costs[0, :] = costs[-1, :] = costs[:, 0] = costs[:, -1] = 1.0
    return costs


@contextmanager
def _handler(action: Callable[[], Any]) -> Iterator[list[int]]:
    """``action`` as the SIGUSR1 handler; yields the count of its runs."""
    runs = [0]

    def handle(signum: int, frame: object) -> None:
        runs[0] += 1
        action()

    previous = signal.signal(signal.SIGUSR1, handle)
    try:
        yield runs
    finally:
        signal.signal(signal.SIGUSR1, previous)


def _signalled(kernel: Callable[..., Any]) -> Callable[..., Any]:
    """``kernel``, raising SIGUSR1 as it returns (as a signal arriving during it would be).

    Not in the handler itself: its searches run as they would, uninterrupted.
    """
    inside = [False]

    def wrapped(*args: Any) -> Any:
        out = kernel(*args)
        if not inside[0]:
            inside[0] = True
            try:
                signal.raise_signal(signal.SIGUSR1)
            finally:
                inside[0] = False
        return out

    return wrapped


def _same(a: Any, b: Any) -> bool:
    return bool(np.array_equal(a.points, b.points) and a.cost == b.cost and a.length == b.length)


@pytest.mark.parametrize("method", ["astar", "jps"])
def test_a_plan_interrupted_by_a_handlers_plan_is_its_own(
    monkeypatch: pytest.MonkeyPatch, method: str
) -> None:
    costs = _grid()
    planner = AStarPlanner(costs, method=method)
    mine = planner.plan((0, 0), (39, 39))
    theirs = planner.plan((39, 0), (0, 39))
    assert not _same(mine, theirs)
    name = "grid_search" if method == "astar" else "jps_search"
    monkeypatch.setattr(_astar, name, _signalled(getattr(_astar, name)))
    handled: list[Any] = []
    with _handler(lambda: handled.append(planner.plan((39, 0), (0, 39)))) as runs:
        got = planner.plan((0, 0), (39, 39))
    assert runs[0] >= 1
    assert _same(got, mine)
    # The handler's own plans (made alone: nothing interrupts them) are right too.
    assert all(_same(h, theirs) for h in handled)
    # And the function, which plans with a planner of its own.
    with _handler(lambda: astar(costs, (39, 0), (0, 39), method=method)):
        assert _same(astar(costs, (0, 0), (39, 39), method=method), mine)


def test_a_distance_field_interrupted_by_a_handlers_search_is_its_own(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    costs = _grid(wide=True)
    planner = AStarPlanner(costs)
    mine = planner.distance_field((0, 0))
    theirs = planner.distance_field((39, 39))
    assert not np.array_equal(mine, theirs)
    monkeypatch.setattr(_astar, "grid_search", _signalled(_astar.grid_search))
    with _handler(lambda: planner.plan((39, 0), (0, 39))) as runs:
        got = planner.distance_field((0, 0))
    assert runs[0] >= 1
    assert np.array_equal(got, mine)


def test_jump_point_tables_built_around_a_handlers_tables_are_their_own(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    """A handler builds another grid's tables (the same shape) as the kernel filling ours returns.

    Since review 48 one kernel fills the tables, before the values are
    checked (the rows were marked by ``np.less`` into per-thread scratch,
    where this test raised the signal before).
    """
    costs = _grid(seed=1)
    other = _grid(seed=2)  # the same shape
    mine = [t.copy() if isinstance(t, np.ndarray) else t for t in _jps_kernels.jps_tables(costs)]
    monkeypatch.setattr(_jps_kernels, "_build_tables", _signalled(_jps_kernels._build_tables))
    with _handler(lambda: _jps_kernels.jps_tables(other)) as runs:
        got = _jps_kernels.jps_tables(costs)
    assert runs[0] >= 1
    for a, b in zip(got, mine, strict=True):
        assert np.array_equal(a, b)
