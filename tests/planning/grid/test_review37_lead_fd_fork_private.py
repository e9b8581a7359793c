"""Review 37 (lead): a forked child's Field D* searches stay out of its parent's planner.

FDFRESH put a large planner's queue in anonymous mapped pages (lazily zeroed).
``mmap.mmap(-1, n)`` maps *shared* pages on POSIX, so after ``os.fork`` (the
default start method of ``multiprocessing`` on Linux before Python 3.14, and
Dask's forking workers) a child's plan wrote into its parent's queue: the
parent's next replan read the child's entries. The mapping is private now
(copy-on-write, as ``malloc``'d memory is).
"""

from __future__ import annotations

import os
import sys
import warnings

import numpy as np
import pytest

from navkit.planning import FieldDStar

pytestmark = pytest.mark.skipif(not hasattr(os, "fork"), reason="needs os.fork")


def _costs() -> np.ndarray:
    rng = np.random.default_rng(3)
    # 400 x 400: the queue (24 bytes a node) is past the 1 MiB of a mapping.
    costs = np.where(rng.random((400, 400)) < 0.2, np.inf, 1.0)
    for r, c in ((0, 0), (-1, -1), (0, -1), (-1, 0), (200, 200)):
        costs[r, c] = 1.0
    return costs


def _fork_and_plan_in_child(planner: FieldDStar) -> None:
    with warnings.catch_warnings():
        # Python 3.12+ warns of forking a process with threads; the child only plans.
        warnings.simplefilter("ignore", DeprecationWarning)
        pid = os.fork()
    if pid == 0:  # the child: a different query on the inherited planner, then out
        try:
            planner.plan((400, 0), (0, 400))
        finally:
            os._exit(0)
    _, status = os.waitpid(pid, 0)
    assert status == 0


def test_a_childs_plan_leaves_the_parents_replan_as_without_the_fork() -> None:
    costs = _costs()
    forked, alone = FieldDStar(costs), FieldDStar(costs)
    for planner in (forked, alone):
        planner.plan((0, 0), (400, 400))
    _fork_and_plan_in_child(forked)
    paths = []
    for planner in (forked, alone):
        # A small repair near the start: it runs on the queue the plan left.
        planner.update_costs([(5, 5)], [np.inf])
        paths.append(planner.replan((0, 0)))
    assert np.array_equal(paths[0].points, paths[1].points)
    assert paths[0].expanded == paths[1].expanded
    assert paths[0].cost == paths[1].cost


def test_a_childs_plan_leaves_the_parents_queue_bytes() -> None:
    planner = FieldDStar(_costs())
    planner.plan((0, 0), (400, 400))
    before = [np.array(a, copy=True) for a in planner._heap]
    _fork_and_plan_in_child(planner)
    for was, now in zip(before, planner._heap, strict=True):
        assert np.array_equal(was, now)


if __name__ == "__main__":  # pragma: no cover
    sys.exit(pytest.main([__file__, "-q"]))
