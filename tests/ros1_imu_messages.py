"""ROS 1 IMU messages for the bag readers' tests, made with rosbags' typestore.

Each message carries its record time in its header stamp and a label in
``angular_velocity.z``, so that a test can tell which message a reader gave
back and in what order. Review 8's record-length, review 9's chunk-walker and
review 47's mutation tests each wrote this maker (review 47).
"""

from __future__ import annotations

from typing import Any

import numpy as np
from rosbags.typesys import Stores, get_typestore

IMU = "sensor_msgs/msg/Imu"
STORE = get_typestore(Stores.ROS1_NOETIC)


def imu_message(ns: int, label: float) -> Any:
    """A ``sensor_msgs/Imu`` stamped ``ns`` nanoseconds, ``angular_velocity.z = label``."""
    T = STORE.types
    stamp = T["builtin_interfaces/msg/Time"](sec=ns // 10**9, nanosec=ns % 10**9)
    vec = T["geometry_msgs/msg/Vector3"]
    return T[IMU](
        header=T["std_msgs/msg/Header"](seq=0, stamp=stamp, frame_id="imu"),
        orientation=T["geometry_msgs/msg/Quaternion"](x=0.0, y=0.0, z=0.0, w=1.0),
        orientation_covariance=np.zeros(9),
        angular_velocity=vec(x=0.0, y=0.0, z=label),
        angular_velocity_covariance=np.zeros(9),
        linear_acceleration=vec(x=0.0, y=0.0, z=9.8),
        linear_acceleration_covariance=np.zeros(9),
    )
