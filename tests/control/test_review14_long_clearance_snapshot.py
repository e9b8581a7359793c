"""RegulatedPurePursuit's map clearance is a snapshot taken when the tracker is built.

A node running for days may keep writing scans into the map it gave the
tracker (``integrate_scan`` updates a grid in place). The distances to the
obstacles are computed once, from the map as it was then; the docs say so, and
point to a function (which reads the live map at every step) or a new tracker.
"""

from __future__ import annotations

import numpy as np

from navkit.control import RegulatedPurePursuit
from navkit.mapping import LaserScan, OccupancyGrid, integrate_scan

PATH = [[0.0, 0.0], [4.0, 0.0]]


def _free_map() -> OccupancyGrid:
    return OccupancyGrid(np.full((100, 100), -2.0, dtype=np.float32), resolution=0.1,
                         origin=(-5.0, -5.0, 0.0))  # fmt: skip


def _wall_ahead(grid: OccupancyGrid) -> None:
    """Write a wall 0.3 m ahead of the origin into ``grid`` (in place)."""
    scan = LaserScan([0.3] * 11, angle_min=-0.5, angle_increment=0.1, range_min=0.05,
                     range_max=10.0)  # fmt: skip
    for _ in range(5):
        integrate_scan(grid, scan, (0.0, 0.0, 0.0))


def _speed(tracker: RegulatedPurePursuit) -> float:
    tracker.set_path(PATH)
    return tracker.step((0.0, 0.0, 0.0), 0.05).vx


def test_a_map_changed_after_the_tracker_was_built_is_not_seen() -> None:
    grid = _free_map()
    built_before = RegulatedPurePursuit(clearance=grid)
    live = RegulatedPurePursuit(clearance=lambda x, y: _distance(grid, x, y))
    free_speed = _speed(built_before)
    assert _speed(live) == free_speed
    _wall_ahead(grid)
    assert grid.occupied().any()
    # The snapshot: the wall written since does not slow the tracker built before.
    assert _speed(built_before) == free_speed
    # A function reads the live map, and a tracker built now sees the wall.
    assert _speed(live) < free_speed
    assert _speed(RegulatedPurePursuit(clearance=grid)) < free_speed


def _distance(grid: OccupancyGrid, x: float, y: float) -> float:
    """Centre-to-centre distance from (x, y)'s cell to the nearest occupied cell (m)."""
    occupied = np.argwhere(grid.occupied())
    if occupied.size == 0:
        return float("inf")
    cell = grid.world_to_cell(np.array([x, y]))
    return float(np.min(np.hypot(*(occupied - cell).T)) * grid.resolution)
