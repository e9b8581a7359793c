"""A noise-free replica of the CARMEN aces building, for the scan-matching tests.

Review 53's SCANMATCH tests and review 54's figures of the mapping guide measure
the mapper on the same replica; one builder keeps them on one world.
"""

from __future__ import annotations

import math

import numpy as np
from shapely.geometry import MultiLineString

from navkit.mapping import LaserScan
from navkit.mapping.io import CarmenLog
from navkit.sim import Lidar, World


def replica_scans(log: CarmenLog) -> list[LaserScan]:
    """Noise-free scans at the corrected poses of a world drawn from every 5th scan
    (neighbouring returns within 0.3 m and 20 m of the sensor joined by walls)."""
    walls = []
    for scan, pose in list(zip(log.scans, log.laser_poses, strict=True))[::5]:
        ranges = scan.ranges
        ok = scan.valid_mask() & (ranges < 20.0)
        angles = pose.theta + scan.angle_min + np.arange(len(ranges)) * scan.angle_increment
        x = pose.x + ranges * np.cos(angles)
        y = pose.y + ranges * np.sin(angles)
        for i in range(len(ranges) - 1):
            if ok[i] and ok[i + 1] and math.hypot(x[i + 1] - x[i], y[i + 1] - y[i]) < 0.3:
                walls.append(((x[i], y[i]), (x[i + 1], y[i + 1])))
    world = World(MultiLineString(walls))
    lidar = Lidar(n_beams=180, fov=math.radians(179.0), range_max=50.0, noise=None)
    return [lidar.scan(world, pose) for pose in log.laser_poses]
