"""An IMU's all-zero orientation quaternion with a covariance claiming an orientation (review 52).

REP 145 marks "no orientation" with ``orientation_covariance[0] = -1`` and an
all-zero quaternion; a driver leaving the covariance unset sent the zero
quaternion as an orientation, which read as yaw 0 and, through ``to_base``,
as the mounting's inverse. ``read_bag_imu`` now marks such messages "no
orientation" with a RuntimeWarning naming the first one; ``to_base`` keeps an
all-zero orientation whatever its covariance.
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from navkit.geometry import quaternion_to_yaw, rpy_to_quaternion
from navkit.mapping.io import BagImu, read_bag_imu

rosbags = pytest.importorskip("rosbags")
from rosbags.rosbag2 import Writer  # noqa: E402
from rosbags.typesys import Stores, get_typestore  # noqa: E402

STORE = get_typestore(Stores.ROS2_HUMBLE)
T = STORE.types
ZERO = (0.0, 0.0, 0.0, 0.0)


def imu_msg(k: int, quat: tuple[float, float, float, float], cov00: float, gz: float) -> Any:
    vec = T["geometry_msgs/msg/Vector3"]
    return T["sensor_msgs/msg/Imu"](
        header=T["std_msgs/msg/Header"](
            stamp=T["builtin_interfaces/msg/Time"](sec=100 + k, nanosec=0), frame_id="imu_link"
        ),
        orientation=T["geometry_msgs/msg/Quaternion"](*quat),
        orientation_covariance=np.array([cov00, 0.0, 0.0, 0.0, 2.0, 0.0, 0.0, 0.0, 3.0]),
        angular_velocity=vec(x=0.0, y=0.0, z=gz),
        angular_velocity_covariance=np.diag([4.0, 5.0, 6.0]).ravel(),
        linear_acceleration=vec(x=0.0, y=0.0, z=9.8),
        linear_acceleration_covariance=np.diag([7.0, 8.0, 9.0]).ravel(),
    )


def write_bag(folder: Path, messages: list[Any]) -> Path:
    with Writer(folder, version=9) as writer:
        conn = writer.add_connection("/imu", "sensor_msgs/msg/Imu", typestore=STORE)
        for k, msg in enumerate(messages):
            raw = STORE.serialize_cdr(msg, "sensor_msgs/msg/Imu")
            writer.write(conn, (200 + k) * 1_000_000_000, raw)
    return folder


def turned(yaw: float) -> tuple[float, float, float, float]:
    x, y, z, w = (float(v) for v in rpy_to_quaternion(0.0, 0.0, yaw))
    return (x, y, z, w)


def test_zero_quaternions_claiming_an_orientation_are_marked_not_given(tmp_path: Path) -> None:
    messages = [
        imu_msg(0, turned(0.5), 1.0, 0.1),
        imu_msg(1, ZERO, 1.0, 0.2),  # the driver left the covariance unset
        imu_msg(2, turned(-1.0), 1.0, 0.3),
        imu_msg(3, (-0.0, 0.0, -0.0, 0.0), 0.5, 0.4),
        imu_msg(4, ZERO, -1.0, 0.5),  # REP 145's "no orientation": no warning for it
    ]
    bag = write_bag(tmp_path / "bag", messages)
    with pytest.warns(RuntimeWarning) as caught:
        imu = read_bag_imu(bag)
    assert len(caught) == 1
    text = str(caught[0].message)
    assert "2 of the 5 messages of /imu give an all-zero orientation quaternion" in text
    assert "message 1, recorded at 201.000000000 s" in text
    assert caught[0].filename == __file__  # the caller's line
    np.testing.assert_array_equal(
        imu.orientation_covariances[:, 0, 0], [1.0, -1.0, 1.0, -1.0, -1.0]
    )
    # Only the flag: the rest of each covariance, the orientations (zero, as in the bag)
    # and the other readings are as in the bag.
    np.testing.assert_array_equal(imu.orientation_covariances[:, 1, 1], [2.0] * 5)
    np.testing.assert_array_equal(imu.orientations[[1, 3, 4]], np.zeros((3, 4)))
    np.testing.assert_allclose(quaternion_to_yaw(imu.orientations[[0, 2]]), [0.5, -1.0])
    np.testing.assert_array_equal(imu.angular_velocities[:, 2], [0.1, 0.2, 0.3, 0.4, 0.5])
    np.testing.assert_array_equal(imu.angular_velocity_covariances[1], np.diag([4.0, 5.0, 6.0]))


def test_the_warning_counts_messages_as_the_errors_do(tmp_path: Path) -> None:
    # Message 0 holds a NaN and is left out; the zero quaternion is message 2 of the
    # topic (its index among all messages, as the non-finite error names them).
    messages = [
        imu_msg(0, turned(0.1), 1.0, math.nan),
        imu_msg(1, turned(0.2), 1.0, 0.2),
        imu_msg(2, ZERO, 1.0, 0.3),
        imu_msg(3, ZERO, 1.0, math.inf),  # left out too: not counted
    ]
    bag = write_bag(tmp_path / "bag", messages)
    with pytest.warns(RuntimeWarning) as caught:
        imu = read_bag_imu(bag, skip_nonfinite=True)
    assert len(caught) == 2
    left_out, marked = sorted((str(w.message) for w in caught), key=lambda m: "left out" not in m)
    assert "left out 2 of the 4 messages" in left_out
    assert "1 of the 4 messages of /imu give an all-zero" in marked
    assert "message 2, recorded at 202.000000000 s" in marked
    np.testing.assert_array_equal(imu.orientation_covariances[:, 0, 0], [1.0, -1.0])
    # Without skip_nonfinite the NaN is refused as before (and nothing is warned).
    with pytest.raises(ValueError, match=r"message 0 of /imu has a non-finite angular velocity"):
        read_bag_imu(bag)


def test_unit_and_scaled_quaternions_are_kept_as_in_the_bag(tmp_path: Path) -> None:
    scaled = tuple(2.0 * v for v in turned(0.7))
    messages = [imu_msg(0, turned(0.3), 1.0, 0.0), imu_msg(1, scaled, 1.0, 0.0)]  # type: ignore[arg-type]
    imu = read_bag_imu(write_bag(tmp_path / "bag", messages))  # no warning (errors here)
    np.testing.assert_array_equal(imu.orientation_covariances[:, 0, 0], [1.0, 1.0])
    np.testing.assert_array_equal(imu.orientations[1], scaled)
    np.testing.assert_allclose(quaternion_to_yaw(imu.orientations), [0.3, 0.7])


def test_to_base_keeps_an_all_zero_orientation_whatever_its_covariance() -> None:
    eye = np.eye(3)[None]
    orientations = [ZERO, turned(0.4)]
    imu = BagImu("/imu", "imu_link", [0.0, 1.0], [0.0, 1.0], orientations,
                 [[0.0, 0.0, 0.2]] * 2, [[0.0, 0.0, 9.8]] * 2,
                 np.repeat(eye, 2, axis=0), *[np.repeat(eye, 2, axis=0)] * 2)  # fmt: skip
    mount = rpy_to_quaternion(0.0, 0.0, math.pi / 2)
    base = imu.to_base(mount)
    # Not the mounting's inverse (yaw -π/2) for the zero quaternion: no orientation.
    np.testing.assert_array_equal(base.orientations[0], np.zeros(4))
    assert float(quaternion_to_yaw(base.orientations[1])) == pytest.approx(0.4 - math.pi / 2)
    np.testing.assert_array_equal(imu.orientations[0], np.zeros(4))  # the input unchanged
