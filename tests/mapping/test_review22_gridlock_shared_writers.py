"""Threads writing scans into one OccupancyGrid take turns (the grid's lock).

The ray casting releases the GIL, so two threads integrating scans into one
grid used to run their kernels at once and interleave cell by cell: 0 to 3
cells of 10 runs lost an update. Every grid now has a lock that
``integrate_scan`` holds around its kernel and ``copy()`` holds while it
copies: concurrent writers add whole scans, one after another, and a copy is
the grid after a whole number of scans. The lock is the grid's own: copies,
pickles and deep copies get a new one, and pickles carry none.
"""

from __future__ import annotations

import copy
import pickle
import threading

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from navkit.mapping import LaserScan, OccupancyGrid, integrate_scan
from thread_runs import concurrent_results, free_elsewhere, room_scan

THREADS = 4

# Increments and bounds under which float32 sums are exact (multiples of 1/4,
# far from 2**24) and the clamp never binds: the grid after a set of scans is
# the same whatever order they were written in, so a concurrent run must equal
# the serial one bit for bit, and any lost update shows.
EXACT = {"hit": 1.0, "miss": -0.25, "clamp": (-1e6, 1e6)}


def _scan(seed: int, beams: int = 1440) -> LaserScan:
    return room_scan(seed, beams=beams, lowest=0.9)


def _empty() -> OccupancyGrid:
    return OccupancyGrid.empty(width=7.0, height=5.0, resolution=0.02, origin=(-3.5, -2.5, 0.0))


def _pose(i: int, k: int) -> tuple[float, float, float]:
    return (0.05 * i - 0.1, 0.03 * k - 0.05, 0.01 * (i + k))


def test_threads_writing_one_grid_lose_no_update() -> None:
    scans = [_scan(k) for k in range(4)]
    serial = _empty()
    for i in range(THREADS):
        for k, scan in enumerate(scans):
            integrate_scan(serial, scan, _pose(i, k), **EXACT)
    for _ in range(3):
        shared = _empty()

        def write(i: int, grid: OccupancyGrid = shared) -> int:
            return sum(
                integrate_scan(grid, scan, _pose(i, k), **EXACT) for k, scan in enumerate(scans)
            )

        counts = concurrent_results([lambda i=i: write(i) for i in range(THREADS)], rounds=1)[0]
        assert all(n > 1000 for n in counts)  # real scans: each updates thousands of cells
        assert shared.logodds.tobytes() == serial.logodds.tobytes()


def test_the_method_takes_the_lock_too() -> None:
    scans = [_scan(k) for k in range(4)]
    serial = _empty()
    for i in range(THREADS):
        for k, scan in enumerate(scans):
            serial.integrate_scan(scan, _pose(i, k), exact=True, **EXACT)
    shared = _empty()

    def write(i: int) -> None:
        for k, scan in enumerate(scans):
            shared.integrate_scan(scan, _pose(i, k), exact=True, **EXACT)

    concurrent_results([lambda i=i: write(i) for i in range(THREADS)], rounds=1)
    assert shared.logodds.tobytes() == serial.logodds.tobytes()


def test_default_model_concurrent_writers_give_whole_scans_in_some_order() -> None:
    # With the default clamp the order of the scans matters near the bounds:
    # the concurrent result must be the serial result of one of the orders.
    scans = [_scan(k, beams=720) for k in range(3)]
    poses = [_pose(i, i) for i in range(3)]
    orders = [(0, 1, 2), (0, 2, 1), (1, 0, 2), (1, 2, 0), (2, 0, 1), (2, 1, 0)]
    results = set()
    for order in orders:
        grid = _empty()
        for j in order:
            integrate_scan(grid, scans[j], poses[j])
        results.add(grid.logodds.tobytes())
    for _ in range(3):
        shared = _empty()
        calls = [lambda j=j, g=shared: integrate_scan(g, scans[j], poses[j]) for j in range(3)]
        concurrent_results(calls, rounds=1)
        assert shared.logodds.tobytes() in results


