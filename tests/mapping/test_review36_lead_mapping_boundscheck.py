"""navkit's mapping kernels run with numba's bounds checks on (review 36, lead).

numba does not check array indices by default: a kernel indexing past an array's end
reads or writes other memory silently (a mutant of the ray cast's scratch window did,
and only a guard-band test saw it: review 36, MUTANT7). As the simulator's and the EKF's
kernels already are (review 35), the ray casts (both walks, from inside, on the edge of
and outside a rotated grid, with inf and NaN ranges), cell conversions, inflation and
costmaps, rasterising, and a ScanMapper with its multi-level ScanMatcher run here in a
fresh process with ``NUMBA_BOUNDSCHECK=1`` and an empty cache of its own, where any
out-of-bounds index raises ``IndexError`` (the runner first checks that they are on).
"""

from __future__ import annotations

import textwrap
from pathlib import Path

import pytest

from subprocess_probe import bounds_checked

_SCRIPT = textwrap.dedent(
    """
    import numpy as np
    from navkit.geometry import Pose2D
    from navkit.mapping import (LaserScan, OccupancyGrid, ScanMapper, ScanMatcher, costmap,
                                integrate_scan, rasterize_polygons, traversal_costs)
    from shapely.geometry import box


    rng = np.random.default_rng(7)
    # A small rotated grid; beams from inside, on the edge and outside, long and short.
    grid = OccupancyGrid(np.zeros((30, 45)), resolution=0.1, origin=Pose2D(-1.0, -0.5, 0.3))
    angles = np.linspace(-np.pi, np.pi, 91, endpoint=False)
    for pose in [(0.5, 0.5, 0.2), (-1.0, -0.5, 0.0), (-3.0, 2.0, -1.0), (3.0, 3.0, 2.5)]:
        ranges = rng.uniform(0.05, 9.0, angles.size)
        ranges[::7] = np.inf
        ranges[::11] = np.nan
        scan = LaserScan(ranges, angle_min=-np.pi, angle_increment=angles[1] - angles[0],
                         range_min=0.02, range_max=8.0)
        for exact in (False, True):
            integrate_scan(grid, scan, pose, exact=exact)
    cells = grid.world_to_cell(rng.uniform(-5, 5, (50, 2)))
    xy = grid.cell_to_world(np.array([[0, 0], [29, 44], [15, 20]]))
    inside = grid.contains(rng.uniform(-5, 5, (50, 2)))
    for radius in (0.0, 0.05, 0.35, 3.0):
        traversal_costs(grid, robot_radius=min(radius, 0.2), inflation_radius=max(radius, 0.2))
        costmap(grid, robot_radius=0.1, inflation_radius=max(radius, 0.1), inflate_unknown=True,
                inflate_around_unknown=True)
    rasterize_polygons([box(0, 0, 1, 0.3), box(-0.5, 0.7, 0.2, 1.9)], bounds=(-1, -1, 2, 2),
                       resolution=0.07)
    # Mapping with scan matching: a corridor seen from a moving robot.
    walls = np.zeros((60, 120), dtype=bool)
    walls[[5, 54], :] = True
    walls[:, [3, 116]] = True
    world = OccupancyGrid.from_occupancy(walls, resolution=0.05)
    mapper = ScanMapper(resolution=0.05, matcher=ScanMatcher(levels=3))
    for k in range(12):
        pose = Pose2D(1.0 + 0.1 * k, 1.5, 0.02 * k)
        beams = np.linspace(-2.0, 2.0, 181)
        ranges = np.empty(beams.size)
        for i, a in enumerate(beams):  # brute-force march on the truth map
            d = 0.0
            while d < 10.0:
                p = (pose.x + d * np.cos(pose.theta + a), pose.y + d * np.sin(pose.theta + a))
                r, c = world.world_to_cell(np.array([p]))[0]
                if not (0 <= r < 60 and 0 <= c < 120) or walls[r, c]:
                    break
                d += 0.01
            ranges[i] = d
        mapper.update(LaserScan(ranges, angle_min=-2.0, angle_increment=beams[1] - beams[0],
                                range_min=0.05, range_max=9.0), odometry=pose)
    print("in bounds")
    """
)


@pytest.mark.slow  # exhaustive (review 42: the default suite's budget)
def test_mapping_kernels_stay_in_bounds(tmp_path: Path) -> None:
    assert bounds_checked(_SCRIPT, tmp_path) == ["in bounds"]
