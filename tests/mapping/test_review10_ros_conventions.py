"""ROS message conventions, checked against the .msg definitions and tf2 rather than navkit.

Hand-built messages follow ``nav_msgs/Odometry``, ``sensor_msgs/Imu``,
``sensor_msgs/LaserScan`` and ``nav_msgs/OccupancyGrid``; each test checks a
convention the readers' and converters' docstrings state.
"""

from __future__ import annotations

import array
import math
from collections.abc import Sequence
from fractions import Fraction
from pathlib import Path
from types import SimpleNamespace as NS
from typing import Any

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from navkit.estimation import MeasurementLog
from navkit.geometry import quaternion_to_yaw, rpy_to_quaternion
from navkit.mapping import OccupancyGrid
from navkit.mapping.io import (
    grid_from_msg,
    grid_to_msg_fields,
    read_bag_imu,
    read_bag_odometry,
    scan_from_msg,
)


def tf2_get_yaw(x: float, y: float, z: float, w: float) -> float:
    """tf2::getYaw (tf2/utils.h), transcribed."""
    sqx, sqy, sqz, sqw = x * x, y * y, z * z, w * w
    sarg = -2.0 * (x * z - w * y) / (sqx + sqy + sqz + sqw)
    if sarg <= -0.99999:
        return -2.0 * math.atan2(y, x)
    if sarg >= 0.99999:
        return 2.0 * math.atan2(y, x)
    return math.atan2(2.0 * (x * y + w * z), sqw + sqx - sqy - sqz)


def angle_gap(a: float, b: float) -> float:
    return abs((a - b + math.pi) % (2.0 * math.pi) - math.pi)


component = st.floats(-10.0, 10.0, allow_nan=False)


@settings(max_examples=60, deadline=None)
@given(component, component, component, component, st.sampled_from([1e-3, 1.0, 1e3]))
def test_yaw_is_tf2_get_yaw_away_from_gimbal_lock(
    x: float, y: float, z: float, w: float, scale: float
) -> None:
    q = np.array([x, y, z, w]) * scale  # not normalised: tf2 divides by the norm too
    norm2 = float(q @ q)
    if norm2 < 1e-6:
        return
    sarg = -2.0 * (q[0] * q[2] - q[3] * q[1]) / norm2
    if abs(sarg) >= 0.99999:  # tf2's gimbal-lock branch, documented as differing
        return
    assert angle_gap(float(quaternion_to_yaw(q)), tf2_get_yaw(*q)) < 1e-9


def test_yaw_of_identity_with_negative_w_and_of_a_tilted_orientation() -> None:
    assert quaternion_to_yaw([0.0, 0.0, 0.0, -1.0]) == 0.0
    assert quaternion_to_yaw([0.0, 0.0, 0.0, -3.5]) == 0.0
    # ZYX: yaw survives roll and pitch, as tf2's getYaw gives it.
    q = rpy_to_quaternion(0.4, -0.6, 2.9)
    assert quaternion_to_yaw(q) == pytest.approx(2.9, abs=1e-12)
    assert quaternion_to_yaw(-q) == pytest.approx(tf2_get_yaw(*-q), abs=1e-12)


# ------------------------------------------------------------------ bags
rosbags = pytest.importorskip("rosbags")
from rosbags.rosbag2 import Writer as Writer2  # noqa: E402
from rosbags.typesys import Stores, get_typestore  # noqa: E402

STORE = get_typestore(Stores.ROS2_HUMBLE)
T = STORE.types


def stamp(sec: int, nanosec: int, frame: str) -> Any:
    time = T["builtin_interfaces/msg/Time"](sec=sec, nanosec=nanosec)
    return T["std_msgs/msg/Header"](stamp=time, frame_id=frame)


def odometry(sec: int, nanosec: int) -> Any:
    vec = T["geometry_msgs/msg/Vector3"]
    pose = T["geometry_msgs/msg/Pose"](
        position=T["geometry_msgs/msg/Point"](x=1.0, y=2.0, z=0.0),
        orientation=T["geometry_msgs/msg/Quaternion"](x=0.0, y=0.0, z=0.0, w=1.0),
    )
    twist = T["geometry_msgs/msg/Twist"](linear=vec(x=0.5, y=0.0, z=0.0),
                                        angular=vec(x=0.0, y=0.0, z=0.1))  # fmt: skip
    return T["nav_msgs/msg/Odometry"](
        header=stamp(sec, nanosec, "odom"),
        child_frame_id="base_link",
        pose=T["geometry_msgs/msg/PoseWithCovariance"](pose=pose, covariance=np.arange(36.0)),
        twist=T["geometry_msgs/msg/TwistWithCovariance"](
            twist=twist, covariance=100.0 + np.arange(36.0)
        ),
    )


def imu(sec: int, nanosec: int) -> Any:
    vec = T["geometry_msgs/msg/Vector3"]
    return T["sensor_msgs/msg/Imu"](
        header=stamp(sec, nanosec, "imu_link"),
        orientation=T["geometry_msgs/msg/Quaternion"](x=0.0, y=0.0, z=0.0, w=0.0),
        orientation_covariance=np.array([-1.0, 0, 0, 0, 0, 0, 0, 0, 0]),
        angular_velocity=vec(x=0.0, y=0.0, z=0.2),
        angular_velocity_covariance=np.arange(9.0),
        linear_acceleration=vec(x=0.0, y=0.0, z=9.8),
        linear_acceleration_covariance=np.zeros(9),
    )


STAMPS = [(1_700_000_000, 123_456_789), (1_700_000_000, 123_456_790), (47, 580_000_001)]


