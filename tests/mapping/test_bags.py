"""ROS bags without ROS: the readers against the CSV dumps of the real bags, ROS 2 round trips."""

from __future__ import annotations

import math
import sys
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from navkit.geometry import quaternion_to_yaw, rpy_to_quaternion
from navkit.mapping.io import (
    BagImu,
    BagOdometry,
    bag_topics,
    read_bag_imu,
    read_bag_odometry,
    read_bag_scans,
)
from navkit.mapping.io._bags import _walk_ros1

rosbags = pytest.importorskip("rosbags")
from rosbags.rosbag1 import Writer as Writer1  # noqa: E402
from rosbags.rosbag2 import Writer as Writer2  # noqa: E402
from rosbags.typesys import Stores, get_typestore  # noqa: E402

DEMO = "rosbag-hokuyo-laserscan-demo"
RL = "robot-localization-odom-imu-bags"


def csv_columns(path: Path) -> dict[str, np.ndarray]:
    """Every column of a CSV dump by header name (text columns as str arrays)."""
    raw = np.genfromtxt(path, delimiter=",", names=True, dtype=None, encoding="ascii")
    return {name: np.asarray(raw[name]) for name in raw.dtype.names or ()}


# ------------------------------------------------------------ real bags vs CSV
def test_demo_bag_scans_equal_csv(shared_data: Path) -> None:
    folder = shared_data / DEMO
    scans = read_bag_scans(folder / "demo.bag")  # damaged chunk index: read through chunks
    table = np.loadtxt(folder / "demo_scans.csv", delimiter=",", skiprows=1)
    assert len(scans) == table.shape[0] == 360
    assert scans.topic == "/scan" and scans.frame_id == "/laser"
    np.testing.assert_allclose(scans.times, table[:, 1], rtol=0, atol=1e-6)
    np.testing.assert_allclose(scans.record_times, table[:, 0], rtol=0, atol=1e-6)
    ranges = np.array([s.ranges for s in scans.scans])
    # The CSV holds the float32 values in shortest form: equal bit for bit as float32.
    assert np.array_equal(ranges.astype(np.float32), table[:, 3:].astype(np.float32))
    assert np.array_equal(ranges, ranges.astype(np.float32).astype(np.float64))
    first = scans.scans[0]
    assert len(first) == 681
    assert first.angle_min == pytest.approx(-2.0862, abs=1e-4)
    assert first.angle_max == pytest.approx(2.0862, abs=1e-4)
    assert first.angle_increment == pytest.approx(0.0061359, abs=1e-7)
    assert (first.range_min, first.range_max) == pytest.approx((0.02, 5.6))
    assert first.intensities is None
    assert np.all(np.diff(scans.record_times) >= 0)
    assert bag_topics(folder / "demo.bag") == {"/scan": ("sensor_msgs/msg/LaserScan", 360)}


@pytest.mark.parametrize("name", ["test1", "test2"])
def test_robot_localization_odometry_equals_csv(shared_data: Path, name: str) -> None:
    odom = read_bag_odometry(shared_data / RL / f"{name}.bag")
    csv = csv_columns(shared_data / RL / "csv_extract" / f"{name}_wheel_odom.csv")
    assert len(odom) == csv["stamp"].shape[0]
    assert (odom.frame_id, odom.child_frame_id) == (str(csv["frame_id"][0]), "base_link")
    np.testing.assert_allclose(odom.times, csv["stamp"], rtol=0, atol=1e-6)
    np.testing.assert_allclose(odom.record_times, csv["bag_time"], rtol=0, atol=1e-6)
    quat = np.column_stack([csv[k] for k in ("qx", "qy", "qz", "qw")])
    np.testing.assert_array_equal(odom.orientations, quat)
    np.testing.assert_array_equal(odom.poses[:, :2], np.column_stack((csv["x"], csv["y"])))
    np.testing.assert_allclose(odom.poses[:, 2], quaternion_to_yaw(quat), rtol=0, atol=1e-15)
    np.testing.assert_array_equal(odom.twists, np.column_stack((csv["vx"], csv["vy"], csv["wz"])))
    diag = {"pose_cov_xx": (0, 0), "pose_cov_yy": (1, 1), "pose_cov_yawyaw": (5, 5)}
    for column, (i, j) in diag.items():
        np.testing.assert_array_equal(odom.pose_covariances[:, i, j], csv[column])
    for column, i in (("twist_cov_vxvx", 0), ("twist_cov_vyvy", 1), ("twist_cov_wzwz", 5)):
        np.testing.assert_array_equal(odom.twist_covariances[:, i, i], csv[column])


