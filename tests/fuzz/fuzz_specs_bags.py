"""Fuzz specs of the ROS bag readers (``navkit.mapping.io``) and the quaternion helpers
(``navkit.geometry``), registered on import by ``fuzz_specs.py``.

The valid bag is a tiny ROS 1 bag (one LaserScan, one Odometry, one Imu message)
built once with ``rosbags`` and copied into each case's folder.
"""

from __future__ import annotations

import functools
import math
from pathlib import Path
from typing import Any

import numpy as np
from fuzz_engine import Array, Call, FileKind, Flag, SequenceOf, Text, call, method, spec

from navkit.geometry import (
    ImuInBase,
    imu_to_base,
    quaternion_to_matrix,
    quaternion_to_yaw,
    rpy_to_quaternion,
    yaw_to_quaternion,
)
from navkit.mapping import LaserScan
from navkit.mapping.io import (
    BagImu,
    BagOdometry,
    BagScans,
    bag_topics,
    read_bag_imu,
    read_bag_odometry,
    read_bag_scans,
)

A = np.array
G = "navkit.geometry."
IO = "navkit.mapping.io."


# ------------------------------------------------------------ geometry
spec(G + "quaternion_to_yaw", lambda c: call(quaternion_to_yaw, A([[0.0, 0.0, 0.6, 0.8]])))
spec(G + "quaternion_to_matrix", lambda c: call(quaternion_to_matrix, A([0.1, 0.2, 0.3, 0.9])))
spec(G + "yaw_to_quaternion", lambda c: call(yaw_to_quaternion, A([0.5, -2.0])))
spec(G + "rpy_to_quaternion", lambda c: call(rpy_to_quaternion, A([0.1]), A([0.2]), A([0.3])))
spec(
    G + "imu_to_base",
    lambda c: call(
        imu_to_base,
        A([[0.0, 0.0, 0.6, 0.8]]),
        A([[0.0, 0.1, 0.2]]),
        A([[0.0, 9.8, 0.0]]),
        mount=A([0.5, 0.5, 0.5, 0.5]),
    ),
)
spec(
    G + "ImuInBase",
    lambda c: call(ImuInBase, A([0.0, 0.0, 0.0, 1.0]), A([0.0, 0.0, 0.1]), A([0.0, 0.0, 9.8])),
)


# ------------------------------------------------------------ bag files
def _header(store: Any, t: float, frame: str) -> Any:
    types = store.types
    stamp = types["builtin_interfaces/msg/Time"](sec=int(t), nanosec=int((t % 1) * 1e9))
    return types["std_msgs/msg/Header"](seq=0, stamp=stamp, frame_id=frame)


def _messages(store: Any, *, nan: bool = False) -> dict[str, tuple[str, Any]]:
    types = store.types
    vec = types["geometry_msgs/msg/Vector3"]
    quat = types["geometry_msgs/msg/Quaternion"](x=0.0, y=0.0, z=0.6, w=0.8)
    scan = types["sensor_msgs/msg/LaserScan"](
        header=_header(store, 1.5, "laser"),
        angle_min=-0.5,
        angle_max=0.5,
        angle_increment=0.5,
        time_increment=0.0,
        scan_time=0.1,
        range_min=0.1,
        range_max=4.0,
        ranges=A([1.0, math.inf, 2.0], dtype=np.float32),
        intensities=A([], dtype=np.float32),
    )
    pose = types["geometry_msgs/msg/Pose"](
        position=types["geometry_msgs/msg/Point"](x=math.nan if nan else 1.0, y=2.0, z=0.0),
        orientation=quat,
    )
    odom = types["nav_msgs/msg/Odometry"](
        header=_header(store, 1.6, "odom"),
        child_frame_id="base_link",
        pose=types["geometry_msgs/msg/PoseWithCovariance"](pose=pose, covariance=np.eye(6).ravel()),
        twist=types["geometry_msgs/msg/TwistWithCovariance"](
            twist=types["geometry_msgs/msg/Twist"](
                linear=vec(0.3, 0.0, 0.0), angular=vec(0, 0, 0.1)
            ),
            covariance=np.eye(6).ravel(),
        ),
    )
    imu = types["sensor_msgs/msg/Imu"](
        header=_header(store, 1.7, "imu_link"),
        orientation=quat,
        orientation_covariance=np.eye(3).ravel(),
        angular_velocity=vec(0.0, 0.0, math.nan if nan else 0.2),
        angular_velocity_covariance=np.eye(3).ravel(),
        linear_acceleration=vec(0.0, 0.0, 9.8),
        linear_acceleration_covariance=np.eye(3).ravel(),
    )
    return {
        "/scan": ("sensor_msgs/msg/LaserScan", scan),
        "/odom": ("nav_msgs/msg/Odometry", odom),
        "/imu": ("sensor_msgs/msg/Imu", imu),
    }


@functools.cache
def _bag_bytes(nan: bool = False) -> bytes:
    import tempfile

    from rosbags.rosbag1 import Writer
    from rosbags.typesys import Stores, get_typestore

    store = get_typestore(Stores.ROS1_NOETIC)
    with tempfile.TemporaryDirectory() as folder:
        path = Path(folder) / "tiny.bag"
        with Writer(path) as writer:
            for i, (topic, (msgtype, msg)) in enumerate(_messages(store, nan=nan).items()):
                conn = writer.add_connection(topic, msgtype, typestore=store)
                writer.write(conn, 1_000_000_000 + i, store.serialize_ros1(msg, msgtype))
        return path.read_bytes()


