"""Quaternion helpers against scipy.spatial.transform.Rotation."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays
from scipy.spatial.transform import Rotation

from hypothesis_twins import slow_twin
from navkit.geometry import (
    ImuInBase,
    imu_to_base,
    quaternion_to_matrix,
    quaternion_to_yaw,
    rpy_to_quaternion,
    wrap_angle,
    yaw_to_quaternion,
)

component = st.floats(-10.0, 10.0, allow_nan=False)
quaternions = arrays(
    np.float64, st.tuples(st.integers(1, 6), st.just(4)), elements=component
).filter(lambda q: bool(np.all(np.linalg.norm(q, axis=1) > 1e-3)))
vectors3 = st.floats(-100.0, 100.0, allow_nan=False)
angle = st.floats(-10.0, 10.0, allow_nan=False)


@pytest.mark.filterwarnings("ignore:Gimbal lock detected")
@settings(max_examples=40)
@given(quaternions)
def test_yaw_matches_scipy_zyx_euler(q: np.ndarray) -> None:
    rot = Rotation.from_quat(q)
    yaw, pitch, _ = rot.as_euler("ZYX").T
    keep = np.abs(np.cos(pitch)) > 1e-3  # away from gimbal lock, where yaw is undefined
    got = quaternion_to_yaw(q)
    assert got.shape == (q.shape[0],)
    assert np.all((got > -math.pi) & (got <= math.pi))
    diff = wrap_angle(got[keep] - yaw[keep])
    np.testing.assert_allclose(diff, 0.0, atol=1e-6)


test_yaw_matches_scipy_zyx_euler_thoroughly = slow_twin(
    test_yaw_matches_scipy_zyx_euler, max_examples=100
)


@settings(max_examples=40)
@given(quaternions)
def test_matrix_matches_scipy(q: np.ndarray) -> None:
    np.testing.assert_allclose(
        quaternion_to_matrix(q), Rotation.from_quat(q).as_matrix(), atol=1e-12
    )


test_matrix_matches_scipy_thoroughly = slow_twin(test_matrix_matches_scipy, max_examples=100)


@settings(max_examples=40)
@given(arrays(np.float64, st.integers(1, 5), elements=angle), st.data())
def test_rpy_matches_scipy(roll: np.ndarray, data: st.DataObject) -> None:
    n = roll.shape[0]
    pitch = data.draw(arrays(np.float64, n, elements=angle))
    yaw = data.draw(arrays(np.float64, n, elements=angle))
    q = rpy_to_quaternion(roll, pitch, yaw)
    expected = Rotation.from_euler("ZYX", np.column_stack((yaw, pitch, roll))).as_matrix()
    np.testing.assert_allclose(quaternion_to_matrix(q), expected, atol=1e-12)
    np.testing.assert_allclose(np.linalg.norm(q, axis=-1), 1.0, atol=1e-12)


test_rpy_matches_scipy_thoroughly = slow_twin(test_rpy_matches_scipy, max_examples=100)


@given(angle)
def test_yaw_round_trip(yaw: float) -> None:
    back = quaternion_to_yaw(yaw_to_quaternion(yaw))
    assert isinstance(back, float)
    assert back == pytest.approx(float(wrap_angle(yaw)), abs=1e-12) or abs(back) == pytest.approx(
        math.pi
    )


@settings(max_examples=50)
@given(quaternions, st.data())
def test_imu_to_base_matches_scipy(q: np.ndarray, data: st.DataObject) -> None:
    n = q.shape[0]
    mount_q = data.draw(quaternions.filter(lambda m: m.shape[0] == 1))[0]
    w = data.draw(arrays(np.float64, (n, 3), elements=vectors3))
    a = data.draw(arrays(np.float64, (n, 3), elements=vectors3))
    q_before, w_before = q.copy(), w.copy()
    out = imu_to_base(q, w, a, mount=mount_q)
    mount = Rotation.from_quat(mount_q)
    np.testing.assert_allclose(out.angular_velocities, mount.apply(w), atol=1e-9)
    np.testing.assert_allclose(out.linear_accelerations, mount.apply(a), atol=1e-9)
    expected = (Rotation.from_quat(q) * mount.inv()).as_matrix()
    np.testing.assert_allclose(quaternion_to_matrix(out.orientations), expected, atol=1e-9)
    np.testing.assert_allclose(np.linalg.norm(out.orientations, axis=-1), 1.0, atol=1e-12)
    np.testing.assert_array_equal(q, q_before)  # inputs untouched
    np.testing.assert_array_equal(w, w_before)
    assert not out.orientations.flags.writeable


def test_zero_quaternion_is_no_rotation() -> None:
    assert quaternion_to_yaw([0.0, 0.0, 0.0, 0.0]) == 0.0
    np.testing.assert_array_equal(quaternion_to_matrix(np.zeros(4)), np.eye(3))


def test_huge_and_tiny_quaternions_normalise() -> None:
    q = np.array([0.0, 0.0, math.sin(0.3), math.cos(0.3)])
    for scale in (1e-300, 1e300):
        assert quaternion_to_yaw(q * scale) == pytest.approx(0.6)


def test_yaw_at_pi_is_positive() -> None:
    assert quaternion_to_yaw([0.0, 0.0, 1.0, -0.0]) == math.pi
    assert quaternion_to_yaw([0.0, 0.0, 1.0, 0.0]) == math.pi


def test_gimbal_lock_gives_zero_yaw() -> None:
    assert quaternion_to_yaw(rpy_to_quaternion(0.0, math.pi / 2, 0.0)) == 0.0


def test_husky_mounting() -> None:
    """robot_localization's test1: roll +90°, yaw -90° puts the IMU's y axis along the robot's z."""
    mount = rpy_to_quaternion(math.pi / 2, 0.0, -math.pi / 2)
    rot = quaternion_to_matrix(mount)
    expected = Rotation.from_euler("xyz", [math.pi / 2, 0.0, -math.pi / 2]).as_matrix()
    np.testing.assert_allclose(rot, expected, atol=1e-12)
    # A gyro turning about the IMU's y axis is the robot turning about its z axis.
    out = imu_to_base([0.0, 0.0, 0.0, 1.0], [0.0, 0.3, 0.0], [0.0, 9.8, 0.0], mount=mount)
    np.testing.assert_allclose(out.angular_velocities, [0.0, 0.0, 0.3], atol=1e-12)
    np.testing.assert_allclose(out.linear_accelerations, [0.0, 0.0, 9.8], atol=1e-12)


