"""CarmenLog.laser_trajectory / robot_trajectory: the log's poses as (N, 3) arrays.

Review 52's PIPELINE user took ``log.laser_poses[:, :2]`` (a tuple of Pose2D)
where the other trajectories of navkit (BagOdometry.poses, ScanMapper.trajectory,
Trace.poses) are (N, 3) arrays. The tuple stays (it pairs with the scans); the
array form is there too.
"""

from __future__ import annotations

import copy
import pickle
from pathlib import Path

import numpy as np
import pytest

from navkit.geometry import Pose2D
from navkit.mapping import LaserScan, ScanMapper
from navkit.mapping.io import CarmenLog, read_carmen


def _log() -> CarmenLog:
    scan = LaserScan(
        np.array([1.0, 2.0]), angle_min=-0.1, angle_increment=0.2, range_min=0.0, range_max=5.0
    )
    laser = (Pose2D(0.5, -1.0, 3.0), Pose2D(2.0, 1.0, -3.0))
    robot = ((0.25, -1.0, 3.0), (1.75, 1.0, -3.0))
    return CarmenLog((scan, scan), laser, robot, times=[1.0, 2.0], odometry=np.empty((0, 4)))


def test_rows_are_the_poses() -> None:
    log = _log()
    for rows, poses in ((log.laser_trajectory, log.laser_poses),
                        (log.robot_trajectory, log.robot_poses)):  # fmt: skip
        assert rows.shape == (2, 3) and rows.dtype == np.float64
        assert rows.tolist() == [[p.x, p.y, p.theta] for p in poses]
        assert not rows.flags.writeable


def test_a_fresh_array_each_access() -> None:
    log = _log()
    first = log.laser_trajectory
    assert log.laser_trajectory is not first
    assert not np.shares_memory(first, log.laser_trajectory)


def test_empty_log_gives_no_rows() -> None:
    log = CarmenLog((), (), (), times=[], odometry=[])
    assert log.laser_trajectory.shape == (0, 3)
    assert log.robot_trajectory.shape == (0, 3)


@pytest.mark.parametrize("duplicate", [copy.copy, copy.deepcopy,
                                       lambda log: pickle.loads(pickle.dumps(log))])  # fmt: skip
def test_copies_have_it_too(duplicate) -> None:  # type: ignore[no-untyped-def]
    log = _log()
    np.testing.assert_array_equal(duplicate(log).laser_trajectory, log.laser_trajectory)


def test_layout_is_scan_mappers(shared_data: Path) -> None:
    log = read_carmen(shared_data / "carmen-logs" / "intel-corrected.log.gz")
    rows = log.laser_trajectory
    assert rows.tobytes() == np.array([p.as_array() for p in log.laser_poses]).tobytes()
    # A mapper started at the first pose holds it in the same layout.
    mapper = ScanMapper(resolution=0.1, pose=log.laser_poses[0])
    mapper.update(log.scans[0])  # the first scan is placed at the start pose
    assert mapper.trajectory.tobytes() == rows[:1].tobytes()
    assert log.robot_trajectory.shape == rows.shape
