"""A NaN or infinity in one odometry or IMU message of a bag (review 47).

``read_bag_odometry`` and ``read_bag_imu`` refused the whole topic, naming the
first message with a non-finite value field by field (so not always the first
bad message), by its index only. They still refuse by default, now naming the
first bad message by its index and record time, and ``skip_nonfinite=True``
leaves such messages out with a ``RuntimeWarning`` saying how many (what a
robot_localization user expects of one bad message, without hiding it).
"""

from __future__ import annotations

import math
import re
import warnings
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from navkit.mapping.io import read_bag_imu, read_bag_odometry

pytest.importorskip("rosbags")
from rosbags.rosbag1 import Writer
from rosbags.typesys import Stores, get_typestore

STORE = get_typestore(Stores.ROS1_NOETIC)
T = STORE.types
ODOM = "nav_msgs/msg/Odometry"
IMU = "sensor_msgs/msg/Imu"
RL = "robot-localization-odom-imu-bags"


def _vector(x: float, y: float = 0.0, z: float = 0.0) -> Any:
    return T["geometry_msgs/msg/Vector3"](x=x, y=y, z=z)


def _odometry(k: int, bad: dict[str, float]) -> Any:
    """Message ``k`` (x = k m, speed 1 m/s), with the values ``bad`` names put in."""
    cov = np.eye(6).ravel()
    pose_cov = cov.copy()
    pose_cov[7] = bad.get("pose covariance", 1.0)
    pose = T["geometry_msgs/msg/Pose"](
        position=T["geometry_msgs/msg/Point"](x=bad.get("position", float(k)), y=0.0, z=0.0),
        orientation=T["geometry_msgs/msg/Quaternion"](x=0.0, y=0.0, z=0.0, w=1.0),
    )
    twist = T["geometry_msgs/msg/Twist"](
        linear=_vector(bad.get("twist", 1.0)), angular=_vector(0.0, 0.0, 0.1 * k)
    )
    return T[ODOM](
        header=T["std_msgs/msg/Header"](
            seq=k, stamp=T["builtin_interfaces/msg/Time"](sec=10 + k, nanosec=5), frame_id="odom"
        ),
        child_frame_id="base_link",
        pose=T["geometry_msgs/msg/PoseWithCovariance"](pose=pose, covariance=pose_cov),
        twist=T["geometry_msgs/msg/TwistWithCovariance"](twist=twist, covariance=cov),
    )


def _imu(k: int, bad: dict[str, float]) -> Any:
    acc_cov = np.eye(3).ravel()
    acc_cov[4] = bad.get("linear acceleration covariance", 1.0)
    return T[IMU](
        header=T["std_msgs/msg/Header"](
            seq=k, stamp=T["builtin_interfaces/msg/Time"](sec=10 + k, nanosec=0), frame_id="imu"
        ),
        orientation=T["geometry_msgs/msg/Quaternion"](x=0.0, y=0.0, z=0.0, w=1.0),
        orientation_covariance=np.eye(3).ravel(),
        angular_velocity=_vector(0.0, 0.0, bad.get("angular velocity", 0.1 * k)),
        angular_velocity_covariance=np.eye(3).ravel(),
        linear_acceleration=_vector(0.0, 0.0, 9.8),
        linear_acceleration_covariance=acc_cov,
    )


def _bag(path: Path, msgtype: str, bad: dict[int, dict[str, float]], count: int = 5) -> Path:
    """A bag of ``count`` messages (record times 1 s, 2 s, ...), those of ``bad`` damaged;
    messages whose entry in ``bad`` is None are left out."""
    make = _odometry if msgtype == ODOM else _imu
    with Writer(path) as writer:
        conn = writer.add_connection("/topic", msgtype, typestore=STORE)
        for k in range(count):
            msg = make(k, bad.get(k, {}))
            writer.write(conn, (k + 1) * 10**9, STORE.serialize_ros1(msg, msgtype))
    return path


READERS = {ODOM: read_bag_odometry, IMU: read_bag_imu}
FIELDS = {
    ODOM: ("times", "record_times", "poses", "orientations", "twists", "pose_covariances",
           "twist_covariances"),
    IMU: ("times", "record_times", "orientations", "angular_velocities", "linear_accelerations",
          "orientation_covariances", "angular_velocity_covariances",
          "linear_acceleration_covariances"),
}  # fmt: skip
CASES = [
    (ODOM, {1: {"position": math.nan}, 3: {"twist": math.inf}}, "position"),
    (ODOM, {2: {"pose covariance": -math.inf}}, "pose covariance"),
    (IMU, {1: {"angular velocity": math.nan}}, "angular velocity"),
    (IMU, {2: {"linear acceleration covariance": math.nan}, 4: {"angular velocity": math.inf}},
     "linear acceleration covariance"),
]  # fmt: skip


