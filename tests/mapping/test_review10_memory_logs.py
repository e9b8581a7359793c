"""Peak memory of reading ROS bags and CARMEN logs (review 10).

Robots log for hours: a reader should need about what it returns, not a
Python object tree per message. The bounds are peak NumPy and Python
allocations (tracemalloc) relative to the arrays returned, with margin. The
earlier readers held every deserialized message until the arrays were built (an
Odometry message some 5 kB for 83 numbers: 7x the result's 672 bytes, an Imu
8x), and a CARMEN log's ODOM lines as tuples of floats and its readings twice.
"""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from memory_peak import peak_bytes
from navkit.mapping.io import bag_topics, read_bag_imu, read_bag_odometry, read_carmen

BAGS = "robot-localization-odom-imu-bags"


def _array_bytes(record: Any) -> int:
    return sum(
        value.nbytes
        for name in record.__dataclass_fields__
        if isinstance(value := getattr(record, name), np.ndarray)
    )


@pytest.mark.parametrize("reader", [read_bag_odometry, read_bag_imu])
def test_bag_readers_do_not_hold_every_message(
    shared_data: Path, reader: Callable[[Path], Any]
) -> None:
    pytest.importorskip("rosbags")
    bag = shared_data / BAGS / "test2.bag"
    opening, _ = peak_bytes(lambda: bag_topics(bag))  # rosbags' own index of the whole bag
    peak, result = peak_bytes(lambda: reader(bag))
    assert len(result) > 3000
    # The result, the rows it is copied from and one message at a time: the
    # earlier reader needed 6.4 (odometry) and 8.2 (IMU) times the result.
    assert peak - opening < 5.0 * _array_bytes(result)


def test_carmen_log_holds_its_readings_once(shared_data: Path) -> None:
    path = shared_data / "carmen-logs" / "aces-corrected.log.gz"
    peak, log = peak_bytes(lambda: read_carmen(path))
    assert len(log) > 400 and log.odometry.shape[0] > 7000
    needed = sum(scan.ranges.nbytes for scan in log.scans) + log.odometry.nbytes
    # The readings and ODOM records once, with the scans' and poses' own objects
    # (the earlier reader needed 4.2 times as much).
    assert peak < 2.8 * needed
