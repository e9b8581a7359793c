"""ScanMapper.pose: the latest row of the trajectory, as a Pose2D."""

from __future__ import annotations

import math

import numpy as np

from navkit.geometry import Pose2D
from navkit.mapping import LaserScan, ScanMapper


def _room_scan() -> LaserScan:
    angles = np.linspace(-math.pi, math.pi, 120, endpoint=False)
    ranges = 2.0 / np.maximum(np.abs(np.cos(angles)), np.abs(np.sin(angles)))
    return LaserScan(ranges, angle_min=-math.pi, angle_increment=2 * math.pi / 120,
                     range_min=0.1, range_max=10.0)


def test_pose_follows_the_trajectory() -> None:
    mapper = ScanMapper(resolution=0.1, pose=(0.3, -0.2, 0.1))
    assert mapper.pose == Pose2D(0.3, -0.2, 0.1)
    scan = _room_scan()
    for odometry in [None, (0.35, -0.18, 0.12), (0.4, -0.15, 0.15)]:
        mapper.update(scan, odometry=odometry)
        assert isinstance(mapper.pose, Pose2D)
        assert np.array_equal(mapper.pose.as_array(), mapper.trajectory[-1])