@pytest.fixture(scope="module")
def bag(tmp_path_factory: pytest.TempPathFactory) -> Path:
    folder = tmp_path_factory.mktemp("ros") / "bag"
    with Writer2(folder, version=9) as writer:
        for topic, msgtype, make in (
            ("/odom", "nav_msgs/msg/Odometry", odometry),
            ("/imu", "sensor_msgs/msg/Imu", imu),
        ):
            conn = writer.add_connection(topic, msgtype, typestore=STORE)
            for i, (sec, ns) in enumerate(STAMPS):
                raw = STORE.serialize_cdr(make(sec, ns), msgtype)
                writer.write(conn, 1_800_000_000_000_000_000 + i, raw)
    return folder


def test_covariance_layouts_follow_the_messages(bag: Path) -> None:
    odom = read_bag_odometry(bag)
    # Row-major over (x, y, z, rot x, rot y, rot z): the planar block is 0, 1, 5; 6, 7, 11;
    # 30, 31, 35 of the message's 36 numbers.
    planar = odom.pose_covariances[0][np.ix_([0, 1, 5], [0, 1, 5])]
    np.testing.assert_array_equal(planar, [[0, 1, 5], [6, 7, 11], [30, 31, 35]])
    assert odom.twist_covariances[0, 5, 5] == 135.0 and odom.twist_covariances[0, 0, 5] == 105.0
    readings = read_bag_imu(bag)
    np.testing.assert_array_equal(
        readings.angular_velocity_covariances[0], np.arange(9.0).reshape(3, 3)
    )
    assert readings.orientation_covariances[0, 0, 0] == -1.0  # REP 145: not given
    # The docstrings' warning: an unknown (all-zero) covariance is no variance.
    with pytest.raises(ValueError, match="yaw_rate_variance"):
        MeasurementLog.from_streams(
            yaw_rate=(readings.times, readings.angular_velocities[:, 2]),
            yaw_rate_variance=readings.linear_acceleration_covariances[:, 2, 2],
        )


def test_stamps_and_their_documented_resolution(bag: Path) -> None:
    odom = read_bag_odometry(bag)
    exact = [Fraction(sec) + Fraction(ns, 10**9) for sec, ns in STAMPS]
    # Wall-clock stamps: within 0.12 µs of the exact instant, one nanosecond apart
    # stamps may coincide or not, but never reverse order.
    for t, e in zip(odom.times[:2], exact[:2], strict=True):
        assert abs(Fraction(float(t)) - e) <= Fraction(12, 10**8)
    assert odom.times[1] >= odom.times[0]
    # Simulation-time stamps (below 2**23 s) resolve the nanosecond.
    assert abs(Fraction(float(odom.times[2])) - exact[2]) < Fraction(1, 2 * 10**9)
    # record_times are the recorder's, not the stamps.
    assert odom.record_times[0] == pytest.approx(1.8e9) and odom.record_times[0] != odom.times[0]


# --------------------------------------------------------------- messages
def test_scan_timing_fields_are_not_read() -> None:
    fields: dict[str, Any] = {
        "ranges": [1.0, 2.0, 3.0],
        "angle_min": -0.1,
        "angle_max": 0.1,
        "angle_increment": 0.1,
        "range_min": 0.1,
        "range_max": 5.0,
        "intensities": [],
    }
    still = scan_from_msg(NS(**fields, time_increment=0.0, scan_time=0.0))
    sweeping = scan_from_msg(NS(**fields, time_increment=0.033, scan_time=0.1))
    np.testing.assert_array_equal(still.to_points(), sweeping.to_points())


def test_float32_resolution_keeps_cells_within_the_documented_bound() -> None:
    width = 384
    grid = OccupancyGrid.from_occupancy(np.zeros((2, width), dtype=bool), resolution=0.05,
                                        origin=(-10.0, -10.0, 0.0))  # fmt: skip
    fields = grid_to_msg_fields(grid, mode="trinary")
    info = T["nav_msgs/msg/MapMetaData"](
        map_load_time=T["builtin_interfaces/msg/Time"](sec=0, nanosec=0),
        resolution=fields.resolution, width=fields.width, height=fields.height,
        origin=T["geometry_msgs/msg/Pose"](
            position=T["geometry_msgs/msg/Point"](x=-10.0, y=-10.0, z=0.0),
            orientation=T["geometry_msgs/msg/Quaternion"](*fields.origin_orientation),
        ),
    )  # fmt: skip
    msg = T["nav_msgs/msg/OccupancyGrid"](header=stamp(0, 0, "map"), info=info, data=fields.data)
    back = grid_from_msg(
        STORE.deserialize_cdr(STORE.serialize_cdr(msg, "nav_msgs/msg/OccupancyGrid"),
                              "nav_msgs/msg/OccupancyGrid")
    )  # fmt: skip
    assert back.resolution == float(np.float32(0.05)) != grid.resolution
    edges = back.cell_to_world(np.column_stack((np.full(width, -0.5), np.arange(width) + 0.5)))
    shift = np.abs(edges[:, 0] - (-10.0 + 0.05 * (np.arange(width) + 1)))
    assert shift.max() <= width * 7.5e-10
    np.testing.assert_array_equal(back.occupied(), grid.occupied())


def test_documented_rclpy_conversion_of_grid_data() -> None:
    fields = grid_to_msg_fields(
        OccupancyGrid.from_occupancy(np.array([[True, False]]), resolution=0.1), mode="trinary"
    )
    # rclpy's int8[] setter takes an array.array('b') or a Sequence of ints, not NumPy.
    data: object = fields.data
    assert not isinstance(data, Sequence)
    converted = array.array("b", fields.data.tobytes())
    assert converted.typecode == "b" and converted.tolist() == [100, 0]
    assert all(type(v) is int for v in fields.data.tolist())
