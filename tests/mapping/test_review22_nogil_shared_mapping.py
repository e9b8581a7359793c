"""Mapping objects shared by threads whose kernels now really run at once.

Ray casting into a map, scan matching and ``cells_near`` release the GIL
(``navkit._shared.jit.RELEASES_GIL``). A ``ScanMatcher``, its pyramid, a
``LaserScan`` and a grid only read may be shared: threads matching at once
get the lone call's result bit for bit. ``integrate_scan`` on a grid of each
thread's own is unaffected by the others, and threads writing one grid take
turns (its lock): they lose no update. The mapping guide's snapshot pattern
still holds with the writer's kernel running beside the readers: every
snapshot a reader plans on is the map after a whole number of scans.
(test_review22_gridlock_shared_writers.py tests the lock itself.)
"""

from __future__ import annotations

import threading
from typing import Any

import numpy as np

from navkit.mapping import LaserScan, OccupancyGrid, ScanMatcher, integrate_scan
from navkit.planning import MapPlanner
from thread_runs import concurrent_results, room_scan

THREADS = 4


def _scan(seed: int, beams: int = 360) -> LaserScan:
    return room_scan(seed, beams=beams, lowest=0.97)


def _empty() -> OccupancyGrid:
    return OccupancyGrid.empty(width=7.0, height=5.0, resolution=0.05, origin=(-3.5, -2.5, 0.0))


def _check(calls: list[Any]) -> None:
    serial = [call() for call in calls]
    for results in concurrent_results(calls, rounds=3):
        assert results == serial


def test_one_scan_matcher_pyramid_and_scan_shared_by_threads() -> None:
    room = _empty()
    for k in range(5):
        integrate_scan(room, _scan(k), (0.0, 0.0, 0.0))
    matcher = ScanMatcher(search_distance=0.2, search_angle=0.2)
    levels = matcher.pyramid(room)
    scan = _scan(9)
    guesses = [(0.08, -0.05, 0.04), (-0.1, 0.06, -0.05), (0.03, 0.09, 0.08), (0.0, 0.0, 0.0)]

    def match(i: int) -> tuple[Any, ...]:
        res = matcher.match(levels if i % 2 else room, scan, guesses[i])
        return (res.pose, res.covariance.tobytes(), res.iterations, res.score, res.converged)

    _check([lambda i=i: match(i) for i in range(THREADS)])
    assert all(match(i)[4] for i in range(THREADS))  # they converge: real matches


def test_integrate_scan_into_each_threads_grid() -> None:
    scans = [_scan(k) for k in range(6)]

    def build(i: int) -> bytes:
        grid = _empty()
        for k, scan in enumerate(scans):
            integrate_scan(grid, scan, (0.1 * i, -0.05 * k, 0.02 * k))
        return grid.logodds.tobytes()

    _check([lambda i=i: build(i) for i in range(THREADS)])


def test_integrate_scan_by_threads_into_one_grid_loses_no_update() -> None:
    # Without the grid's lock the kernels interleaved and 0 to 3 cells of 10 runs
    # lost an update. Increments exact in float32 and a clamp that never binds make
    # the result independent of the order the threads took turns in.
    scans = [_scan(k, beams=1440) for k in range(THREADS)]
    model = {"hit": 1.0, "miss": -0.25, "clamp": (-1e6, 1e6)}
    serial = _empty()
    for k, scan in enumerate(scans):
        integrate_scan(serial, scan, (0.02 * k, -0.03 * k, 0.01 * k), **model)
    for _ in range(3):
        grid = _empty()
        calls = [
            lambda k=k, scan=scan, g=grid: integrate_scan(
                g, scan, (0.02 * k, -0.03 * k, 0.01 * k), **model
            )
            for k, scan in enumerate(scans)
        ]
        concurrent_results(calls, rounds=1)
        assert grid.logodds.tobytes() == serial.logodds.tobytes()


def test_cells_near_on_one_grid() -> None:
    grid = _empty()
    integrate_scan(grid, _scan(0), (0.0, 0.0, 0.0))
    rng = np.random.default_rng(3)
    hits = [rng.uniform(-3.0, 3.0, (300, 2)) for _ in range(THREADS)]
    _check([lambda h=h: grid.cells_near(h, robot_radius=0.3).tobytes() for h in hits])


def test_snapshots_stay_whole_while_the_writer_casts_beside_the_readers() -> None:
    scans = [_scan(k, beams=1440) for k in range(12)]
    maps = [_empty()]
    for scan in scans:  # the map after each number of scans
        grid = maps[-1].copy()
        integrate_scan(grid, scan, (0.0, 0.0, 0.0))
        maps.append(grid)
    live = _empty()
    lock = threading.Lock()
    latest = [live.copy()]
    used: list[np.ndarray] = []
    done = threading.Event()
    together = threading.Barrier(3)

    def writer() -> None:
        together.wait()
        for scan in scans:
            integrate_scan(live, scan, (0.0, 0.0, 0.0))
            snapshot = live.copy()  # taken by the only writer: whole
            with lock:
                latest[0] = snapshot
        done.set()

    def reader() -> None:
        together.wait()
        while True:
            last = done.is_set()
            with lock:
                grid = latest[0]
            used.append(grid.logodds.copy())
            MapPlanner(grid, unknown_cost=1.0).plan((0.0, 0.0), (1.0, 0.5))
            if last:
                return

    threads = [threading.Thread(target=f) for f in (writer, reader, reader)]
    for th in threads:
        th.start()
    for th in threads:
        th.join()
    np.testing.assert_array_equal(live.logodds, maps[-1].logodds)
    assert used
    for seen in used:
        assert any(np.array_equal(seen, m.logodds) for m in maps)