@pytest.mark.parametrize("name", ["test1", "test2"])
def test_robot_localization_imu_equals_csv(shared_data: Path, name: str) -> None:
    imu = read_bag_imu(shared_data / RL / f"{name}.bag", topic="/imu/data")
    csv = csv_columns(shared_data / RL / "csv_extract" / f"{name}_imu.csv")
    assert len(imu) == csv["stamp"].shape[0]
    assert imu.frame_id == str(csv["frame_id"][0])
    np.testing.assert_allclose(imu.times, csv["stamp"], rtol=0, atol=1e-6)
    np.testing.assert_allclose(imu.record_times, csv["bag_time"], rtol=0, atol=1e-6)
    cols = {
        "orientations": ("qx", "qy", "qz", "qw"),
        "angular_velocities": ("wx", "wy", "wz"),
        "linear_accelerations": ("ax", "ay", "az"),
    }
    for attr, names in cols.items():
        np.testing.assert_array_equal(getattr(imu, attr), np.column_stack([csv[k] for k in names]))
    covs = {
        "orientation_covariances": "ori_cov",
        "angular_velocity_covariances": "gyr_cov",
        "linear_acceleration_covariances": "acc_cov",
    }
    for attr, prefix in covs.items():
        for i, axis in enumerate("xyz"):
            np.testing.assert_array_equal(
                getattr(imu, attr)[:, i, i], csv[f"{prefix}_{axis}{axis}"]
            )


def test_chunk_walker_agrees_with_rosbags(shared_data: Path) -> None:
    """The fallback used for demo.bag gives what rosbags' own reader gives on a sound bag."""
    path = shared_data / RL / "test2.bag"
    walked = _walk_ros1(path)
    assert {t: (ty, n) for (t, ty), n in walked.counts.items()} == bag_topics(path)
    from rosbags.rosbag1 import Reader

    with Reader(path) as reader:
        conns = [c for c in reader.connections if c.topic == "/imu/data"]
        expected = [(ns, bytes(raw)) for _, ns, raw in reader.messages(connections=conns)]
    assert list(walked.messages("/imu/data", "sensor_msgs/msg/Imu")) == expected


# ------------------------------------------------------------ written bags
STORE2 = get_typestore(Stores.ROS2_HUMBLE)
STORE1 = get_typestore(Stores.ROS1_NOETIC)


def header(store: Any, t: float, frame: str) -> Any:
    time = store.types["builtin_interfaces/msg/Time"]
    sec = math.floor(t)
    stamp = time(sec=sec, nanosec=round((t - sec) * 1e9))
    fields = {name for name, _ in store.fielddefs["std_msgs/msg/Header"][1]}
    extra = {"seq": 0} if "seq" in fields else {}  # ROS 1 headers have a sequence number
    return store.types["std_msgs/msg/Header"](stamp=stamp, frame_id=frame, **extra)


def scan_msg(store: Any, t: float, ranges: list[float], frame: str = "laser") -> Any:
    return store.types["sensor_msgs/msg/LaserScan"](
        header=header(store, t, frame),
        angle_min=-1.0,
        angle_max=-1.0 + 0.5 * (len(ranges) - 1),
        angle_increment=0.5,
        time_increment=0.0,
        scan_time=0.1,
        range_min=0.1,
        range_max=10.0,
        ranges=np.array(ranges, dtype=np.float32),
        intensities=np.array([], dtype=np.float32),
    )


