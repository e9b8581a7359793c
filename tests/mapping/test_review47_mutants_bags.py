"""Review 47 mutation review: the streaming ROS 1 chunk walker's order.

A bag not in record-time order is gathered and sorted by record time, stably
(chunk order, then order in the chunk, as rosbags gives them). Sorting the
(record time, raw bytes) pairs themselves, which breaks ties by the bytes,
survived every test (mutant b08).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from navkit.mapping.io import read_bag_imu
from navkit.mapping.io._bags import _walk_ros1

pytest.importorskip("rosbags")
from rosbags.rosbag1 import Writer as Writer1

from ros1_imu_messages import IMU, STORE, imu_message


def test_messages_of_one_record_time_keep_their_order_in_an_unordered_bag(
    tmp_path: Path,
) -> None:
    # Record times 3 s, 1 s, 1 s: the bag is out of order, so the walker sorts. The
    # two messages at 1 s keep the order they were recorded in, 1.0 then 2.0,
    # although 2.0's bytes sort first (little-endian: ... 00 40 below ... f0 3f).
    labels = [(3, 3.0), (1, 1.0), (1, 2.0)]
    raws = [STORE.serialize_ros1(imu_message(s * 10**9, z), IMU) for s, z in labels]
    assert bytes(raws[2]) < bytes(raws[1])
    path = tmp_path / "ties.bag"
    with Writer1(path) as writer:
        conn = writer.add_connection("/imu", IMU, typestore=STORE)
        for (seconds, _), raw in zip(labels, raws, strict=True):
            writer.write(conn, seconds * 10**9, raw)
    walked = list(_walk_ros1(path).messages("/imu", IMU))
    assert [ns for ns, _ in walked] == [10**9, 10**9, 3 * 10**9]
    assert [bytes(raw) for _, raw in walked] == [bytes(raws[1]), bytes(raws[2]), bytes(raws[0])]
    # The public reader (through rosbags here) agrees.
    assert read_bag_imu(path).angular_velocities[:, 2].tolist() == [1.0, 2.0, 3.0]


def test_a_stream_of_two_connections_reads_chunks_holding_either(tmp_path: Path) -> None:
    # Two recorders (caller ids) on one topic and type make one stream of two
    # connections; each message is a chunk of its own, alternately of either. A
    # chunk is read when it holds a message of any of the stream's connections
    # (mutant b06 read only those holding messages of all).
    path = tmp_path / "two_callers.bag"
    with Writer1(path) as writer:
        writer.chunk_threshold = 1  # each message closes its chunk
        first = writer.add_connection("/imu", IMU, typestore=STORE, callerid="/first")
        second = writer.add_connection("/imu", IMU, typestore=STORE, callerid="/second")
        for k in range(4):
            ns = (k + 1) * 10**9
            conn = first if k % 2 == 0 else second
            writer.write(conn, ns, STORE.serialize_ros1(imu_message(ns, float(k)), IMU))
    bag = _walk_ros1(path)
    assert bag.counts == {("/imu", IMU): 4}
    walked = list(bag.messages("/imu", IMU))
    assert [ns for ns, _ in walked] == [k * 10**9 for k in (1, 2, 3, 4)]


def test_a_topic_of_two_types_gives_each_type_its_own_messages(tmp_path: Path) -> None:
    # One topic recorded with two message types (two connections): a stream is a
    # (topic, type) pair, so the IMU stream holds no Odometry message (mutant b21
    # selected the stream's connections by topic alone).
    odom = "nav_msgs/msg/Odometry"
    T = STORE.types
    path = tmp_path / "two_types.bag"
    with Writer1(path) as writer:
        imu = writer.add_connection("/mixed", IMU, typestore=STORE)
        other = writer.add_connection("/mixed", odom, typestore=STORE)
        for k in range(4):
            ns = (k + 1) * 10**9
            if k % 2 == 0:
                writer.write(imu, ns, STORE.serialize_ros1(imu_message(ns, float(k)), IMU))
            else:
                msg = T[odom](
                    header=T["std_msgs/msg/Header"](
                        seq=k,
                        stamp=T["builtin_interfaces/msg/Time"](sec=k + 1, nanosec=0),
                        frame_id="odom",
                    ),
                    child_frame_id="base_link",
                    pose=T["geometry_msgs/msg/PoseWithCovariance"](
                        pose=T["geometry_msgs/msg/Pose"](
                            position=T["geometry_msgs/msg/Point"](x=0.0, y=0.0, z=0.0),
                            orientation=T["geometry_msgs/msg/Quaternion"](
                                x=0.0, y=0.0, z=0.0, w=1.0
                            ),
                        ),
                        covariance=np.zeros(36),
                    ),
                    twist=T["geometry_msgs/msg/TwistWithCovariance"](
                        twist=T["geometry_msgs/msg/Twist"](
                            linear=T["geometry_msgs/msg/Vector3"](x=0.0, y=0.0, z=0.0),
                            angular=T["geometry_msgs/msg/Vector3"](x=0.0, y=0.0, z=0.0),
                        ),
                        covariance=np.zeros(36),
                    ),
                )
                writer.write(other, ns, STORE.serialize_ros1(msg, odom))
    bag = _walk_ros1(path)
    assert bag.counts == {("/mixed", IMU): 2, ("/mixed", odom): 2}
    assert [ns for ns, _ in bag.messages("/mixed", IMU)] == [10**9, 3 * 10**9]
    assert [ns for ns, _ in bag.messages("/mixed", odom)] == [2 * 10**9, 4 * 10**9]