def test_copy_while_a_writer_casts_is_a_whole_number_of_scans() -> None:
    scans = [_scan(k) for k in range(8)]
    maps = [_empty()]
    for k, scan in enumerate(scans):  # the map after each number of scans
        grid = maps[-1].copy()
        integrate_scan(grid, scan, _pose(0, k))
        maps.append(grid)
    expected = {m.logodds.tobytes() for m in maps}
    live = _empty()
    seen: list[bytes] = []
    done = threading.Event()
    together = threading.Barrier(2)

    def writer() -> None:
        together.wait()
        for k, scan in enumerate(scans):
            integrate_scan(live, scan, _pose(0, k))
        done.set()

    def reader() -> None:
        together.wait()
        while True:
            last = done.is_set()
            seen.append(live.copy().logodds.tobytes())  # the reader's own snapshot
            if last:
                return

    threads = [threading.Thread(target=f) for f in (writer, reader)]
    for th in threads:
        th.start()
    for th in threads:
        th.join()
    assert seen[-1] == maps[-1].logodds.tobytes()
    assert all(s in expected for s in seen)


def test_a_writer_waits_for_the_lock() -> None:
    # The lock is what the writers hold: a scan cannot be written while it is taken.
    grid = _empty()
    finished = threading.Event()

    def write() -> None:
        integrate_scan(grid, _scan(0, beams=90), (0.0, 0.0, 0.0))
        finished.set()

    with grid._writer_lock():
        th = threading.Thread(target=write)
        th.start()
        assert not finished.wait(0.2)
        assert not grid.logodds.any()
    th.join()
    assert finished.is_set() and grid.logodds.any()


class _Tagged(OccupancyGrid):
    __slots__ = ("tag",)


def _tagged() -> _Tagged:
    grid = _Tagged(np.zeros((20, 30)), resolution=0.1, origin=(-1.0, -1.0, 0.0))
    grid.tag = "kitchen"
    return grid


@pytest.mark.parametrize("make", [_empty, _tagged], ids=["grid", "subclass"])
@pytest.mark.parametrize(
    "duplicate",
    [
        lambda g: g.copy(),
        copy.copy,
        copy.deepcopy,
        *(lambda g, p=p: pickle.loads(pickle.dumps(g, protocol=p)) for p in range(6)),
    ],
    ids=["copy", "copy.copy", "deepcopy", *(f"pickle{p}" for p in range(6))],
)
def test_copies_and_pickles_have_a_lock_of_their_own(make: object, duplicate: object) -> None:
    grid = make()  # type: ignore[operator]
    integrate_scan(grid, _scan(1, beams=90), (0.0, 0.0, 0.0))
    twin = duplicate(grid)  # type: ignore[operator]
    assert type(twin) is type(grid)
    assert twin._writer_lock() is not grid._writer_lock() and free_elsewhere(twin._writer_lock())
    assert twin.logodds.tobytes() == grid.logodds.tobytes()
    assert getattr(twin, "tag", None) == getattr(grid, "tag", None)
    with grid._writer_lock():  # the original's lock taken: the twin still writes
        integrate_scan(twin, _scan(2, beams=90), (0.1, 0.0, 0.0))
    assert twin.logodds.tobytes() != grid.logodds.tobytes()


def test_pickles_carry_no_lock_and_old_pickles_load() -> None:
    grid = _empty()
    integrate_scan(grid, _scan(3, beams=90), (0.0, 0.0, 0.0))
    instance, slots = grid.__getstate__()  # type: ignore[misc]
    assert instance is None and "_lock" not in slots and "_logodds" in slots
    # A pickle written before the lock existed holds this same state: it loads,
    # with a lock of its own, and takes scans.
    old = OccupancyGrid.__new__(OccupancyGrid)
    old.__setstate__((None, slots))
    assert old.logodds.tobytes() == grid.logodds.tobytes() and free_elsewhere(old._writer_lock())
    assert integrate_scan(old, _scan(4, beams=90), (0.0, 0.0, 0.0)) > 0
    for protocol in range(6):
        assert b"_lock" not in pickle.dumps(grid, protocol=protocol)


@settings(max_examples=10, deadline=None)
@given(seeds=st.lists(st.integers(0, 2**16), min_size=2, max_size=THREADS))
def test_any_scans_written_at_once_equal_them_written_in_turn(seeds: list[int]) -> None:
    scans = [_scan(s, beams=360) for s in seeds]
    serial = _empty()
    for i, scan in enumerate(scans):
        integrate_scan(serial, scan, _pose(i, i), **EXACT)
    shared = _empty()
    calls = [
        lambda i=i, scan=scan: integrate_scan(shared, scan, _pose(i, i), **EXACT)
        for i, scan in enumerate(scans)
    ]
    concurrent_results(calls, rounds=1)
    assert shared.logodds.tobytes() == serial.logodds.tobytes()