def odom_msg(store: Any, t: float, x: float, yaw: float, v: float) -> Any:
    T = store.types
    q = rpy_to_quaternion(0.0, 0.0, yaw)
    pose = T["geometry_msgs/msg/Pose"](
        position=T["geometry_msgs/msg/Point"](x=x, y=2.0 * x, z=0.0),
        orientation=T["geometry_msgs/msg/Quaternion"](*q),
    )
    twist = T["geometry_msgs/msg/Twist"](
        linear=T["geometry_msgs/msg/Vector3"](x=v, y=0.0, z=0.0),
        angular=T["geometry_msgs/msg/Vector3"](x=0.0, y=0.0, z=0.25),
    )
    return T["nav_msgs/msg/Odometry"](
        header=header(store, t, "odom"),
        child_frame_id="base_link",
        pose=T["geometry_msgs/msg/PoseWithCovariance"](pose=pose, covariance=np.arange(36.0)),
        twist=T["geometry_msgs/msg/TwistWithCovariance"](twist=twist, covariance=np.eye(6).ravel()),
    )


def imu_msg(store: Any, t: float, yaw: float, gz: float) -> Any:
    T = store.types
    vec = T["geometry_msgs/msg/Vector3"]
    return T["sensor_msgs/msg/Imu"](
        header=header(store, t, "imu_link"),
        orientation=T["geometry_msgs/msg/Quaternion"](*rpy_to_quaternion(0.0, 0.0, yaw)),
        orientation_covariance=np.diag([1.0, 2.0, 3.0]).ravel(),
        angular_velocity=vec(x=0.0, y=0.0, z=gz),
        angular_velocity_covariance=np.diag([4.0, 5.0, 6.0]).ravel(),
        linear_acceleration=vec(x=1.0, y=0.0, z=9.8),
        linear_acceleration_covariance=np.array([-1.0, 0, 0, 0, 0, 0, 0, 0, 0]),
    )


def write_bag2(folder: Path, messages: dict[str, tuple[str, list[tuple[float, Any]]]]) -> Path:
    with Writer2(folder, version=9) as writer:
        for topic, (msgtype, items) in messages.items():
            conn = writer.add_connection(topic, msgtype, typestore=STORE2)
            for t, msg in items:
                writer.write(conn, round((t + 0.01) * 1e9), STORE2.serialize_cdr(msg, msgtype))
    return folder


def mixed_bag(folder: Path, store: Any) -> dict[str, tuple[str, list[tuple[float, Any]]]]:
    del folder
    return {
        "/scan": (
            "sensor_msgs/msg/LaserScan",
            [
                (10.0 + 0.1 * i, scan_msg(store, 10.0 + 0.1 * i, [1.0 + i, math.inf, 2.5]))
                for i in range(3)
            ],
        ),
        "/odom": (
            "nav_msgs/msg/Odometry",
            [
                (10.0 + 0.05 * i, odom_msg(store, 10.0 + 0.05 * i, 0.1 * i, 0.3 * i, 0.5))
                for i in range(4)
            ],
        ),
        "/imu": (
            "sensor_msgs/msg/Imu",
            [
                (10.0 + 0.02 * i, imu_msg(store, 10.0 + 0.02 * i, -0.2 * i, 0.1 * i))
                for i in range(5)
            ],
        ),
    }


