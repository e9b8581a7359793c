"""ScanMapper.map read by another thread while one thread updates: whole scans only.

The ray casting releases the GIL, and ``ScanMapper`` wrote its scans into its
levels without their grids' writer locks, which ``OccupancyGrid.copy`` (and
so ``ScanMapper.map``) holds: a map read meanwhile could hold part of a scan.
Each level is now written holding its grid's lock. Waiting for a lock may be
interrupted (Ctrl-C while another thread copies the map): the level is then
tried again, so an update still writes its scan into every level or none.
"""

from __future__ import annotations

import threading
from typing import Any

import numpy as np
import pytest
from room_scans import room_scan

from navkit._shared.jit import jit_disabled
from navkit.mapping import OccupancyGrid, ScanMapper, ScanMatcher

_POSES = [(0.04 * k, 0.02 * k, 0.02 * k) for k in range(10)]


# Dense scans at 1 cm cells: each level's ray casting takes milliseconds, while
# a copy of the finest level takes far less. As Python (NUMBA_DISABLE_JIT=1) an
# update takes 10 to 60 s: the races are run compiled only.
compiled_only = pytest.mark.skipif(
    jit_disabled(), reason="NUMBA_DISABLE_JIT=1: ray casting as Python, seconds a scan"
)


def _mapper(resolution: float = 0.01) -> ScanMapper:
    matcher = ScanMatcher(
        levels=2, translation_weight=1.0, rotation_weight=1.0,
        search_distance=0.1, search_angle=0.1,
    )  # fmt: skip
    return ScanMapper(resolution=resolution, min_distance=0.0, min_angle=0.0, matcher=matcher)


def _scans(beams: int = 2880) -> list[Any]:
    return [room_scan(*pose, half=3.0, beams=beams) for pose in _POSES]


@compiled_only
def test_maps_read_during_updates_hold_whole_scans() -> None:
    scans = _scans()
    serial = _mapper()
    expected = {serial.map.logodds.tobytes()}
    for pose, scan in zip(_POSES, scans, strict=True):
        serial.update(scan, odometry=pose)
        expected.add(serial.map.logodds.tobytes())  # the finest level after each scan
    live = _mapper()
    live.update(scans[0], odometry=_POSES[0])  # the levels exist before the race
    seen: list[bytes] = []
    done = threading.Event()
    together = threading.Barrier(2)
    errors: list[BaseException] = []

    def writer() -> None:
        try:
            together.wait()
            for pose, scan in zip(_POSES[1:], scans[1:], strict=True):
                live.update(scan, odometry=pose)
        except BaseException as exc:  # reported by the main thread
            errors.append(exc)
        finally:
            done.set()

    def reader() -> None:
        together.wait()
        while True:
            last = done.is_set()
            seen.append(live.map.logodds.tobytes())
            if last:
                return

    threads = [threading.Thread(target=f) for f in (writer, reader)]
    for th in threads:
        th.start()
    for th in threads:
        th.join()
    assert not errors
    # The reader copied the map during the updates (at least once before the last
    # finished: each update holds the finest level's lock for most of its time, so
    # a loaded machine allows about one copy per update, not many).
    assert len(seen) >= 2
    assert seen[-1] == serial.map.logodds.tobytes()
    assert all(s in expected for s in seen)


@compiled_only
def test_an_update_waits_for_the_finest_level_lock() -> None:
    # What makes the copies whole: no scan goes into a level whose lock is held.
    mapper = _mapper()
    scans = _scans()
    mapper.update(scans[0], odometry=_POSES[0])
    finest = mapper._levels[0]
    before = finest.logodds.copy()
    finished = threading.Event()

    def update() -> None:
        mapper.update(scans[1], odometry=_POSES[1])
        finished.set()

    with finest._writer_lock():
        th = threading.Thread(target=update)
        th.start()
        assert not finished.wait(0.3)
        assert np.array_equal(finest.logodds, before)
    th.join()
    assert finished.is_set() and not np.array_equal(finest.logodds, before)


class _InterruptedOnce:
    """A writer lock whose first wait is interrupted (Ctrl-C while another thread holds it)."""

    def __init__(self, lock: Any) -> None:
        self.lock = lock
        self.waits = 0

    def __enter__(self) -> None:
        self.waits += 1
        if self.waits == 1:
            raise KeyboardInterrupt
        self.lock.__enter__()

    def __exit__(self, *exc: object) -> None:
        self.lock.__exit__(*exc)


@pytest.mark.parametrize("level", [0, 1])
def test_an_interrupted_wait_for_a_lock_still_writes_every_level(
    level: int, monkeypatch: pytest.MonkeyPatch
) -> None:
    mapper, twin = _mapper(0.1), _mapper(0.1)
    scans = _scans(beams=180)[:3]
    for pose, scan in zip(_POSES[:2], scans[:2], strict=True):
        mapper.update(scan, odometry=pose)
        twin.update(scan, odometry=pose)
    twin.update(scans[2], odometry=_POSES[2])
    target = mapper._levels[level]
    stand_in = _InterruptedOnce(target._writer_lock())
    real = OccupancyGrid._writer_lock

    def writer_lock(grid: OccupancyGrid) -> Any:
        return stand_in if grid is target else real(grid)

    monkeypatch.setattr(OccupancyGrid, "_writer_lock", writer_lock)
    with pytest.raises(KeyboardInterrupt):
        mapper.update(scans[2], odometry=_POSES[2])
    monkeypatch.undo()
    assert stand_in.waits == 2  # interrupted, then taken
    for ours, theirs in zip(mapper._levels, twin._levels, strict=True):
        assert ours.logodds.tobytes() == theirs.logodds.tobytes()
    assert mapper.trajectory.tolist() == twin.trajectory.tolist()
