"""A simulated LiDAR and its world shared by threads whose ray casts now run at once.

The LiDAR's casts and the cross-track distances release the GIL
(``navkit._shared.jit.RELEASES_GIL``). One ``Lidar`` and one ``World`` (walls,
a map, a moving obstacle) scanned by several threads at once, at different
times and poses, give each thread the lone call's ranges bit for bit.
"""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np
from shapely.geometry import box

from navkit.mapping import OccupancyGrid
from navkit.sim import Lidar, MovingObstacle, World
from navkit.sim._trace import cross_track
from thread_runs import concurrent_results

THREADS = 4


def _check(calls: list[Callable[[], object]]) -> None:
    serial = [call() for call in calls]
    for results in concurrent_results(calls, rounds=3):
        assert results == serial


def test_one_lidar_and_world_scanned_by_threads_at_different_times() -> None:
    occupied = np.zeros((80, 120), dtype=bool)
    occupied[30:50, 60:64] = True
    grid = OccupancyGrid.from_occupancy(occupied, resolution=0.05)
    ball = MovingObstacle.constant_velocity(0.2, start_xy=(5.0, 1.0), velocity_xy=(-0.4, 0.1))
    world = World(box(0.0, 0.0, 6.0, 4.0).exterior, grid=grid, moving=[ball])
    lidar = Lidar(n_beams=1080, range_max=10.0)  # the paper's noise: seeded draws

    def scans(i: int) -> list[bytes]:
        return [
            lidar.scan(world, (1.0 + 0.3 * i, 1.0 + 0.1 * k, 0.2 * k - math.pi / 3),
                       t=0.5 * i + 0.1 * k, seed=i * 10 + k).ranges.tobytes()
            for k in range(5)
        ]  # fmt: skip

    _check([lambda i=i: scans(i) for i in range(THREADS)])


def test_cross_track_on_one_path() -> None:
    path = np.cumsum(np.random.default_rng(1).normal(0.0, 0.1, (3000, 2)), axis=0)
    points = [np.random.default_rng(i).normal(0.0, 2.0, (2000, 2)) for i in range(THREADS)]
    _check([lambda p=p: cross_track(p, path).tobytes() for p in points])