def check_mixed(path: Path) -> None:
    scans = read_bag_scans(path)
    assert scans.topic == "/scan" and scans.frame_id == "laser"
    np.testing.assert_allclose(scans.times, [10.0, 10.1, 10.2], atol=1e-9)
    np.testing.assert_allclose(scans.record_times, scans.times + 0.01, atol=1e-9)
    assert [s.ranges[0] for s in scans.scans] == [1.0, 2.0, 3.0]
    assert all(s.ranges[1] == math.inf and not s.valid_mask()[1] for s in scans.scans)
    assert scans.scans[0].angle_min == -1.0 and scans.scans[0].angle_increment == 0.5
    odom = read_bag_odometry(path, topic="/odom")
    assert (odom.frame_id, odom.child_frame_id) == ("odom", "base_link")
    np.testing.assert_allclose(odom.poses[:, 0], 0.1 * np.arange(4))
    np.testing.assert_allclose(odom.poses[:, 1], 0.2 * np.arange(4))
    np.testing.assert_allclose(odom.poses[:, 2], 0.3 * np.arange(4), atol=1e-12)
    np.testing.assert_allclose(odom.twists, np.tile([0.5, 0.0, 0.25], (4, 1)))
    np.testing.assert_array_equal(odom.pose_covariances[2], np.arange(36.0).reshape(6, 6))
    np.testing.assert_array_equal(odom.twist_covariances[1], np.eye(6))
    imu = read_bag_imu(path)
    assert imu.frame_id == "imu_link" and len(imu) == 5
    np.testing.assert_allclose(quaternion_to_yaw(imu.orientations), -0.2 * np.arange(5), atol=1e-12)
    np.testing.assert_allclose(imu.angular_velocities[:, 2], 0.1 * np.arange(5))
    np.testing.assert_array_equal(imu.orientation_covariances[0], np.diag([1.0, 2.0, 3.0]))
    assert imu.linear_acceleration_covariances[0, 0, 0] == -1.0
    assert bag_topics(path) == {
        "/imu": ("sensor_msgs/msg/Imu", 5),
        "/odom": ("nav_msgs/msg/Odometry", 4),
        "/scan": ("sensor_msgs/msg/LaserScan", 3),
    }


def test_ros2_bag_round_trip(tmp_path: Path) -> None:
    path = write_bag2(tmp_path / "bag2", mixed_bag(tmp_path, STORE2))
    check_mixed(path)


def test_ros1_bag_round_trip_any_file_name(tmp_path: Path) -> None:
    path = tmp_path / "recording.ros1"  # read by its header, not its suffix
    with Writer1(path) as writer:
        for topic, (msgtype, items) in mixed_bag(tmp_path, STORE1).items():
            conn = writer.add_connection(topic, msgtype, typestore=STORE1)
            for t, msg in items:
                writer.write(conn, round((t + 0.01) * 1e9), STORE1.serialize_ros1(msg, msgtype))
    check_mixed(path)
    walked = _walk_ros1(path)
    assert walked.counts == {
        ("/scan", "sensor_msgs/msg/LaserScan"): 3,
        ("/odom", "nav_msgs/msg/Odometry"): 4,
        ("/imu", "sensor_msgs/msg/Imu"): 5,
    }


def test_imu_to_base_rotates_readings_and_covariances(tmp_path: Path) -> None:
    imu = read_bag_imu(write_bag2(tmp_path / "bag", mixed_bag(tmp_path, STORE2)))
    mounting = rpy_to_quaternion(0.0, 0.0, math.pi / 2)  # IMU x axis = robot's y axis
    base = imu.to_base(mounting, frame_id="base")
    assert isinstance(base, BagImu) and base.frame_id == "base" and base.topic == imu.topic
    np.testing.assert_allclose(base.linear_accelerations[0], [0.0, 1.0, 9.8], atol=1e-12)
    np.testing.assert_allclose(
        quaternion_to_yaw(base.orientations), -0.2 * np.arange(5) - math.pi / 2, atol=1e-12
    )
    np.testing.assert_allclose(
        base.orientation_covariances[0], np.diag([2.0, 1.0, 3.0]), atol=1e-12
    )
    assert base.linear_acceleration_covariances[0, 0, 0] == -1.0  # "not given" is kept
    assert not base.orientations.flags.writeable


