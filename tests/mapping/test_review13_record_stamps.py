"""Bag and CARMEN records refuse times float64 would round (review 13, ROS stamps).

An epoch stamp in integer nanoseconds (1.78e18, beyond 2**53) was stored as a float
that merged neighbours 1 ns apart into one time (a ``dt`` of 0), and a float32
epoch stamp is 128 s coarse; both are refused with the message
``PlanarFusion`` gives, naming the field.
"""

from __future__ import annotations

from typing import Any

import numpy as np
import pytest

from navkit.mapping.io import BagImu, BagOdometry, CarmenLog

NS = 1_780_000_000_123_456_789


def _odometry(times: Any, record_times: Any) -> BagOdometry:
    n = len(times)
    return BagOdometry(
        "/odom", "odom", "base_link", times, record_times, np.zeros((n, 3)),
        np.tile([0.0, 0.0, 0.0, 1.0], (n, 1)), np.zeros((n, 3)), np.zeros((n, 6, 6)),
        np.zeros((n, 6, 6)),
    )  # fmt: skip


def _imu(times: Any, record_times: Any) -> BagImu:
    n = len(times)
    return BagImu(
        "/imu", "imu_link", times, record_times, np.tile([0.0, 0.0, 0.0, 1.0], (n, 1)),
        np.zeros((n, 3)), np.zeros((n, 3)), np.zeros((n, 3, 3)), np.zeros((n, 3, 3)),
        np.zeros((n, 3, 3)),
    )  # fmt: skip


def _carmen(times: Any) -> CarmenLog:
    return CarmenLog(times=times, scans=(), laser_poses=(), robot_poses=(), odometry=())


SECONDS = [1.78e9, 1.78e9 + 0.01]


@pytest.mark.parametrize("make", [_odometry, _imu], ids=["BagOdometry", "BagImu"])
@pytest.mark.parametrize("field", ["times", "record_times"])
def test_bag_records_refuse_integer_nanoseconds(make: Any, field: str) -> None:
    stamps = np.array([NS, NS + 1], dtype=np.int64)
    args = (stamps, SECONDS) if field == "times" else (SECONDS, stamps)
    refusal = rf"^{field}, element 0, must be a time in seconds.*2\*\*53"
    with pytest.raises(ValueError, match=refusal):
        make(*args)
    # The same stamps in float64 seconds are accepted and keep their order.
    record = make(SECONDS, SECONDS)
    assert np.diff(getattr(record, field))[0] > 0


@pytest.mark.parametrize("make", [_odometry, _imu], ids=["BagOdometry", "BagImu"])
def test_bag_records_refuse_float32_epoch_stamps(make: Any) -> None:
    with pytest.raises(ValueError, match=r"^times, element 0, must resolve time to 1 ms"):
        make(np.array(SECONDS, dtype=np.float32), SECONDS)
    # float32 times fine to 1 ms (under 2**14 s) are still read.
    small = np.array([0.25, 0.5], dtype=np.float32)
    assert make(small, small).times.tolist() == [0.25, 0.5]


def test_carmen_log_refuses_times_float64_would_round() -> None:
    with pytest.raises(ValueError, match=r"^times, element 0, must be a time in seconds"):
        _carmen([NS])
    with pytest.raises(ValueError, match=r"^times, element 0, must resolve time to 1 ms"):
        _carmen(np.array([1.78e9], dtype=np.float32))
