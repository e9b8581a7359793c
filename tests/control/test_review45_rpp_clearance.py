"""``RegulatedPurePursuit(clearance=grid)`` reads the grid's ``obstacle_distance`` (review 45).

The tracker ran SciPy's Euclidean distance transform on the whole grid itself
(34 bytes a cell at its peak: 136 MiB for a 2048 x 2048 map, 9 GiB for the
largest grid). It now takes ``OccupancyGrid.obstacle_distance``, mapping's
banded transform: the same distances bit for bit, so the same regulation,
at 9 bytes a cell and a band.
"""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np
from scipy import ndimage

from memory_peak import peak_bytes
from navkit.control import RegulatedPurePursuit
from navkit.geometry import Pose2D
from navkit.mapping import OccupancyGrid


def _scipy_clearance(grid: OccupancyGrid) -> Callable[[float, float], float]:
    """The tracker's map clearance as it was computed before, as a function of (x, y)."""
    distance = ndimage.distance_transform_edt(~grid.occupied()) * grid.resolution
    rows, cols = grid.shape

    def clearance(x: float, y: float) -> float:
        r, c = grid.world_to_cell(np.array([x, y]))
        return float(distance[r, c]) if 0 <= r < rows and 0 <= c < cols else math.inf

    return clearance


def test_regulation_on_a_map_is_the_scipy_distances_regulation_exactly() -> None:
    rng = np.random.default_rng(7)
    occupied = rng.random((60, 90)) < 0.02
    occupied[:, 45] = False  # a clear column for the path to run beside
    grid = OccupancyGrid.from_occupancy(occupied, resolution=0.05, origin=(-2.0, -1.5, 0.3))
    path = [[-1.0, -1.0], [0.5, 0.2], [1.5, -0.4]]
    by_grid = RegulatedPurePursuit(clearance=grid, clearance_distance=0.6, clearance_gain=1.0)
    by_scipy = RegulatedPurePursuit(
        clearance=_scipy_clearance(grid), clearance_distance=0.6, clearance_gain=1.0
    )
    free = RegulatedPurePursuit(clearance_distance=0.6, clearance_gain=1.0)
    slowed = 0
    for x, y, yaw in rng.uniform((-2.0, -1.5, -math.pi), (2.5, 1.5, math.pi), (200, 3)):
        commands = []
        for tracker in (by_grid, by_scipy, free):
            tracker.set_path(path)
            commands.append(tracker.step(Pose2D(x, y, yaw), 0.05))
        assert commands[0] == commands[1]
        slowed += abs(commands[0].vx) < abs(commands[2].vx)
    # The map is used: near obstacles the robot drives slower than without one.
    assert slowed > 20, slowed


def test_a_map_with_no_obstacle_does_not_regulate() -> None:
    grid = OccupancyGrid.from_occupancy(np.zeros((20, 20), dtype=bool), resolution=0.1)
    by_grid = RegulatedPurePursuit(clearance=grid)
    free = RegulatedPurePursuit()
    for tracker in (by_grid, free):
        tracker.set_path([[0.2, 0.2], [1.8, 0.2]])
    pose = Pose2D(0.2, 0.2, 0.0)
    assert by_grid.step(pose, 0.05) == free.step(pose, 0.05)


def test_building_a_tracker_on_a_large_map_holds_the_distances_and_a_band() -> None:
    # 2048 x 2048 cells: 136 MiB (34 bytes a cell) with SciPy's transform, 52 MiB now
    # (8 bytes a cell kept, the occupied mask and a band of int64 column distances).
    rows = cols = 2048
    rng = np.random.default_rng(3)
    grid = OccupancyGrid.from_occupancy(rng.random((rows, cols)) < 0.001, resolution=0.05)
    peak, tracker = peak_bytes(lambda: RegulatedPurePursuit(clearance=grid))
    assert isinstance(tracker, RegulatedPurePursuit)
    assert peak <= 14 * rows * cols, peak / (rows * cols)