def test_imu_to_base_keeps_an_orientation_marked_not_given() -> None:
    # REP 145: an IMU without an orientation estimate sends a placeholder (here all
    # zero) with orientation_covariance[0] = -1. Rotating the placeholder gave the
    # mounting's inverse, e.g. (0, 0, 0, 1) for an identity mounting.
    given = np.diag([0.1, 0.1, 0.1])
    not_given = np.diag([-1.0, 0.0, 0.0])
    imu = BagImu(
        "/imu",
        "imu_link",
        [0.0, 0.1],
        [0.0, 0.1],
        [[0.0, 0.0, 0.0, 0.0], [0.0, 0.0, 0.0, 1.0]],
        [[0.0, 0.0, 0.2]] * 2,
        [[0.0, 0.0, 9.8]] * 2,
        [not_given, given],
        [given] * 2,
        [given] * 2,
    )
    for mounting in ([0.0, 0.0, 0.0, 1.0], rpy_to_quaternion(0.0, 0.0, 1.0)):
        base = imu.to_base(mounting)
        np.testing.assert_array_equal(base.orientations[0], [0.0, 0.0, 0.0, 0.0])
        np.testing.assert_array_equal(base.orientation_covariances[0], not_given)
    assert quaternion_to_yaw(base.orientations[1]) == pytest.approx(-1.0)  # given: rotated


def test_odometry_record_wraps_a_given_yaw() -> None:
    q, v, c = np.zeros((2, 4)), np.zeros((2, 3)), np.zeros((2, 6, 6))
    poses = np.array([[1.0, 2.0, 4.0], [0.0, 0.0, -math.pi]])
    odom = BagOdometry("/odom", "odom", "base_link", [0.0, 0.1], [0.0, 0.1], poses, q, v, c, c)
    np.testing.assert_allclose(odom.poses[:, 2], [4.0 - 2.0 * math.pi, math.pi], rtol=0, atol=1e-15)
    assert odom.poses[1, 2] == math.pi  # (-π, π]: -π becomes +π
    assert poses[0, 2] == 4.0 and not odom.poses.flags.writeable


# ------------------------------------------------------------ bad input
def test_bad_paths(tmp_path: Path) -> None:
    with pytest.raises(FileNotFoundError, match="does not exist"):
        read_bag_scans(tmp_path / "missing.bag")
    with pytest.raises(ValueError, match=r"metadata\.yaml"):
        read_bag_scans(tmp_path)
    junk = tmp_path / "junk.bag"
    junk.write_bytes(bytes(range(256)) * 4)
    with pytest.raises(ValueError, match="not a ROS 1 bag"):
        read_bag_imu(junk)
    with pytest.raises(TypeError, match="path"):
        read_bag_scans(3)  # type: ignore[arg-type]
    with pytest.raises(TypeError, match="topic"):
        read_bag_scans(junk, topic=b"/scan")  # type: ignore[arg-type]


def test_truncated_ros1_bag(shared_data: Path, tmp_path: Path) -> None:
    cut = tmp_path / "cut.bag"
    cut.write_bytes((shared_data / RL / "test2.bag").read_bytes()[:200_000])
    with pytest.raises(ValueError, match="cannot read the ROS 1 bag"):
        read_bag_odometry(cut)


def test_topics_without_messages_read_as_empty(tmp_path: Path) -> None:
    # ROS 2 records a topic that was advertised but never published: count 0.
    types = {
        "/scan": "sensor_msgs/msg/LaserScan",
        "/odom": "nav_msgs/msg/Odometry",
        "/imu": "sensor_msgs/msg/Imu",
    }
    with Writer2(tmp_path / "bag2", version=9) as writer:
        for topic, msgtype in types.items():
            writer.add_connection(topic, msgtype, typestore=STORE2)
    with Writer1(tmp_path / "bag1.bag") as writer1:
        writer1.add_connection("/odom", types["/odom"], typestore=STORE1)
    scans = read_bag_scans(tmp_path / "bag2")
    assert (len(scans), scans.frame_id, scans.scans, scans.times.shape) == (0, "", (), (0,))
    for path in (tmp_path / "bag2", tmp_path / "bag1.bag"):
        odom = read_bag_odometry(path)
        assert len(odom) == 0 and odom.child_frame_id == ""
        assert odom.poses.shape == (0, 3) and odom.twist_covariances.shape == (0, 6, 6)
    imu = read_bag_imu(tmp_path / "bag2")
    assert len(imu) == 0 and imu.orientation_covariances.shape == (0, 3, 3)
    assert len(imu.to_base(rpy_to_quaternion(0.0, 0.0, 1.0))) == 0


