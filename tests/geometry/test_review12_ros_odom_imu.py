"""/odom and /imu messages of a ROS 2 node into navkit poses, yaws and times.

``ros_fakes`` emulates rclpy's generated classes (NumPy covariance arrays,
Python-float fields, ``builtin_interfaces/Time`` stamps).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import ros_fakes as ros
from navkit.estimation import PlanarFusion
from navkit.geometry import (
    ImuInBase,
    Pose2D,
    Twist2D,
    imu_to_base,
    quaternion_to_matrix,
    quaternion_to_yaw,
    rpy_to_quaternion,
)


def xyzw(q: Any) -> tuple[float, float, float, float]:
    return (q.x, q.y, q.z, q.w)


def xyz(v: Any) -> tuple[float, float, float]:
    return (v.x, v.y, v.z)


def seconds(stamp: Any) -> float:
    """What every node writes: float64 seconds of a ``builtin_interfaces/Time``."""
    return float(stamp.sec) + float(stamp.nanosec) * 1e-9


def odometry(x: float, y: float, yaw: float, v: float, omega: float, ns: int) -> Any:
    msg = ros.Odometry()
    msg.header = ros.Header(stamp=ros.stamp(ns // 10**9, ns % 10**9), frame_id="odom")
    msg.child_frame_id = "base_link"
    msg.pose.pose = ros.pose_msg(x, y, yaw)
    msg.pose.covariance = np.diag([1e-3, 1e-3, 1e6, 1e6, 1e6, 1e-2]).ravel()
    msg.twist.twist = ros.Twist(
        linear=ros.Vector3(x=v, y=0.0, z=0.0), angular=ros.Vector3(x=0.0, y=0.0, z=omega)
    )
    return ros.deliver(msg)


@settings(max_examples=40)
@given(st.floats(-1e4, 1e4), st.floats(-1e4, 1e4), st.floats(-math.pi, math.pi))
def test_odometry_pose_and_twist_become_a_pose_and_a_body_frame_twist(
    x: float, y: float, yaw: float
) -> None:
    msg = odometry(x, y, yaw, 0.4, -0.2, 1_700_000_000_123_456_789)
    p = msg.pose.pose
    pose = Pose2D(p.position.x, p.position.y, quaternion_to_yaw(xyzw(p.orientation)))
    assert (pose.x, pose.y) == (x, y)
    assert abs(math.remainder(pose.theta - yaw, 2 * math.pi)) < 1e-12
    assert -math.pi < pose.theta <= math.pi
    # The twist is in child_frame_id (base_link), as navkit's Twist2D is.
    t = msg.twist.twist
    assert Twist2D(t.linear.x, t.linear.y, t.angular.z) == Twist2D(0.4, 0.0, -0.2)
    # The covariance arrives as a NumPy float64 array of 36, row-major (x y z roll pitch yaw).
    cov = msg.pose.covariance.reshape(6, 6)
    assert cov[5, 5] == 1e-2 and cov[0, 0] == 1e-3


def test_epoch_stamps_keep_sub_microsecond_differences_in_float64() -> None:
    # 1.7e9 s: float64 values lie 2.4e-7 s apart, so 10 ms steps come back to within it.
    base = 1_700_000_000 * 10**9
    ns = base + np.arange(0, 2_000_000_000, 10_000_000)
    t = np.array([seconds(ros.stamp(int(n) // 10**9, int(n) % 10**9)) for n in ns])
    assert t.dtype == np.float64
    np.testing.assert_allclose(np.diff(t), 0.01, atol=2.4e-7)
    assert np.all(np.diff(t) > 0)


def test_fusion_on_epoch_stamps_matches_fusion_on_stamps_from_zero() -> None:
    # Nothing between the stamp and the filter rounds times to float32.
    def run(sec0: int) -> np.ndarray:
        fusion = PlanarFusion(t0=float(sec0))
        for k in range(1, 201):
            ns = k * 10_000_000
            msg = odometry(0.0, 0.0, 0.0, 0.5, 0.2, sec0 * 10**9 + ns)
            fusion.update_odometry(
                seconds(msg.header.stamp),
                msg.twist.twist.linear.x,
                msg.twist.twist.angular.z,
                v_variance=1e-4,
                omega_variance=1e-4,
            )
        return fusion.x

    np.testing.assert_allclose(run(1_700_000_000), run(0), atol=1e-8)


def imu_msg(
    orientation: np.ndarray, gyro: tuple[float, float, float], accel: tuple[float, float, float]
) -> Any:
    msg = ros.Imu()
    qx, qy, qz, qw = (float(v) for v in orientation)
    msg.orientation = ros.Quaternion(x=qx, y=qy, z=qz, w=qw)
    msg.orientation_covariance = np.diag([1e-3, 1e-3, 1e-2]).ravel()
    msg.angular_velocity = ros.Vector3(x=gyro[0], y=gyro[1], z=gyro[2])
    msg.linear_acceleration = ros.Vector3(x=accel[0], y=accel[1], z=accel[2])
    return ros.deliver(msg)


@pytest.mark.parametrize("mount_yaw", [0.0, math.pi / 2, -2.0])
def test_upside_down_imu_gives_the_base_yaw_and_yaw_rate(mount_yaw: float) -> None:
    # IMU rolled by π (upside down) and yawed on the robot; the robot heads 0.7 rad,
    # turning at +0.3 rad/s and accelerating forward at 1 m/s².
    mount = rpy_to_quaternion(math.pi, 0.0, mount_yaw)
    base_yaw, rate, accel = 0.7, 0.3, 1.0
    base = rpy_to_quaternion(0.0, 0.0, base_yaw)
    r_mount = quaternion_to_matrix(mount)
    # What the IMU reports: its own orientation q_base ⊗ m, vectors in its own frame.
    bx, by, bz, bw = base
    mx, my, mz, mw = mount
    imu_q = np.array(
        [
            bw * mx + bx * mw + by * mz - bz * my,
            bw * my - bx * mz + by * mw + bz * mx,
            bw * mz + bx * my - by * mx + bz * mw,
            bw * mw - bx * mx - by * my - bz * mz,
        ]
    )
    gyro = r_mount.T @ np.array([0.0, 0.0, rate])
    acc = r_mount.T @ np.array([accel, 0.0, 9.81])
    msg = imu_msg(imu_q, tuple(gyro), tuple(acc))
    readings = imu_to_base(
        xyzw(msg.orientation), xyz(msg.angular_velocity), xyz(msg.linear_acceleration), mount=mount
    )
    assert isinstance(readings, ImuInBase)
    assert quaternion_to_yaw(readings.orientations) == pytest.approx(base_yaw, abs=1e-12)
    np.testing.assert_allclose(readings.angular_velocities, [0.0, 0.0, rate], atol=1e-12)
    np.testing.assert_allclose(readings.linear_accelerations, [accel, 0.0, 9.81], atol=1e-12)
    if mount_yaw == 0.0:
        assert msg.angular_velocity.z == pytest.approx(-rate)  # upside down: z flips


@pytest.mark.parametrize(
    "call",
    [
        lambda m: quaternion_to_yaw(m.orientation),
        lambda m: quaternion_to_matrix(m.orientation),
        lambda m: imu_to_base(
            m.orientation, (0.0, 0.0, 0.0), (0.0, 0.0, 9.8), mount=(0.0, 0.0, 0.0, 1.0)
        ),
        lambda m: imu_to_base(
            (0.0, 0.0, 0.0, 1.0), m.angular_velocity, (0.0, 0.0, 9.8), mount=(0.0, 0.0, 0.0, 1.0)
        ),
        lambda m: imu_to_base(
            (0.0, 0.0, 0.0, 1.0), (0.0, 0.0, 0.0), m.linear_acceleration, mount=(0.0, 0.0, 0.0, 1.0)
        ),
        lambda m: imu_to_base(
            (0.0, 0.0, 0.0, 1.0), (0.0, 0.0, 0.0), (0.0, 0.0, 9.8), mount=m.orientation
        ),
        lambda m: ImuInBase(m.orientation, (0.0, 0.0, 0.0), (0.0, 0.0, 9.8)),
    ],
    ids=[
        "yaw",
        "matrix",
        "orientations",
        "angular_velocities",
        "linear_accelerations",
        "mount",
        "ImuInBase",
    ],
)
def test_a_message_passed_whole_is_a_type_error_saying_what_to_pass(call: Any) -> None:
    msg = imu_msg(np.array([0.0, 0.0, 0.0, 1.0]), (0.0, 0.0, 0.1), (0.0, 0.0, 9.8))
    with pytest.raises(TypeError, match=r"a ROS message\?\): pass \(m\.x, m\.y, m\.z"):
        call(msg)


def test_objects_that_are_not_messages_keep_their_errors() -> None:
    class Raising:
        @property
        def x(self) -> float:
            raise RuntimeError("not a field")

        y = z = w = 0.0

    with pytest.raises(TypeError, match="real numbers"):
        quaternion_to_yaw(Raising())  # type: ignore[arg-type]
    with pytest.raises(TypeError, match="real numbers"):
        quaternion_to_yaw(object())  # type: ignore[arg-type]


def test_the_hint_serves_every_array_argument_and_names_navkit_records_plainly() -> None:
    from navkit.geometry import Pose2D
    from navkit.mapping import OccupancyGrid

    grid = OccupancyGrid(np.zeros((4, 4), np.float32), resolution=1.0)
    point = ros.Point(x=1.0, y=2.0, z=0.0)
    ros_hint = r"points_xy .* \(a ROS message\?\): pass \(m\.x, m\.y\)$"
    with pytest.raises(TypeError, match=ros_hint):
        grid.world_to_cell([point])
    navkit_hint = r"type Pose2D with fields x, y: pass \(p\.x, p\.y\) of that Pose2D p$"
    with pytest.raises(TypeError, match=navkit_hint):
        grid.world_to_cell([Pose2D(1.0, 2.0, 0.0)])
