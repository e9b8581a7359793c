"""The conventions the estimation guide now states, checked on the code.

* Batch rows: readings or measurements in, one row per input row out (the state
  after it; the state before the log is not a row): ``DiffOdometry.update_batch``
  and ``PlanarFusion.update_batch``. Increments in, T + 1 rows out with the
  start as row 0: ``OmniOdometry.update_batch`` and ``geometry.rollout``.
* Gates: ``ExtendedKalmanFilter.update(gate=)`` is the NIS threshold,
  ``PlanarFusion(gate_probability=)`` a probability; the same gate in both is
  ``gate = chi2.ppf(gate_probability, m)``.
"""

from __future__ import annotations

import numpy as np
import pytest
from scipy.stats import chi2

from navkit.estimation import (
    DiffOdometry,
    ExtendedKalmanFilter,
    MeasurementLog,
    OmniOdometry,
    PlanarFusion,
)
from navkit.geometry import Pose2D, rollout
from navkit.kinematics import DiffDrive, OmniDrive

T = 4


def test_readings_and_measurements_give_one_row_each_after_it() -> None:
    odo = DiffOdometry(DiffDrive(track=0.5, wheel_radius=0.1), ticks_per_rev=1000)
    ticks = [0, 500, 1000, 1500]
    poses = odo.update_batch(ticks, ticks)
    assert poses.shape == (T, 3)
    # The first reading latches the counters: its row is the pose before the log.
    np.testing.assert_allclose(poses[:, 0], [0.0, 0.1 * np.pi, 0.2 * np.pi, 0.3 * np.pi])

    fusion = PlanarFusion(t0=0.0)
    before = fusion.x.copy()
    times = 0.1 * np.arange(1, T + 1)
    log = MeasurementLog.from_streams(odometry=(times, np.ones(T), np.zeros(T)))
    result = fusion.update_batch(log)
    assert result.states.shape == (T, 6) and result.times.tolist() == times.tolist()
    # Row 0 is the state after the first measurement (0.1 s at 1 m/s), not x0.
    assert result.states[0, 0] > 0.05 and before[0] == 0.0
    np.testing.assert_array_equal(result.states[-1], fusion.x)


def test_increments_give_the_start_as_row_zero() -> None:
    drive = OmniDrive.three_wheel(wheel_radius=0.05, base_radius=0.2)
    start = Pose2D(1.0, 2.0, 0.0)
    odo = OmniOdometry(drive, pose=start)
    step = drive.inverse([1.0, 0.0, 0.0]) * 0.1
    poses = odo.update_batch([step] * T, [0.0] * T)
    assert poses.shape == (T + 1, 3)
    np.testing.assert_array_equal(poses[0], start.as_array())
    np.testing.assert_allclose(poses[:, 0], 1.0 + 0.1 * np.arange(T + 1), atol=1e-12)

    traj = rollout(start, [[1.0, 0.0, 0.0]] * T, 0.1)
    assert traj.shape == (T + 1, 3)
    np.testing.assert_array_equal(traj[0], start.as_array())
    np.testing.assert_allclose(traj[:, 0], poses[:, 0], atol=1e-12)


@pytest.mark.parametrize("probability", [0.9, 0.997])
def test_gate_is_the_quantile_of_gate_probability(probability: float) -> None:
    # One yaw measurement, no prediction (t equals the filter time): NIS = y² / (p + r).
    p, r = 0.04, 0.01
    threshold = float(chi2.ppf(probability, 1))
    edge = float(np.sqrt(threshold * (p + r)))
    for y in (0.99 * edge, 1.01 * edge):
        x0 = np.zeros(6)
        P0 = np.diag([1e-9, 1e-9, p, 1.0, 1.0, 1.0])
        fusion = PlanarFusion(x0, P0, t0=0.0, gate_probability=probability)
        fused = fusion.update_yaw(0.0, y, variance=r)
        ekf = ExtendedKalmanFilter([0.0], [[p]])
        general = ekf.update([y], lambda x: x[:1], np.array([[1.0]]), [[r]], gate=threshold)
        assert fused.accepted == general.accepted == (y < edge)
        assert fused.nis == pytest.approx(general.nis, rel=1e-12)
