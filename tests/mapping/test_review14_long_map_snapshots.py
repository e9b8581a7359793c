"""What a map written into for days shares with it, and what it does not.

``integrate_scan`` updates a grid in place. ``OccupancyGrid.logodds`` is a live
(read-only) view of it, so a node that keeps one to compare maps over time must
copy it; ``ScanMatcher.pyramid``'s coarse levels are copies, so a matcher that
keeps one pyramid while scans are written into the finest grid would match
against coarse levels of the old map: the docs say to build it again.
"""

from __future__ import annotations

import numpy as np

from navkit.mapping import LaserScan, OccupancyGrid, ScanMatcher, integrate_scan


def _wall_scan() -> LaserScan:
    return LaserScan([1.0] * 21, angle_min=-1.0, angle_increment=0.1, range_min=0.05,
                     range_max=10.0)  # fmt: skip


def test_logodds_is_a_live_view_and_a_copy_of_it_is_a_snapshot() -> None:
    grid = OccupancyGrid(np.zeros((64, 64), dtype=np.float32), resolution=0.1,
                         origin=(-3.2, -3.2, 0.0))  # fmt: skip
    view = grid.logodds
    snapshot = grid.logodds.copy()
    integrate_scan(grid, _wall_scan(), (0.0, 0.0, 0.0))
    assert not view.flags.writeable
    np.testing.assert_array_equal(view, grid.logodds)
    assert not np.array_equal(view, snapshot)
    assert not snapshot.any()


def test_the_coarse_levels_keep_the_map_as_it_was_and_a_new_pyramid_sees_the_change() -> None:
    grid = OccupancyGrid(np.zeros((64, 64), dtype=np.float32), resolution=0.1,
                         origin=(-3.2, -3.2, 0.0))  # fmt: skip
    matcher = ScanMatcher(levels=3)
    old = matcher.pyramid(grid)
    before = [level.logodds.copy() for level in old]
    integrate_scan(grid, _wall_scan(), (0.0, 0.0, 0.0))
    assert old[0] is grid  # the finest level is the grid itself: live
    assert not np.array_equal(old[0].logodds, before[0])
    for level, was in zip(old[1:], before[1:], strict=True):
        np.testing.assert_array_equal(level.logodds, was)  # copies made then
    fresh = matcher.pyramid(grid)
    for level, was in zip(fresh[1:], before[1:], strict=True):
        assert level.logodds.max() > was.max()  # the wall's hits reach every level
