"""Review 9: the ROS 1 chunk walker's order and header-field checks (found by mutation testing).

When rosbags refuses a bag (a damaged index), the readers walk its chunks
themselves (``_walk_ros1``); their results are documented "in bag (record-time)
order", and ``_record`` refuses "a cut or lying length", naming the record.
"""

from __future__ import annotations

import struct
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from navkit.mapping.io import read_bag_imu
from navkit.mapping.io._bags import _Corrupt, _record, _walk_ros1

pytest.importorskip("rosbags")
from rosbags.rosbag1 import Writer as Writer1
from rosbags.typesys import Stores, get_typestore

IMU = "sensor_msgs/msg/Imu"
STORE = get_typestore(Stores.ROS1_NOETIC)


def _imu(ns: int) -> Any:
    T = STORE.types
    stamp = T["builtin_interfaces/msg/Time"](sec=ns // 10**9, nanosec=ns % 10**9)
    vec = T["geometry_msgs/msg/Vector3"]
    return T[IMU](
        header=T["std_msgs/msg/Header"](seq=0, stamp=stamp, frame_id="imu"),
        orientation=T["geometry_msgs/msg/Quaternion"](x=0.0, y=0.0, z=0.0, w=1.0),
        orientation_covariance=np.zeros(9),
        angular_velocity=vec(x=0.0, y=0.0, z=ns / 1e9),  # labels the message
        angular_velocity_covariance=np.zeros(9),
        linear_acceleration=vec(x=0.0, y=0.0, z=9.8),
        linear_acceleration_covariance=np.zeros(9),
    )


def test_the_chunk_walker_yields_messages_in_record_time_order(tmp_path: Path) -> None:
    # Messages recorded out of time order within a chunk (record times 3 s, 1 s,
    # 2 s): the walker, like rosbags' reader, gives them by record time.
    path = tmp_path / "shuffled.bag"
    with Writer1(path) as writer:
        conn = writer.add_connection("/imu", IMU, typestore=STORE)
        for seconds in (3, 1, 2):
            ns = seconds * 10**9
            writer.write(conn, ns, STORE.serialize_ros1(_imu(ns), IMU))
    walked = [ns for ns, _ in _walk_ros1(path).messages("/imu", IMU)]
    assert walked == [1 * 10**9, 2 * 10**9, 3 * 10**9]
    # The public reader (through rosbags here) agrees.
    readings = read_bag_imu(path)
    assert readings.record_times.tolist() == [1.0, 2.0, 3.0]
    assert readings.angular_velocities[:, 2].tolist() == [1.0, 2.0, 3.0]


def test_a_header_field_longer_than_its_header_is_refused() -> None:
    # A field that declares more bytes than its record header holds is a lying
    # length: refused naming the record, not read as a shorter field.
    header = struct.pack("<I", 40) + b"op=\x02"
    block = struct.pack("<I", len(header)) + header + struct.pack("<I", 3) + b"abc"
    with pytest.raises(_Corrupt, match="record at byte 0: malformed record header field"):
        _record(block, 0)
    sound = struct.pack("<I", 4) + b"op=\x02"
    block = struct.pack("<I", len(sound)) + sound + struct.pack("<I", 3) + b"abc"
    assert _record(block, 0) == ({"op": b"\x02"}, b"abc", len(block))
