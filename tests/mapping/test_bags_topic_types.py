"""A bag topic recorded with several message types: each reader reads its own type only.

A ROS 1 bag may hold one topic with connections of different types (a topic name
reused by another node). The readers, the auto-selection of a topic and
``bag_topics`` treat each (topic, type) as a stream of its own, alike through rosbags
and through navkit's chunk walker (used for bags whose index rosbags refuses).
"""

from __future__ import annotations

import struct
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import Any

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from hypothesis_twins import slow_twin
from navkit.mapping.io import bag_topics, read_bag_imu, read_bag_odometry, read_bag_scans

pytest.importorskip("rosbags")
from rosbags.rosbag1 import Reader as Reader1
from rosbags.rosbag1 import Writer as Writer1
from rosbags.rosbag2 import Writer as Writer2
from rosbags.typesys import Stores, get_typestore

IMU = "sensor_msgs/msg/Imu"
ODOM = "nav_msgs/msg/Odometry"
SCAN = "sensor_msgs/msg/LaserScan"
STORES = {"ros1": get_typestore(Stores.ROS1_NOETIC), "ros2": get_typestore(Stores.ROS2_HUMBLE)}

#: reader per type, and the value each result carries of a message's label
READERS: dict[str, tuple[Callable[..., Any], Callable[[Any], list[float]]]] = {
    IMU: (read_bag_imu, lambda r: r.angular_velocities[:, 2].tolist()),
    ODOM: (read_bag_odometry, lambda r: r.poses[:, 0].tolist()),
    SCAN: (read_bag_scans, lambda r: [s.ranges[0] for s in r.scans]),
}


def message(store: Any, msgtype: str, ns: int, label: float) -> Any:
    """A message of ``msgtype`` stamped ``ns`` carrying ``label`` in the field its reader
    reports (Imu: angular velocity z; Odometry: x; LaserScan: first range)."""
    T = store.types
    sec, nanosec = divmod(ns, 1_000_000_000)
    fields = {name for name, _ in store.fielddefs["std_msgs/msg/Header"][1]}
    extra = {"seq": 0} if "seq" in fields else {}
    stamp = T["builtin_interfaces/msg/Time"](sec=sec, nanosec=nanosec)
    head = T["std_msgs/msg/Header"](stamp=stamp, frame_id="f", **extra)
    vec = T["geometry_msgs/msg/Vector3"]
    if msgtype == IMU:
        return T[IMU](
            header=head,
            orientation=T["geometry_msgs/msg/Quaternion"](x=0.0, y=0.0, z=0.0, w=1.0),
            orientation_covariance=np.zeros(9),
            angular_velocity=vec(x=0.0, y=0.0, z=label),
            angular_velocity_covariance=np.zeros(9),
            linear_acceleration=vec(x=0.0, y=0.0, z=9.8),
            linear_acceleration_covariance=np.zeros(9),
        )
    if msgtype == ODOM:
        pose = T["geometry_msgs/msg/Pose"](
            position=T["geometry_msgs/msg/Point"](x=label, y=0.0, z=0.0),
            orientation=T["geometry_msgs/msg/Quaternion"](x=0.0, y=0.0, z=0.0, w=1.0),
        )
        still = vec(x=0.0, y=0.0, z=0.0)
        twist = T["geometry_msgs/msg/Twist"](linear=still, angular=still)
        return T[ODOM](
            header=head,
            child_frame_id="base_link",
            pose=T["geometry_msgs/msg/PoseWithCovariance"](pose=pose, covariance=np.zeros(36)),
            twist=T["geometry_msgs/msg/TwistWithCovariance"](twist=twist, covariance=np.zeros(36)),
        )
    return T[SCAN](
        header=head,
        angle_min=0.0,
        angle_max=0.5,
        angle_increment=0.5,
        time_increment=0.0,
        scan_time=0.1,
        range_min=0.1,
        range_max=100.0,
        ranges=np.array([label, 1.0], dtype=np.float32),
        intensities=np.array([], dtype=np.float32),
    )


# (topic, type, callerid) of each connection, and the connection of each message in
# record order (message k is recorded at (k + 1) s and labelled k + 1).
Layout = tuple[list[tuple[str, str, str]], list[int]]


def write(path: Path, kind: str, layout: Layout) -> Path:
    conns, order = layout
    store = STORES["ros2" if kind == "ros2" else "ros1"]
    if kind == "ros2":
        with Writer2(path, version=9) as writer2:
            # ROS 2 has no caller ids: connections differing only by theirs are one.
            added: dict[tuple[str, str], Any] = {}
            for t, ty, _ in conns:
                if (t, ty) not in added:
                    added[(t, ty)] = writer2.add_connection(t, ty, typestore=store)
            handles = [added[(t, ty)] for t, ty, _ in conns]
            for k, c in enumerate(order):
                msg = message(store, conns[c][1], (k + 1) * 10**9, k + 1.0)
                writer2.write(handles[c], (k + 1) * 10**9, store.serialize_cdr(msg, conns[c][1]))
        return path
    with Writer1(path) as writer1:
        handles = [
            writer1.add_connection(t, ty, typestore=store, callerid=caller)
            for t, ty, caller in conns
        ]
        for k, c in enumerate(order):
            msg = message(store, conns[c][1], (k + 1) * 10**9, k + 1.0)
            writer1.write(handles[c], (k + 1) * 10**9, store.serialize_ros1(msg, conns[c][1]))
    if kind == "ros1-walked":
        path.write_bytes(lengthen_index_data(path.read_bytes()))
        # rosbags refuses it (with whatever it raises): navkit's walker reads it.
        refused = False
        try:
            Reader1(path).open()
        except Exception:
            refused = True
        assert refused
    return path