@pytest.mark.parametrize(("msgtype", "bad", "what"), CASES)
def test_a_non_finite_message_is_refused_naming_its_index_and_record_time(
    tmp_path: Path, msgtype: str, bad: dict[int, dict[str, float]], what: str
) -> None:
    path = _bag(tmp_path / "bad.bag", msgtype, bad)
    first = min(bad)
    message = (
        f"{path}: message {first} of /topic has a non-finite {what} (recorded at "
        f"{first + 1}.000000000 s); skip_nonfinite=True leaves such messages out"
    )
    with pytest.raises(ValueError, match="^" + re.escape(message) + "$"):
        READERS[msgtype](path)


def test_the_first_bad_message_is_named_whichever_field_is_bad(tmp_path: Path) -> None:
    # Message 1's bad field (a covariance) comes after message 2's (its position) in the
    # order the fields were checked: the error named message 2, not the first bad one.
    bad = {1: {"pose covariance": math.nan}, 2: {"position": math.nan}}
    path = _bag(tmp_path / "bad.bag", ODOM, bad)
    with pytest.raises(ValueError, match=r"message 1 of /topic has a non-finite pose covariance "):
        read_bag_odometry(path)


@pytest.mark.parametrize(("msgtype", "bad", "what"), CASES)
def test_skip_nonfinite_leaves_the_bad_messages_out_and_says_so(
    tmp_path: Path, msgtype: str, bad: dict[int, dict[str, float]], what: str
) -> None:
    path = _bag(tmp_path / "bad.bag", msgtype, bad)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        got = READERS[msgtype](path, skip_nonfinite=True)
    assert [w.category for w in caught] == [RuntimeWarning]
    assert caught[0].filename == __file__  # the caller's line, not navkit's
    first = min(bad)
    assert str(caught[0].message) == (
        f"{path}: left out {len(bad)} of the 5 messages of /topic holding a NaN or infinity "
        f"(skip_nonfinite=True); the first: message {first}, recorded at {first + 1}.000000000 "
        f"s, its {what}"
    )
    # The same as the bag's sound messages, read from a bag of them alone.
    kept = [k for k in range(5) if k not in bad]
    assert got.record_times.tolist() == [k + 1.0 for k in kept]
    whole = READERS[msgtype](_bag(tmp_path / "sound.bag", msgtype, {}))
    for name in FIELDS[msgtype]:
        np.testing.assert_array_equal(getattr(got, name), getattr(whole, name)[kept], name)
    assert got.frame_id == whole.frame_id


def test_every_message_bad_leaves_an_empty_result(tmp_path: Path) -> None:
    path = _bag(tmp_path / "bad.bag", IMU, {k: {"angular velocity": math.nan} for k in range(3)}, 3)
    with pytest.warns(RuntimeWarning, match="left out 3 of the 3 messages"):
        got = read_bag_imu(path, skip_nonfinite=True)
    assert len(got) == 0
    assert got.angular_velocities.shape == (0, 3)


@pytest.mark.parametrize("msgtype", [ODOM, IMU])
def test_skip_nonfinite_on_a_sound_bag_changes_nothing_and_warns_nothing(
    tmp_path: Path, msgtype: str
) -> None:
    path = _bag(tmp_path / "sound.bag", msgtype, {})
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        got = READERS[msgtype](path, skip_nonfinite=True)
    whole = READERS[msgtype](path)
    for name in FIELDS[msgtype]:
        assert getattr(got, name).tobytes() == getattr(whole, name).tobytes(), name


@pytest.mark.parametrize("value", [1, 0, "no", None, np.array([True])])
@pytest.mark.parametrize("msgtype", [ODOM, IMU])
def test_skip_nonfinite_must_be_a_bool(tmp_path: Path, msgtype: str, value: Any) -> None:
    path = _bag(tmp_path / "sound.bag", msgtype, {}, 1)
    with pytest.raises(TypeError, match=r"^skip_nonfinite must be a bool, got "):
        READERS[msgtype](path, skip_nonfinite=value)
    assert len(READERS[msgtype](path, skip_nonfinite=np.bool_(True))) == 1


def test_the_real_bags_read_the_same_with_skip_nonfinite(shared_data: Path) -> None:
    path = shared_data / RL / "test2.bag"
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        odom = read_bag_odometry(path, skip_nonfinite=True)
        imu = read_bag_imu(path, topic="/imu/data", skip_nonfinite=True)
    assert odom.poses.tobytes() == read_bag_odometry(path).poses.tobytes()
    assert (
        imu.orientations.tobytes() == read_bag_imu(path, topic="/imu/data").orientations.tobytes()
    )
