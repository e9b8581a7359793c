"""diff-astar's ScanLocalizer places the beams by the LiDAR's mount (review 46, LEFTOVERS).

The localiser took a scan's sensor-frame points as the robot's: a LiDAR
mounted off the robot's centre, or turned, was matched as if it sat at the
centre facing forward, and the pose it found was the sensor's, not the
robot's, with no word said. The points are now ``scan.to_points(lidar.mount)``.
"""

from __future__ import annotations

import math
import sys
from pathlib import Path

import numpy as np
import pytest

from navkit.geometry import Pose2D
from navkit.kinematics import DiffDrive
from navkit.mapping import OccupancyGrid
from navkit.sim import EncoderReading, Lidar, ScanReading, World
from navkit.sim.scenarios._diff_astar_localizer import LikelihoodField, ScanLocalizer

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from house_localizer import assert_pulls_a_wrong_start_back


def _room() -> OccupancyGrid:
    """A 4 m x 3 m room of 0.05 m cells, walled, with a block (every direction constrained)."""
    occupied = np.zeros((60, 80), dtype=bool)
    occupied[[0, -1], :] = True
    occupied[:, [0, -1]] = True
    occupied[40:48, 55:70] = True  # y 2.0-2.4 m, x 2.75-3.5 m
    return OccupancyGrid.from_occupancy(occupied, resolution=0.05)


def _matched(lidar: Lidar, truth: Pose2D, start: Pose2D) -> Pose2D:
    """The localiser's pose after one scan taken by ``lidar`` on a robot at ``truth``."""
    grid = _room()
    world = World(grid=grid)
    loc = ScanLocalizer(
        LikelihoodField.from_grid(grid), DiffDrive(track=0.3, wheel_radius=0.05), lidar,
        ticks_per_rev=1024, bits=16, start=start, prior_sigma_xy=0.2, prior_sigma_theta=0.2,
        iterations=20,
    )  # fmt: skip
    loc.observe(0.0, EncoderReading(0.0, np.array([0, 0])))
    loc.observe(0.0, ScanReading(0.0, lidar.scan(world, truth)))
    loc.observe(0.0, EncoderReading(0.0, np.array([0, 0])))  # the encoders caught up
    assert loc.matches == 1
    return loc.pose


@pytest.mark.parametrize(
    "mount",
    [(0.3, 0.0, 0.0), (-0.2, 0.15, 0.0), (0.0, 0.0, math.pi / 2), (0.25, -0.1, -2.5)],
)
def test_a_mounted_lidar_finds_the_robots_pose(mount: tuple[float, float, float]) -> None:
    truth = Pose2D(1.5, 1.2, 0.3)
    start = Pose2D(1.53, 1.18, 0.32)  # odometry a little off
    found = _matched(Lidar(noise=None, mount=mount), truth, start)
    assert math.hypot(found.x - truth.x, found.y - truth.y) < 0.01, (found, mount)
    assert abs(math.remainder(found.theta - truth.theta, math.tau)) < 0.01, (found, mount)


def test_the_centred_lidar_is_matched_as_before() -> None:
    # The default mount: the sensor-frame points are the robot's, and the
    # same scan matched through an explicit zero mount gives the same pose.
    truth = Pose2D(1.5, 1.2, 0.3)
    start = Pose2D(1.53, 1.18, 0.32)
    plain = _matched(Lidar(noise=None), truth, start)
    zero = _matched(Lidar(noise=None, mount=(0.0, -0.0, 0.0)), truth, start)
    assert plain == zero
    assert math.hypot(plain.x - truth.x, plain.y - truth.y) < 0.01


def test_the_scenarios_house_with_a_mounted_lidar() -> None:
    # The scenario's own map and localiser, the scanner 0.2 m ahead and turned:
    # scans at a standing robot pull a wrong start back onto the robot's pose.
    assert_pulls_a_wrong_start_back(Lidar(noise=None, mount=(0.2, 0.05, 0.3)))
