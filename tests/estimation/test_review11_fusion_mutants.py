"""FusionResult.final_pose is the pose after the LAST row (mutation testing).

No test ran ``final_pose`` on a result whose rows moved the robot, so taking the
first row's pose went unnoticed.
"""

from __future__ import annotations

import numpy as np
import pytest

from navkit.estimation import FusionResult, MeasurementLog, PlanarFusion


def test_final_pose_is_the_state_after_the_last_row() -> None:
    # 1 m/s straight ahead for 1 s, odometry every 0.1 s: the robot moves along x.
    times = np.arange(1, 11) * 0.1
    log = MeasurementLog.from_streams(odometry=(times, np.ones(10), np.zeros(10)))
    result = PlanarFusion(t0=0.0).update_batch(log)
    assert result.accepted.all()
    first, last = result.states[0, :3], result.states[-1, :3]
    assert last[0] > first[0] + 0.5  # the rows really moved the pose
    pose = result.final_pose
    assert (pose.x, pose.y, pose.theta) == pytest.approx(tuple(last.tolist()), abs=0.0)


def test_final_pose_of_a_built_result_reads_its_last_row() -> None:
    states = np.zeros((3, 6))
    states[:, 0] = [1.0, 2.0, 3.0]
    states[:, 2] = [0.1, 0.2, 0.3]
    result = FusionResult(
        times=np.array([0.0, 1.0, 2.0]),
        states=states,
        covariances=np.tile(np.eye(6), (3, 1, 1)),
        status=np.zeros(3, dtype=np.int8),
        nis=np.zeros(3),
    )
    pose = result.final_pose
    assert (pose.x, pose.y, pose.theta) == (3.0, 0.0, 0.3)


@pytest.mark.parametrize("prob", [0.0, 1.0])
def test_gate_probability_ends_are_refused(prob: float) -> None:
    # "gate_probability must be in (0, 1)": 0 or 1 would give zero or infinite gates.
    with pytest.raises(ValueError, match="gate_probability"):
        PlanarFusion(gate_probability=prob)


def test_predicting_to_the_filter_time_is_a_no_op() -> None:
    fusion = PlanarFusion(t0=1.0)
    fusion.update_odometry(1.5, 1.0, 0.0, v_variance=0.01, omega_variance=0.01)
    before = (fusion.x, fusion.P, fusion.t)
    fusion.predict(1.5)  # not older than the filter time: nothing to do, no error
    np.testing.assert_array_equal(fusion.x, before[0])
    np.testing.assert_array_equal(fusion.P, before[1])
    assert fusion.t == before[2] == 1.5


def test_stream_variances_at_the_documented_limits_are_accepted() -> None:
    # Variances "in [1e-100, 1e100]": both ends included.
    for variance in (1e-100, 1e100):
        log = MeasurementLog.from_streams(
            yaw=([0.0], [0.1]), yaw_variance=variance,
            odometry=([0.1], [1.0], [0.0]), odometry_variance=(variance, variance),
        )  # fmt: skip
        assert log.variances[0, 0] == variance
        assert log.variances[1, 1] == log.variances[1, 2] == variance


def test_odometry_variance_must_be_a_pair() -> None:
    with pytest.raises(ValueError, match="odometry_variance must be a pair"):
        MeasurementLog.from_streams(
            odometry=([0.1], [1.0], [0.0]), odometry_variance=(0.01, 0.01, 0.01),  # type: ignore[arg-type]
        )