def _file(folder: Path, name: str, data: bytes) -> Path:
    path = folder / name
    path.write_bytes(data)
    return path


def _ros2_folder(folder: Path, metadata: str) -> Path:
    bag = folder / "bag2"
    bag.mkdir(exist_ok=True)
    (bag / "metadata.yaml").write_text(metadata)
    return bag


BROKEN_BAGS = [
    ("only the magic", lambda d: _file(d, "magic.bag", b"#ROSBAG V2.0\n")),
    ("truncated bag", lambda d: _file(d, "cut.bag", _bag_bytes()[:300])),
    ("bag cut in its index", lambda d: _file(d, "cut2.bag", _bag_bytes()[:-40])),
    ("magic then junk", lambda d: _file(d, "junk2.bag", b"#ROSBAG V2.0\n" + bytes(range(256)))),
    ("ROS 2 folder, junk metadata", lambda d: _ros2_folder(d, "::: not yaml [")),
    ("ROS 2 folder, empty metadata", lambda d: _ros2_folder(d, "")),
    (
        "ROS 2 folder, no storage",
        lambda d: _ros2_folder(
            d,
            "rosbag2_bagfile_information:\n  version: 4\n  storage_identifier: sqlite3\n"
            "  relative_file_paths: [missing.db3]\n  duration: {nanoseconds: 0}\n"
            "  starting_time: {nanoseconds_since_epoch: 0}\n  message_count: 0\n"
            "  topics_with_message_count: []\n  compression_format: ''\n"
            "  compression_mode: ''\n",
        ),
    ),
]
BAG_FILES = FileKind(files=BROKEN_BAGS)
# A NaN in a message is malformed for the reader of that message only.
ODOMETRY_FILES = FileKind(
    files=[*BROKEN_BAGS, ("a NaN position", lambda d: _file(d, "nan.bag", _bag_bytes(nan=True)))]
)
IMU_FILES = FileKind(
    files=[
        *BROKEN_BAGS,
        ("a NaN angular velocity", lambda d: _file(d, "nan.bag", _bag_bytes(nan=True))),
    ]
)


def _bag(c: Any) -> Path:
    return _file(c.tmp, "tiny.bag", _bag_bytes())


TOPIC = Text(optional=True)
spec(
    IO + "read_bag_scans",
    lambda c: call(read_bag_scans, _bag(c), topic="/scan"),
    kinds={"path": BAG_FILES, "topic": TOPIC},
    inf_ok="REP 117: a +inf range means no return within range_max",
)
spec(
    IO + "read_bag_odometry",
    lambda c: call(read_bag_odometry, _bag(c), topic="/odom", skip_nonfinite=False),
    kinds={"path": ODOMETRY_FILES, "topic": TOPIC, "skip_nonfinite": Flag()},
)
spec(
    IO + "read_bag_imu",
    lambda c: call(read_bag_imu, _bag(c), topic="/imu", skip_nonfinite=False),
    kinds={"path": IMU_FILES, "topic": TOPIC, "skip_nonfinite": Flag()},
)
spec(IO + "bag_topics", lambda c: call(bag_topics, _bag(c)), kinds={"path": BAG_FILES})


def _scan() -> Call:
    return call(
        LaserScan, A([1.0, 2.0]), angle_min=0.0, angle_increment=0.1, range_min=0.1, range_max=5.0
    )


spec(
    IO + "BagScans",
    lambda c: call(BagScans, "/scan", "laser", A([1.5]), A([1.6]), (_scan(),)),
    kinds={"topic": Text(), "frame_id": Text(), "scans": SequenceOf(LaserScan)},
)
spec(
    IO + "BagOdometry",
    lambda c: call(
        BagOdometry,
        "/odom",
        "odom",
        "base_link",
        A([0.0]),
        A([0.1]),
        A([[1.0, 2.0, 0.5]]),
        A([[0.0, 0.0, 0.247404, 0.968912]]),
        A([[0.3, 0.0, 0.1]]),
        np.eye(6)[None],
        np.eye(6)[None],
    ),
    kinds={"topic": Text(), "frame_id": Text(), "child_frame_id": Text()},
)


def _imu() -> Call:
    return call(
        BagImu,
        "/imu",
        "imu_link",
        A([0.0]),
        A([0.1]),
        A([[0.0, 0.0, 0.0, 1.0]]),
        A([[0.0, 0.0, 0.2]]),
        A([[0.0, 0.0, 9.8]]),
        np.eye(3)[None],
        np.eye(3)[None],
        np.eye(3)[None] * -1.0,
    )


spec(IO + "BagImu", lambda c: _imu(), kinds={"topic": Text(), "frame_id": Text()})
spec(
    IO + "BagImu.to_base",
    lambda c: method(_imu(), "to_base", A([0.5, 0.5, 0.5, 0.5]), frame_id="base_link"),
    kinds={"mount": Array(), "frame_id": Text()},
)