def test_corrupt_bags_raise_value_errors_naming_the_bag(tmp_path: Path) -> None:
    # rosbags' own reactions to these were OSError (bz2), a bare ValueError of an
    # enum and UnicodeDecodeError, none naming the bag.
    path = tmp_path / "bz2.bag"
    bz2_writer = Writer1(path)
    bz2_writer.set_compression(Writer1.CompressionFormat.BZ2)
    with bz2_writer as writer:
        for topic, (msgtype, items) in mixed_bag(tmp_path, STORE1).items():
            conn = writer.add_connection(topic, msgtype, typestore=STORE1)
            for t, msg in items:
                writer.write(conn, round(t * 1e9), STORE1.serialize_ros1(msg, msgtype))
    data = path.read_bytes()
    assert len(read_bag_imu(path)) == 5
    start = data.index(b"BZh")  # the compressed chunk
    chunk = tmp_path / "chunk.bag"
    chunk.write_bytes(data[: start + 40] + b"\xff" * 8 + data[start + 48 :])
    with pytest.raises(ValueError, match="corrupt compressed chunk") as info:
        read_bag_imu(chunk)
    assert str(chunk) in str(info.value)
    op = data.rindex(b"op=\x07")  # the last connection record of the index
    index = tmp_path / "index.bag"
    index.write_bytes(data[:op] + b"op=J" + data[op + 4 :])
    for read in (bag_topics, read_bag_scans):
        with pytest.raises(ValueError, match="cannot read the ROS 1 bag") as info:
            read(index)
        assert str(index) in str(info.value)
    folder = write_bag2(tmp_path / "bag2", mixed_bag(tmp_path, STORE2))
    meta = (folder / "metadata.yaml").read_text()
    (folder / "metadata.yaml").write_bytes(meta.replace("/imu", "/\xe9mu").encode("latin-1"))
    with pytest.raises(ValueError, match="cannot read the ROS 2 bag") as info:
        read_bag_imu(folder)
    assert type(info.value) is ValueError and str(folder) in str(info.value)


def test_topic_errors(tmp_path: Path) -> None:
    items = mixed_bag(tmp_path, STORE2)
    items["/scan_rear"] = ("sensor_msgs/msg/LaserScan", items["/scan"][1][:1])
    path = write_bag2(tmp_path / "bag", items)
    with pytest.raises(ValueError, match="several sensor_msgs/msg/LaserScan topics"):
        read_bag_scans(path)
    assert len(read_bag_scans(path, topic="/scan_rear")) == 1
    with pytest.raises(ValueError, match=r"topic '/nope' is not in .*/imu \(sensor_msgs/msg/Imu\)"):
        read_bag_imu(path, topic="/nope")
    with pytest.raises(ValueError, match="holds nav_msgs/msg/Odometry messages, not sensor_msgs"):
        read_bag_imu(path, topic="/odom")
    only_scans = write_bag2(tmp_path / "scans", {"/scan": items["/scan"]})
    with pytest.raises(ValueError, match="no nav_msgs/msg/Odometry topic; topics: /scan"):
        read_bag_odometry(only_scans)


def test_invalid_scan_message_names_topic_and_index(tmp_path: Path) -> None:
    bad = scan_msg(STORE2, 1.0, [1.0, 2.0])
    bad.angle_increment = 30.0  # degrees, not radians
    path = write_bag2(tmp_path / "bag", {"/scan": ("sensor_msgs/msg/LaserScan", [(1.0, bad)])})
    with pytest.raises(ValueError, match=r"message 0 of /scan.*degrees"):
        read_bag_scans(path)


def test_missing_rosbags_names_the_extra(monkeypatch: pytest.MonkeyPatch, tmp_path: Path) -> None:
    for name in [m for m in sys.modules if m == "rosbags" or m.startswith("rosbags.")]:
        monkeypatch.delitem(sys.modules, name)
    monkeypatch.setitem(sys.modules, "rosbags", None)
    path = tmp_path / "x.bag"
    path.write_bytes(b"#ROSBAG V2.0\n")
    with pytest.raises(ImportError, match=r"navkit\[ros\]"):
        read_bag_scans(path)
