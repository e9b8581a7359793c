"""ScanMapper's map growth at scale (review 20, scale lens).

Each growth built every level's enlarged array and then handed it to the
OccupancyGrid constructor, which scanned and copied it again: a second copy of
the map at every growth, and the largest level's size added to the growth's
peak. A route that keeps leaving the map grows it every ~10 m, so the copies
add up (a 1 km corridor at 5 cm: 93 growths, 5-9 s of 18-31 s before, 2-4 s
after, and a peak RSS of 249 MiB instead of 288).
"""

from __future__ import annotations

import math
import tracemalloc

import numpy as np

from navkit.mapping import LaserScan, ScanMapper


def _ring(radius: float = 3.0) -> LaserScan:
    return LaserScan(np.full(90, radius), angle_min=-math.pi, angle_increment=2 * math.pi / 90,
                     range_min=0.1, range_max=5.0)  # fmt: skip


def test_a_growth_copies_the_map_once() -> None:
    scan = _ring()
    mapper = ScanMapper(resolution=0.05)
    mapper.update(scan, odometry=(0.0, 0.0, 0.0))
    old = [grid.logodds.copy() for grid in mapper._levels]
    old_origin = mapper.map.origin
    tracemalloc.start()
    try:
        mapper.update(scan, odometry=(12.0, 0.0, 0.0))  # beyond the +10 m edge: grows
        _, peak = tracemalloc.get_traced_memory()
    finally:
        tracemalloc.stop()
    levels = mapper._levels
    grown = sum(grid._logodds.nbytes for grid in levels)
    assert mapper.map.shape[1] > old[-1].shape[1]
    # The new levels, plus the ray casting's byte-a-cell scratch of the finest level
    # (0.19 of them); a second copy of each level (HEAD) made it 1.72.
    assert peak < 1.4 * grown, peak / grown
    # Each level is the old one, in place, with unknown cells around it, and is
    # an array of its own that the ray casting can write into.
    for grid, before in zip(levels, old, strict=True):
        arr = grid._logodds
        assert arr.dtype == np.float32 and arr.flags.c_contiguous and arr.flags.writeable
        assert arr.flags.owndata or arr.base is None or arr.base.size == arr.size
        step = grid.resolution
        dc = round((old_origin.x - grid.origin.x) / step)
        dr = round((old_origin.y - grid.origin.y) / step)
        r, c = before.shape
        inside = arr[dr : dr + r, dc : dc + c]
        # The second scan, written after the growth, lies within 3 m of x = 12 m:
        # left of x = 8.5 m the old map is unchanged.
        keep = round((8.5 - old_origin.x) / step)
        assert np.array_equal(inside[:, :keep], before[:, :keep])
        outside = arr.copy()
        outside[dr : dr + r, dc : dc + c] = 0.0
        written = np.zeros(arr.shape, dtype=bool)
        x = grid.origin.x + (np.arange(arr.shape[1]) + 0.5) * step
        written[:, np.abs(x - 12.0) < 3.5] = True
        assert not outside[~written].any()
    assert mapper.map.occupied().any()


def test_a_grown_level_takes_further_scans() -> None:
    scan = _ring()
    mapper = ScanMapper(resolution=0.1)
    # Rings 12 m apart do not overlap: each scan is written at its odometry pose.
    for x in (0.0, 12.0, 24.0, 36.0, 48.0):
        mapper.update(scan, odometry=(x, 0.0, 0.0))
    grid = mapper.map
    assert grid.width > 50.0
    assert np.array_equal(mapper.trajectory[:, 0], [0.0, 12.0, 24.0, 36.0, 48.0])
    # Every ring is in the final map: hits 3 m to each side of its centre.
    for point in ([0.0, 3.0], [24.0, -3.0], [48.0, 3.0], [48.0, -3.0]):
        r, c = grid.world_to_cell(point)
        assert grid.occupied()[r - 1 : r + 2, c - 1 : c + 2].any()
