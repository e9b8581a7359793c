"""The OccupancyGrid writer lock where the constructor did not make it, across fork, in deepcopy.

Found by the fresh-eyes review of the grid lock (session 22): a grid built by
``__new__`` (as a subclass's own constructor may) had no lock, so
``integrate_scan`` and ``copy()`` raised ``AttributeError: _lock``; a child
forked while another thread wrote a scan (held the lock) waited for ever on
its first scan or copy; and ``copy.deepcopy`` copied the log-odds without the
lock (half a scan); and a signal handler copying the grid (saving the map
on Ctrl-C) waited for ever when it ran, as handlers do, at the return of the
main thread's ray casting, whose lock that thread still held. The lock is now
made on first need, anew in a forked child, and re-entrant, and ``deepcopy``
copies the log-odds under it, as ``copy()`` does.
"""

from __future__ import annotations

import copy
import os
import signal
import subprocess
import sys
import textwrap
import threading
import time

import numpy as np
import pytest

from navkit._shared.jit import jit_disabled
from navkit.mapping import LaserScan, OccupancyGrid, integrate_scan
from subprocess_probe import probe_outcome
from thread_runs import free_elsewhere, room_scan

_SLOTS = (
    "_logodds", "_resolution", "_origin", "_origin_x", "_origin_y", "_origin_yaw",
    "_occupied_thresh", "_free_thresh",
)  # fmt: skip


def _grid() -> OccupancyGrid:
    return OccupancyGrid.empty(width=4.0, height=3.0, resolution=0.05, origin=(-2.0, -1.5, 0.0))


def _scan(seed: int) -> LaserScan:
    return room_scan(seed, beams=90, lowest=0.9)


class _Built(OccupancyGrid):
    """A subclass with a constructor of its own that does not call ``__init__``."""

    __slots__ = ()

    @classmethod
    def like(cls, other: OccupancyGrid) -> _Built:
        grid = cls.__new__(cls)
        for name in _SLOTS:
            value = getattr(other, name)
            object.__setattr__(grid, name, value.copy() if name == "_logodds" else value)
        return grid


def test_a_grid_built_by_new_takes_scans_and_copies() -> None:
    reference = _grid()
    built = _Built.like(reference)
    assert integrate_scan(built, _scan(0), (0.1, 0.0, 0.0)) > 0
    integrate_scan(reference, _scan(0), (0.1, 0.0, 0.0))
    assert built.logodds.tobytes() == reference.logodds.tobytes()
    twin = built.copy()
    assert type(twin) is _Built and twin.logodds.tobytes() == built.logodds.tobytes()
    assert copy.deepcopy(built).logodds.tobytes() == built.logodds.tobytes()


def test_threads_asking_for_a_new_lock_at_once_get_one_lock() -> None:
    for _ in range(20):
        grid = _Built.like(_grid())
        barrier = threading.Barrier(4)
        locks: list[object] = []

        def take(
            grid: OccupancyGrid = grid,
            barrier: threading.Barrier = barrier,
            locks: list[object] = locks,
        ) -> None:
            barrier.wait()
            locks.append(grid._writer_lock())

        threads = [threading.Thread(target=take) for _ in range(4)]
        for th in threads:
            th.start()
        for th in threads:
            th.join()
        assert len(locks) == 4 and all(lock is locks[0] for lock in locks)


def test_deepcopy_waits_for_a_scan_being_written() -> None:
    grid = _grid()
    integrate_scan(grid, _scan(1), (0.0, 0.0, 0.0))
    copies: list[OccupancyGrid] = []
    with grid._writer_lock():  # a writer mid-scan
        th = threading.Thread(target=lambda: copies.append(copy.deepcopy(grid)))
        th.start()
        th.join(0.2)
        assert not copies  # it waits for the scan to end
    th.join()
    assert copies[0].logodds.tobytes() == grid.logodds.tobytes()
    assert copies[0]._writer_lock() is not grid._writer_lock()


