"""The angle convention at its boundary in the estimators.

Every heading an estimator stores or returns lies in (-π, π] (-π never), a yaw
given at π or at -π is the same yaw, and every heading difference (residuals,
mid-step headings) is taken across the cut: from 3.1 to -3.1 is +0.083 rad.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from navkit.estimation import (
    CompassCalibration,
    DiffOdometry,
    ExtendedKalmanFilter,
    MeasurementLog,
    OmniOdometry,
    PlanarFusion,
    compass_to_yaw,
)
from navkit.geometry import angle_diff, wrap_angle
from navkit.kinematics import DiffDrive, OmniDrive

PI = math.pi
BIG = 1.7e308
CUT = 2.0 * PI - 6.2  # from 3.1 to -3.1, counter-clockwise: 0.0832 rad
SPECIAL = (
    PI, -PI, float(np.nextafter(PI, 0.0)), float(np.nextafter(-PI, 0.0)),
    float(np.nextafter(PI, 4.0)), float(np.nextafter(-PI, -4.0)),
    2.0 * PI, -2.0 * PI, 1e6 * PI, 1e15, -1e15, 3.1, -3.1, 0.0,
)  # fmt: skip
angles = st.one_of(st.sampled_from(SPECIAL), st.floats(-10.0, 10.0), st.floats(-1e15, 1e15))


def in_range(a: float) -> bool:
    return -PI < a <= PI


def _identity(x: np.ndarray) -> np.ndarray:
    return x.copy()


# ---------------------------------------------------------------- EKF
@pytest.mark.parametrize(("z", "hx"), [(BIG, -BIG), (-BIG, BIG), (1.7976931348623157e308, -1e308)])
def test_ekf_angle_residual_of_huge_angles_is_their_wrapped_difference(z: float, hx: float) -> None:
    # z - h(x) overflows float64, but the angle it stands for does not: the update
    # uses angle_diff(z, h(x)), as PlanarFusion's yaw (whose θ is wrapped) always can.
    ekf = ExtendedKalmanFilter([1.0], [[0.1]])
    result = ekf.update([z], lambda x: np.array([hx]), np.eye(1), [[0.1]], angle_measurements=[0])
    expected = angle_diff(z, hx)
    assert result.accepted
    assert result.residual.tolist() == [expected]
    assert in_range(float(result.residual[0]))
    assert float(ekf.x[0]) == pytest.approx(1.0 + 0.5 * expected, rel=1e-12)


def test_ekf_non_angle_residual_overflow_is_still_refused() -> None:
    ekf = ExtendedKalmanFilter([1.0], [[0.1]])
    result = ekf.update([BIG], lambda x: np.array([-BIG]), np.eye(1), [[0.1]])
    assert not result.accepted and result.nis == math.inf and result.residual.shape == (0,)
    assert float(ekf.x[0]) == 1.0


@settings(max_examples=80, deadline=None)
@given(angles, angles)
def test_ekf_angles_stay_in_range_and_residuals_cross_the_cut(x0: float, z: float) -> None:
    ekf = ExtendedKalmanFilter([x0], [[0.1]], angle_states=[0])
    assert float(ekf.x[0]) == wrap_angle(x0)
    ekf.predict(lambda x: x + 0.05, np.eye(1), 0.01 * np.eye(1))
    before = float(ekf.x[0])
    assert in_range(before)
    assert before == wrap_angle(wrap_angle(x0) + 0.05)
    result = ekf.update([z], _identity, np.eye(1), [[0.1]], angle_measurements=[0])
    assert result.residual.tolist() == [angle_diff(z, before)]
    assert in_range(float(ekf.x[0]))


def test_ekf_residual_from_3_1_to_minus_3_1_is_small() -> None:
    ekf = ExtendedKalmanFilter([3.1], [[0.1]], angle_states=[0])
    result = ekf.update([-3.1], _identity, np.eye(1), [[0.1]], angle_measurements=[0])
    assert float(result.residual[0]) == pytest.approx(CUT, abs=1e-15)
    assert float(ekf.x[0]) == pytest.approx(3.1 + 0.5 * CUT, abs=1e-15)


def test_ekf_measurement_at_pi_and_at_minus_pi_is_one_measurement() -> None:
    results = []
    for z in (PI, -PI):
        ekf = ExtendedKalmanFilter([-3.0], [[0.1]], angle_states=[0])
        res = ekf.update([z], _identity, np.eye(1), [[0.1]], angle_measurements=[0])
        results.append((res.residual.tolist(), float(ekf.x[0])))
    assert results[0][0] == pytest.approx(results[1][0], abs=1e-15)
    assert results[0][1] == pytest.approx(results[1][1], abs=1e-15)


# ---------------------------------------------------------------- PlanarFusion
@settings(max_examples=60, deadline=None)
@given(angles, angles, st.floats(-50.0, 50.0))
def test_fusion_headings_stay_in_range(theta0: float, yaw: float, omega: float) -> None:
    fusion = PlanarFusion(x0=[0.0, 0.0, theta0, 0.5, omega, 0.0], t0=0.0)
    assert fusion.pose.theta == wrap_angle(theta0)
    fusion.predict(0.1)
    predicted = fusion.pose.theta
    assert in_range(predicted)
    result = fusion.update_yaw(0.1, yaw, variance=0.1)
    assert result.residual.tolist() == [angle_diff(yaw, predicted)]
    assert in_range(fusion.pose.theta)


def test_fusion_yaw_at_pi_and_at_minus_pi_is_one_yaw() -> None:
    outcomes = []
    for yaw in (PI, -PI, float(np.float32(-PI)) + 0.0):
        fusion = PlanarFusion(x0=[0.0, 0.0, -3.1, 0.0, 0.0, 0.0], t0=0.0)
        res = fusion.update_yaw(0.0, yaw, variance=0.1)
        outcomes.append((float(res.residual[0]), fusion.pose.theta))
    # π + 3.1 is rounded before it is wrapped: the same yaw to rounding.
    assert outcomes[0] == pytest.approx(outcomes[1], abs=1e-15)
    # float32(-π) lies 8.7e-8 rad beyond the cut: the same yaw to that much.
    assert outcomes[2][0] == pytest.approx(outcomes[0][0], abs=1e-7)


def test_fusion_batch_yaws_across_the_cut_match_the_online_updates() -> None:
    yaws = [3.1, -3.1, PI, -PI, (1e6 + 1) * PI, np.float32(-PI)]  # all near the cut
    times = np.arange(1, len(yaws) + 1) * 0.1
    online = PlanarFusion(x0=[0.0, 0.0, 3.0, 0.0, 0.0, 0.0], t0=0.0)
    thetas = [online.update_yaw(t, float(y), variance=0.01) and online.pose.theta
              for t, y in zip(times.tolist(), yaws, strict=True)]  # fmt: skip
    batch = PlanarFusion(x0=[0.0, 0.0, 3.0, 0.0, 0.0, 0.0], t0=0.0)
    result = batch.update_batch(
        MeasurementLog.from_streams(
            yaw=(times, np.array(yaws, dtype=np.float64)), yaw_variance=0.01
        )
    )
    assert result.states[:, 2].tolist() == thetas
    assert all(in_range(t) for t in thetas)
    # Each yaw pulls toward the measured heading the short way round: never far from ±π.
    assert min(abs(t) for t in thetas) > 2.9


# ---------------------------------------------------------------- odometry
def _omni() -> OmniDrive:
    return OmniDrive.three_wheel(wheel_radius=0.05, base_radius=0.2)


@pytest.mark.parametrize("yaw", [PI, -PI, 3.0 * PI, -3.0 * PI])
def test_omni_odometry_yaw_at_the_cut_is_plus_pi(yaw: float) -> None:
    drive = _omni()
    step = drive.inverse([1.0, 0.0, 0.0]) * 0.1
    odo = OmniOdometry(drive, pose=(0.0, 0.0, 3.0))
    pose = odo.update(step, yaw)
    assert pose.theta == wrap_angle(yaw)
    assert in_range(pose.theta)
    batch = OmniOdometry(drive, pose=(0.0, 0.0, 3.0)).update_batch(step[None, :], [yaw])
    assert batch[-1].tolist() == [pose.x, pose.y, pose.theta]


def test_omni_odometry_turning_across_the_cut_moves_along_the_mid_heading() -> None:
    # From heading 3.1 to -3.1 (a 0.083 rad turn through π): the step is rotated by
    # about π, so 0.1 m ahead moves the robot to x ≈ -0.1, not along heading 0.
    drive = _omni()
    step = drive.inverse([1.0, 0.0, 0.0]) * 0.1
    for pose in (
        OmniOdometry(drive, pose=(0.0, 0.0, 3.1)).update(step, -3.1),
        OmniOdometry(drive, pose=(0.0, 0.0, -3.1)).update(step, 3.1),
    ):
        assert pose.x == pytest.approx(-0.1, abs=1e-12)
        assert abs(pose.y) < 1e-12
    rows = OmniOdometry(drive, pose=(0.0, 0.0, 3.1)).update_batch([step, step], [-3.1, 3.1])
    assert rows[1:, 0].tolist() == pytest.approx([-0.1, -0.2], abs=1e-12)
    assert np.abs(rows[1:, 1]).max() < 1e-12


def test_diff_odometry_turning_past_pi_stays_wrapped() -> None:
    # Right wheel only: each reading turns the robot by 0.3 rad; 40 readings turn it
    # past ±π almost twice. Online and batch agree (to the rounding of their sums),
    # all headings in (-π, π].
    drive = DiffDrive(track=0.5, wheel_radius=0.1)
    right = np.arange(41) * 240
    left = np.zeros(41, dtype=np.int64)
    online = DiffOdometry(drive, ticks_per_rev=1000, pose=(0.0, 0.0, 3.0))
    poses = [online.update(int(a), int(b)) for a, b in zip(left, right, strict=True)]
    batch = DiffOdometry(drive, ticks_per_rev=1000, pose=(0.0, 0.0, 3.0)).update_batch(left, right)
    for row, pose in zip(batch.tolist(), poses, strict=True):
        assert row[:2] == pytest.approx([pose.x, pose.y], abs=1e-12)
        assert abs(angle_diff(row[2], pose.theta)) < 1e-12
        assert in_range(row[2]) and in_range(pose.theta)
    turn = 2 * PI * 0.1 * 240 / 1000 / 0.5
    for k in range(41):
        assert abs(angle_diff(float(batch[k, 2]), 3.0 + k * turn)) < 1e-12


# ---------------------------------------------------------------- compass
@settings(max_examples=150, deadline=None)
@given(
    st.one_of(st.floats(-1e20, 1e20), st.sampled_from([180.0, -180.0, 540.0, 179.99999999999997])),
    st.one_of(st.floats(-1e6, 1e6), st.sampled_from([0.0, 180.0, -180.0])),
    st.sampled_from([np.float64, np.float32]),
)
def test_compass_yaws_stay_in_range(raw: float, initial: float, dtype: type) -> None:
    reading = dtype(raw)
    yaw = compass_to_yaw(reading, initial_deg=initial)
    assert in_range(yaw)
    assert compass_to_yaw(np.array([reading]), initial_deg=initial).tolist() == [yaw]


def test_compass_half_turn_is_plus_pi() -> None:
    assert compass_to_yaw(180.0) == PI
    assert compass_to_yaw(-180.0) == PI
    assert compass_to_yaw(10.0, initial_deg=190.0) == PI
    cal = CompassCalibration()
    assert cal(20.0) == 0.0
    assert cal(200.0) == PI
