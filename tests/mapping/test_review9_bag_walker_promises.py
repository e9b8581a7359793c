"""Review 9: the ROS 1 chunk walker's order and header-field checks (found by mutation testing).

When rosbags refuses a bag (a damaged index), the readers walk its chunks
themselves (``_walk_ros1``); their results are documented "in bag (record-time)
order", and ``_record`` refuses "a cut or lying length", naming the record.
"""

from __future__ import annotations

import struct
from pathlib import Path

import pytest

from navkit.mapping.io import read_bag_imu
from navkit.mapping.io._bags import _Corrupt, _record, _walk_ros1

pytest.importorskip("rosbags")
from rosbags.rosbag1 import Writer as Writer1

from ros1_imu_messages import IMU, STORE, imu_message


def test_the_chunk_walker_yields_messages_in_record_time_order(tmp_path: Path) -> None:
    # Messages recorded out of time order within a chunk (record times 3 s, 1 s,
    # 2 s): the walker, like rosbags' reader, gives them by record time.
    path = tmp_path / "shuffled.bag"
    with Writer1(path) as writer:
        conn = writer.add_connection("/imu", IMU, typestore=STORE)
        for seconds in (3, 1, 2):
            ns = seconds * 10**9
            writer.write(conn, ns, STORE.serialize_ros1(imu_message(ns, ns / 1e9), IMU))
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
