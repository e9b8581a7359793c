"""The process-wide locks of the map files and the simulator's world, across fork.

A lock held by another thread when the process forks would stay held in the
child, where that thread does not exist; :class:`ForkSafeLock` is made anew
there. Its users: ``atomic_paths``' renames, ``read_map``'s warning filters,
``World``'s shapely queries.
"""

from __future__ import annotations

import os
import sys
import threading

import pytest

from navkit._shared import files
from navkit._shared.locks import ForkSafeLock
from navkit.mapping.io import _map_files
from navkit.sim import _world

pytestmark = pytest.mark.skipif(
    not hasattr(os, "fork") or sys.platform != "linux", reason="needs os.fork"
)


def _child_takes(lock: ForkSafeLock) -> int:
    """Exit status of a forked child taking ``lock`` (0: took it; 3: it was held)."""
    pid = os.fork()
    if pid == 0:  # the child: leave at once, no pytest teardown here
        took = lock._lock.acquire(timeout=5.0)
        os._exit(0 if took else 3)
    _, status = os.waitpid(pid, 0)
    return os.waitstatus_to_exitcode(status)


@pytest.mark.parametrize(
    "lock",
    [files.RENAME_LOCK, _map_files._WARNINGS_LOCK, _world._GEOS_LOCK, ForkSafeLock()],
    ids=["renames", "warnings", "geos", "new"],
)
def test_a_child_forked_while_another_thread_holds_the_lock_can_take_it(
    lock: ForkSafeLock,
) -> None:
    inside, leave = threading.Event(), threading.Event()

    def hold() -> None:
        with lock:
            inside.set()
            leave.wait(30)

    worker = threading.Thread(target=hold)
    worker.start()
    try:
        assert inside.wait(30)
        assert not lock._lock.acquire(blocking=False)  # held here, by the worker
        assert _child_takes(lock) == 0
    finally:
        leave.set()
        worker.join(30)
    with lock:  # and free again here once the worker let go
        pass


def test_a_reentrant_lock_is_taken_twice_by_one_thread_and_a_plain_one_is_not() -> None:
    again = ForkSafeLock(reentrant=True)
    with again, again:
        pass
    plain = ForkSafeLock()
    with plain:
        assert not plain._lock.acquire(blocking=False)