def records(data: bytes) -> Iterator[tuple[bytes, int, int]]:
    """(header, data position, data length) of each top-level record of a ROS 1 bag."""
    pos = len(b"#ROSBAG V2.0\n")
    while pos < len(data):
        (header_len,) = struct.unpack_from("<I", data, pos)
        (data_len,) = struct.unpack_from("<I", data, pos + 4 + header_len)
        yield data[pos + 4 : pos + 4 + header_len], pos + 8 + header_len, data_len
        pos += 8 + header_len + data_len


def lengthen_index_data(data: bytes) -> bytes:
    """The bag with its first index data record 12 bytes longer than its entries (as in
    the real demo.bag), the bag header's index position moved to match (one chunk)."""
    chunks = [h for h, _, _ in records(data) if b"op=\x05" in h]
    assert len(chunks) == 1  # only the index position moves
    _, at, length = next(r for r in records(data) if b"op=\x04" in r[0])
    out = bytearray(data[: at + length] + bytes(12) + data[at + length :])
    struct.pack_into("<I", out, at - 4, length + 12)
    field = out.index(b"index_pos=") + len(b"index_pos=")
    struct.pack_into("<Q", out, field, struct.unpack_from("<Q", out, field)[0] + 12)
    return bytes(out)


def expected_streams(layout: Layout) -> dict[tuple[str, str], list[float]]:
    """Labels of each (topic, type) stream in record order, the reference."""
    conns, order = layout
    streams: dict[tuple[str, str], list[float]] = {(t, ty): [] for t, ty, _ in conns}
    for k, c in enumerate(order):
        streams[conns[c][:2]].append(k + 1.0)
    return streams


def check(path: Path, layout: Layout) -> None:
    streams = expected_streams(layout)
    topics = sorted({t for t, _ in streams})
    entries: dict[str, Any] = {}
    for topic in topics:
        pairs = tuple(sorted((ty, len(v)) for (t, ty), v in streams.items() if t == topic))
        entries[topic] = pairs[0] if len(pairs) == 1 else pairs
    assert bag_topics(path) == entries
    for msgtype, (reader, labels) in READERS.items():
        having = [t for t in topics if (t, msgtype) in streams]
        for topic in topics:
            if topic in having:
                got = reader(path, topic=topic)
                assert got.topic == topic
                assert labels(got) == streams[(topic, msgtype)]
                np.testing.assert_array_equal(got.record_times, streams[(topic, msgtype)])
                np.testing.assert_array_equal(got.times, streams[(topic, msgtype)])
            else:
                with pytest.raises(ValueError, match=f"holds .* messages, not {msgtype}"):
                    reader(path, topic=topic)
        if len(having) == 1:
            assert labels(reader(path)) == streams[(having[0], msgtype)]
        else:
            with pytest.raises(ValueError, match="several" if having else f"no {msgtype} topic"):
                reader(path)


KINDS = ["ros1", "ros1-walked", "ros2"]


@pytest.mark.parametrize("kind", KINDS)
def test_one_topic_recorded_as_imu_and_as_odometry(tmp_path: Path, kind: str) -> None:
    # Before: bag_topics gave ("nav_msgs/msg/Odometry", 5) for /x, read_bag_imu(topic="/x")
    # was refused as "holds Odometry" and read_bag_odometry failed decoding the Imu messages.
    layout: Layout = ([("/x", IMU, "/imu_node"), ("/x", ODOM, "/odom_node")], [0, 1, 0, 1, 1])
    path = write(tmp_path / ("bag" if kind == "ros2" else "x.bag"), kind, layout)
    assert bag_topics(path) == {"/x": ((ODOM, 3), (IMU, 2))}
    imu = read_bag_imu(path, topic="/x")
    assert imu.angular_velocities[:, 2].tolist() == [1.0, 3.0]
    odom = read_bag_odometry(path)  # the only topic with Odometry messages
    assert odom.topic == "/x" and odom.poses[:, 0].tolist() == [2.0, 4.0, 5.0]
    with pytest.raises(ValueError, match="holds nav_msgs/msg/Odometry and sensor_msgs/msg/Imu"):
        read_bag_scans(path, topic="/x")
    with pytest.raises(ValueError, match=r"topics: /x \(nav_msgs/msg/Odometry, sensor_msgs"):
        read_bag_scans(path)
    check(path, layout)


TOPIC_NAMES = ["/a", "/b", "/c"]


@st.composite
def layouts(draw: st.DrawFn) -> Layout:
    conns = draw(
        st.lists(
            st.tuples(
                st.sampled_from(TOPIC_NAMES),
                st.sampled_from([IMU, ODOM, SCAN]),
                st.sampled_from(["/n1", "/n2"]),
            ),
            min_size=1,
            max_size=6,
            unique=True,
        )
    )
    order = draw(st.lists(st.integers(0, len(conns) - 1), max_size=12))
    return conns, order


@pytest.mark.parametrize("kind", KINDS)
@settings(max_examples=10, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(layout=layouts())
def test_readers_read_each_topic_and_type_as_written(
    tmp_path_factory: pytest.TempPathFactory, kind: str, layout: Layout
) -> None:
    folder = tmp_path_factory.mktemp("bags")
    if kind == "ros1-walked" and not layout[1]:
        layout = (layout[0], [0])  # the damage needs an index data record
    check(write(folder / ("bag" if kind == "ros2" else "x.bag"), kind, layout), layout)


test_readers_read_each_topic_and_type_as_written_thoroughly = slow_twin(
    test_readers_read_each_topic_and_type_as_written, max_examples=25
)
