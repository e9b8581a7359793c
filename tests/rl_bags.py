"""robot_localization's odometry and IMU bags in shared/data, as the fusion tests read them.

Review 46's bag-stream and configuration tests each read a bag the same way
(and skipped when it is absent): now here, with the IMU's mount (review 47).
"""

from __future__ import annotations

import math
from pathlib import Path

import pytest

from navkit.geometry import rpy_to_quaternion
from navkit.mapping.io import BagImu, BagOdometry, read_bag_imu, read_bag_odometry

FOLDER = "robot-localization-odom-imu-bags"

#: base_link -> imu_link of each bag's upstream launch file: test1's IMU is turned
#: (roll +pi/2, yaw -pi/2), test2's is base_link's own.
MOUNTS = {"test1": rpy_to_quaternion(math.pi / 2, 0.0, -math.pi / 2), "test2": None}


def read_bag(shared_data: Path, name: str) -> tuple[BagOdometry, BagImu, BagImu]:
    """Bag ``name``'s wheel odometry, its IMU as recorded and in base_link.

    The calling test skips when the bag is not in ``shared_data``.
    """
    path = shared_data / FOLDER / f"{name}.bag"
    if not path.is_file():
        pytest.skip(f"{path} is not available")
    imu = read_bag_imu(path, topic="/imu/data")
    mount = MOUNTS[name]
    return read_bag_odometry(path), imu, imu if mount is None else imu.to_base(mount)