@pytest.mark.parametrize(
    ("call", "error", "name"),
    [
        (lambda: quaternion_to_yaw([1.0, 2.0, 3.0]), ValueError, "quaternion"),
        (lambda: quaternion_to_yaw([0.0, 0.0, math.nan, 1.0]), ValueError, "quaternion"),
        (lambda: quaternion_to_yaw("abcd"), TypeError, "quaternion"),
        (lambda: quaternion_to_matrix([[1 + 1j, 0, 0, 0]]), TypeError, "quaternion"),
        (lambda: yaw_to_quaternion(math.inf), ValueError, "yaw"),
        (lambda: rpy_to_quaternion([0.0, 1.0], [0.0, 1.0, 2.0], 0.0), ValueError, "broadcast"),
        (lambda: rpy_to_quaternion(True, 0.0, 0.0), TypeError, "roll"),
        (
            lambda: imu_to_base([0, 0, 0, 1], [0, 0, 0], [0, 0, 0], mount=[0, 0, 0, 0]),
            ValueError,
            "mount",
        ),
        (
            lambda: imu_to_base(
                [[0, 0, 0, 1]], [[0, 0, 0]] * 2, [[0, 0, 0]], mount=[0, 0, 0, 1]
            ),
            ValueError,
            "angular_velocities",
        ),
        (
            lambda: imu_to_base([0, 0, 0, 1], [0, 0, 0], [0, 0], mount=[0, 0, 0, 1]),
            ValueError,
            "linear_accelerations",
        ),
        (lambda: ImuInBase([0, 0, 0, 1], [0, 0, 0], [[0, 0, 0]]), ValueError, "linear_acc"),
        (lambda: ImuInBase([0, 0, 1], [0, 0, 0], [0, 0, 0]), ValueError, "orientations"),
    ],
)
def test_bad_input_names_the_argument(call, error, name) -> None:  # type: ignore[no-untyped-def]
    with pytest.raises(error, match=name):
        call()


def test_imu_in_base_holds_unit_quaternions() -> None:
    """The attribute is documented as unit quaternions: normalised like every input here."""
    zeros = np.zeros((2, 3))
    readings = ImuInBase([[0.0, 0.0, 0.6, 1.6], [0.0, 0.0, 0.0, 0.0]], zeros, zeros)
    np.testing.assert_allclose(np.linalg.norm(readings.orientations, axis=-1), 1.0, atol=1e-15)
    np.testing.assert_array_equal(readings.orientations[1], [0.0, 0.0, 0.0, 1.0])
    assert quaternion_to_yaw(readings.orientations[0]) == pytest.approx(2 * math.atan2(0.6, 1.6))


def test_imu_in_base_copies_and_pickles_stay_read_only() -> None:
    import copy
    import pickle

    readings = ImuInBase(
        np.array([[0.0, 0.0, 0.6, 0.8]]), np.array([[0.0, 0.0, 0.1]]), np.array([[0.0, 0.0, 9.8]])
    )
    twins = (copy.copy(readings), copy.deepcopy(readings), pickle.loads(pickle.dumps(readings)))
    for twin in twins:
        for name in ("orientations", "angular_velocities", "linear_accelerations"):
            arr = getattr(twin, name)
            assert not arr.flags.writeable, name
            np.testing.assert_array_equal(arr, getattr(readings, name))