def test_deepcopy_keeps_shared_references_shared() -> None:
    grid = _grid()
    twin_a, twin_b = copy.deepcopy([grid, grid])
    assert twin_a is twin_b and twin_a is not grid
    assert not np.shares_memory(twin_a._logodds, grid._logodds)
    assert twin_a._logodds.flags.writeable  # the grid's own storage, written in place
    integrate_scan(twin_a, _scan(2), (0.0, 0.0, 0.0))
    assert not grid.logodds.any()


@pytest.mark.skipif(not hasattr(os, "fork") or sys.platform != "linux", reason="needs os.fork")
@pytest.mark.filterwarnings("ignore::DeprecationWarning")  # 3.12+: fork with threads
def test_a_child_forked_mid_scan_writes_and_copies() -> None:
    grid = _grid()
    integrate_scan(grid, _scan(3), (0.0, 0.0, 0.0))  # compiled before the fork
    holding, release = threading.Event(), threading.Event()

    def writer() -> None:  # holds the lock as a thread mid-scan does
        with grid._writer_lock():
            holding.set()
            release.wait()

    th = threading.Thread(target=writer)
    th.start()
    holding.wait()
    try:
        pid = os.fork()
        if pid == 0:  # the child: leave at once, no pytest teardown here
            try:
                ok = integrate_scan(grid, _scan(4), (0.0, 0.0, 0.0)) > 0 and grid.copy() is not None
                os._exit(0 if ok else 4)
            except BaseException:
                os._exit(5)
        deadline = time.monotonic() + 60.0
        while True:
            done, status = os.waitpid(pid, os.WNOHANG)
            if done:
                break
            if time.monotonic() > deadline:  # it waits for the lock for ever: stop it
                os.kill(pid, 9)
                os.waitpid(pid, 0)
                pytest.fail("the forked child waited for a lock held by a thread it lacks")
            time.sleep(0.01)
        assert os.waitstatus_to_exitcode(status) == 0
    finally:
        release.set()
        th.join()
    assert free_elsewhere(grid._writer_lock())  # the parent's lock: free again


def test_the_thread_holding_the_lock_takes_it_again() -> None:
    grid = _grid()
    integrate_scan(grid, _scan(5), (0.0, 0.0, 0.0))
    lock = grid._writer_lock()
    with lock:
        assert lock.acquire(blocking=False)  # a plain Lock: False, and copy() waits for ever
        lock.release()
        assert grid.copy().logodds.tobytes() == grid.logodds.tobytes()
        assert not free_elsewhere(lock)
    assert free_elsewhere(lock)


_HANDLER_COPIES = """
import json, math, signal
import numpy as np
from navkit.mapping import LaserScan, OccupancyGrid, integrate_scan

grid = OccupancyGrid.empty(width=30.0, height=30.0, resolution=0.01, origin=(-15.0, -15.0, 0.0))
beams = 8000
scan = LaserScan(np.full(beams, 12.0), angle_min=-math.pi, angle_increment=2 * math.pi / beams,
                 range_min=0.1, range_max=20.0)
integrate_scan(grid, scan, (0.0, 0.0, 0.0))
copies = []
# A handler saving the map: it runs in the main thread as the kernel returns,
# inside integrate_scan's hold of the lock.
def save(signum, frame):
    copies.append(grid.copy())
    signal.setitimer(signal.ITIMER_REAL, 0.005)  # the next one once this returns

signal.signal(signal.SIGALRM, save)
signal.setitimer(signal.ITIMER_REAL, 0.005)
while len(copies) < 5:
    integrate_scan(grid, scan, (0.0, 0.0, 0.0))
signal.setitimer(signal.ITIMER_REAL, 0.0)
print(json.dumps(len(copies)))
"""


@pytest.mark.skipif(not hasattr(signal, "setitimer"), reason="needs signal.setitimer")
@pytest.mark.skipif(jit_disabled(), reason="NUMBA_DISABLE_JIT=1: 8,000-beam scans as Python")
def test_a_signal_handler_copying_the_grid_during_a_scan_returns() -> None:
    try:
        assert probe_outcome(textwrap.dedent(_HANDLER_COPIES), timeout=120) >= 5
    except subprocess.TimeoutExpired:
        pytest.fail("the handler's copy() waited for the lock its own thread held")
