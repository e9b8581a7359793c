"""Review 9 (mutation testing, second pass): filter promises the existing tests left open.

Each test states the documented behaviour it pins down; references are computed
independently of navkit.
"""

from __future__ import annotations

from typing import Any

import numpy as np
import pytest

from navkit._shared.types import FloatArray
from navkit.estimation import ExtendedKalmanFilter


def _h2(x: FloatArray) -> FloatArray:
    out: FloatArray = x[:2].copy()
    return out


def _h1(x: FloatArray) -> FloatArray:
    out: FloatArray = x[:1].copy()
    return out


def test_ekf_angle_index_checked_again_for_a_smaller_measurement() -> None:
    # angle_measurements are indices of z: index 1 is valid for a 2-D measurement and
    # out of range for a 1-D one. The same tuple object, validated once for m = 2, must
    # not skip the range check when it comes back with m = 1 (the fast path keeps
    # validated tuples by identity).
    angles = (1,)
    ekf = ExtendedKalmanFilter(np.zeros(2), np.eye(2))
    h2 = np.eye(2)
    r2 = np.eye(2)
    for _ in range(2):
        assert ekf.update(np.array([0.1, 0.2]), _h2, h2, r2, angle_measurements=angles).accepted
    before_x, before_p = ekf.x.copy(), ekf.P.copy()
    with pytest.raises(ValueError, match="angle_measurements"):
        ekf.update(np.array([0.1]), _h1, np.array([[1.0, 0.0]]), np.array([[1.0]]),
                   angle_measurements=angles)
    np.testing.assert_array_equal(ekf.x, before_x)
    np.testing.assert_array_equal(ekf.P, before_p)


def test_ekf_angle_list_changed_in_place_is_read_again() -> None:
    # Only immutable options can stand for their values between calls: a list passed
    # again after being changed in place must be read (and checked) again, like any
    # other argument, never taken as the values it held last time.
    angles = [0]
    ekf = ExtendedKalmanFilter(np.zeros(1), np.eye(1))
    h = np.eye(1)
    r = np.eye(1)
    wrapped = ekf.update(np.array([3.0]), lambda x: x - 3.0, h, r, angle_measurements=angles)
    assert wrapped.residual[0] == pytest.approx(6.0 - 2.0 * np.pi)  # an angle: wrapped
    angles.clear()
    plain = ekf.update(np.array([3.0]), lambda x: x - 3.0, h, r, angle_measurements=angles)
    assert plain.residual[0] > np.pi  # 6 - x[0], x[0] near 0: no longer an angle, not wrapped
    angles.append(5)  # out of range for a 1-D measurement
    with pytest.raises(ValueError, match="angle_measurements"):
        ekf.update(np.array([3.0]), lambda x: x - 3.0, h, r, angle_measurements=angles)


def test_ekf_gate_array_changed_in_place_is_read_again() -> None:
    # As above for a gate given as a 0-d array: typed float, but any real number is
    # accepted at run time (positive_float), and this one is mutable.
    gate: Any = np.array(100.0)
    ekf = ExtendedKalmanFilter(np.zeros(1), np.eye(1))
    h = np.eye(1)
    r = np.eye(1)
    assert ekf.update(np.array([1.0]), lambda x: x.copy(), h, r, gate=gate).accepted
    gate[()] = 1e-6
    result = ekf.update(np.array([1.0]), lambda x: x.copy(), h, r, gate=gate)
    assert result.nis > 1e-6
    assert not result.accepted
    gate[()] = -1.0
    with pytest.raises(ValueError, match="gate"):
        ekf.update(np.array([1.0]), lambda x: x.copy(), h, r, gate=gate)


def test_ekf_predict_failing_after_f_modified_its_copy_leaves_the_state() -> None:
    # f gets "a copy of the state" which it "may modify", and a failed predict leaves
    # the state unchanged: f writing into its argument must not reach the filter.
    def f(x: FloatArray) -> FloatArray:
        x[0] = 99.0
        x[1] = -7.0
        return x

    ekf = ExtendedKalmanFilter(np.array([0.5, -0.25]), np.eye(2))
    before_x, before_p = ekf.x.copy(), ekf.P.copy()
    with pytest.raises(ValueError, match="Q"):
        ekf.predict(f, np.eye(2), np.array([[1.0, 0.0], [0.0, -1.0]]))  # Q not PSD
    np.testing.assert_array_equal(ekf.x, before_x)
    np.testing.assert_array_equal(ekf.P, before_p)
    # And with a valid Q the prediction is what f returned.
    ekf.predict(f, np.eye(2), np.zeros((2, 2)))
    np.testing.assert_array_equal(ekf.x, [99.0, -7.0])


def test_ekf_update_with_h_modifying_its_copy() -> None:
    # h is "called on a copy of the state (which it may modify)": the update is that of
    # the value h returned, from the filter's own state; a failed update changes nothing.
    def h(x: FloatArray) -> FloatArray:
        x[0] = 50.0
        out: FloatArray = x[:1].copy()
        return out

    hmat = np.array([[1.0, 0.0]])
    ekf = ExtendedKalmanFilter(np.array([1.0, 2.0]), np.diag([4.0, 1.0]))
    with pytest.raises(ValueError, match="R"):
        ekf.update(np.array([60.0]), h, hmat, np.array([[-1.0]]))
    np.testing.assert_array_equal(ekf.x, [1.0, 2.0])
    result = ekf.update(np.array([60.0]), h, hmat, np.array([[1.0]]))
    assert result.accepted
    gain = 4.0 / (4.0 + 1.0)
    assert result.residual[0] == 10.0  # z - h(x)
    assert ekf.x[0] == pytest.approx(1.0 + gain * 10.0, rel=1e-12)
    assert ekf.x[1] == 2.0


def test_omni_odometry_empty_log_changes_nothing() -> None:
    # update_batch of an empty log returns just row 0 (the pose before the log) and
    # keeps the pose given, as it is (a Pose2D subclass stays itself).
    from navkit.estimation import OmniOdometry
    from navkit.geometry import Pose2D
    from navkit.kinematics import OmniDrive

    class TaggedPose(Pose2D):
        pass

    start = TaggedPose(1.0, -2.0, 0.5)
    odo = OmniOdometry(OmniDrive.three_wheel(wheel_radius=0.05, base_radius=0.2), pose=start)
    rows = odo.update_batch(np.empty((0, 3)), np.empty(0))
    np.testing.assert_array_equal(rows, [[1.0, -2.0, 0.5]])
    assert odo.pose is start


@pytest.mark.parametrize("side", [1.0, -1.0])
def test_fusion_yaw_update_across_pi_keeps_the_heading_wrapped(side: float) -> None:
    # The heading is documented in (-π, π]. A yaw update that moves it across ±π (the
    # estimate just below π, the reading just past it) must wrap the updated heading;
    # here without a prediction (dt = 0), so the posterior is the scalar update
    # θ + P/(P + R) · wrap(z - θ).
    from navkit.estimation import PlanarFusion

    theta = side * (np.pi - 0.01)
    reading = -side * (np.pi - 0.01)  # 0.02 rad further on, across ±π
    prior, r = 1.0, 1e-4
    fusion = PlanarFusion([0.0, 0.0, theta, 0.0, 0.0, 0.0], [1e-9, 1e-9, prior, 1.0, 1.0, 1.0],
                          t0=0.0)
    result = fusion.update_yaw(0.0, reading, variance=r)
    assert result.accepted
    assert result.residual[0] == pytest.approx(side * 0.02, abs=1e-12)
    unwrapped = theta + prior / (prior + r) * side * 0.02
    expected = unwrapped - side * 2.0 * np.pi
    assert -np.pi < fusion.x[2] <= np.pi
    assert fusion.x[2] == pytest.approx(expected, abs=1e-12)
    assert fusion.pose.theta == fusion.x[2]


def test_fusion_nis_exactly_at_the_gate_is_accepted() -> None:
    # Documented: reject measurements whose NIS *exceeds* the chi-square quantile.
    # With P_vv = R = 1/2, S = 1 exactly and the NIS of a speed reading y (state
    # v = 0, no prediction) is y·y; a y whose square is exactly the 1-dof quantile
    # 2·gammaincinv(1/2, p) (scipy.stats.chi2.ppf's formula) sits on the gate.
    from scipy.special import gammaincinv

    from navkit.estimation import PlanarFusion

    cases = 0
    for p in (0.5, 0.6, 0.7, 0.8, 0.9, 0.95, 0.99, 0.997, 0.999):
        gate = float(2.0 * gammaincinv(0.5, p))
        y = float(np.sqrt(gate))
        if y * y != gate:
            continue
        cases += 1
        for reading, accepted in ((y, True), (float(np.nextafter(y, np.inf)), False)):
            fusion = PlanarFusion(P0=[1e-9, 1e-9, 1e-9, 0.5, 1.0, 1.0], t0=0.0,
                                  gate_probability=p)
            result = fusion.update_speed(0.0, reading, variance=0.5)
            assert result.nis == reading * reading
            assert result.accepted is accepted
            assert bool(fusion.x[3] != 0.0) is accepted
    assert cases >= 2


def test_ekf_noise_changed_in_place_anywhere_is_used() -> None:
    # Q and R are read at every call: a change of any entry of the caller's matrix
    # between calls (not only the first) is used, and an invalid one is refused.
    ekf = ExtendedKalmanFilter(np.zeros(2), np.eye(2))
    q = np.diag([0.1, 0.2])
    for _ in range(2):
        ekf.predict(lambda x: x, np.eye(2), q)
    before = ekf.P.copy()
    q[1, 1] = 5.0
    ekf.predict(lambda x: x, np.eye(2), q)
    np.testing.assert_allclose(ekf.P, before + np.diag([0.1, 5.0]), rtol=1e-15)
    q[1, 1] = -1.0
    with pytest.raises(ValueError, match="Q"):
        ekf.predict(lambda x: x, np.eye(2), q)

    ekf = ExtendedKalmanFilter(np.zeros(2), np.eye(2))
    r = np.diag([1.0, 1.0])
    for _ in range(2):
        ekf.update(np.zeros(2), _h2, np.eye(2), r)
    p_before = ekf.P.copy()
    r[1, 1] = 1e6  # a reading of component 1 now carries next to no information
    result = ekf.update(np.array([0.0, 10.0]), _h2, np.eye(2), r)
    s11 = p_before[1, 1] + 1e6
    assert result.nis == pytest.approx(100.0 / s11, rel=1e-12)
    assert ekf.x[1] == pytest.approx(p_before[1, 1] / s11 * 10.0, rel=1e-12)
    r[1, 1] = 0.0
    with pytest.raises(ValueError, match="R"):
        ekf.update(np.zeros(2), _h2, np.eye(2), r)


@pytest.mark.parametrize("indices", [(-1,), (1, -1), (-2,)])
def test_ekf_negative_indices_are_refused(indices: tuple[int, ...]) -> None:
    # Indices must lie in [0, length): a negative one would alias another component
    # ((1, -1) names component 1 twice) and slip past the duplicate check.
    with pytest.raises(ValueError, match="angle_states"):
        ExtendedKalmanFilter(np.zeros(2), np.eye(2), angle_states=indices)
    ekf = ExtendedKalmanFilter(np.zeros(2), np.eye(2))
    with pytest.raises(ValueError, match="angle_measurements"):
        ekf.update(np.zeros(2), _h2, np.eye(2), np.eye(2), angle_measurements=indices)
    np.testing.assert_array_equal(ekf.x, [0.0, 0.0])


def test_ekf_predict_to_a_subnormal_covariance_is_refused() -> None:
    # P0 is refused with a subnormal LDLᵀ pivot (its reciprocal overflows); a predict
    # that would produce one (F P Fᵀ = 1e-320 here) raises FilterError and leaves the
    # state unchanged, rather than committing a covariance the next step cannot use.
    from navkit.errors import FilterError

    ekf = ExtendedKalmanFilter(np.array([1.0]), np.array([[1.0]]))
    with pytest.raises(FilterError, match="positive definite"):
        ekf.predict(lambda x: x, np.array([[1e-160]]), np.array([[0.0]]))
    assert ekf.x[0] == 1.0
    assert ekf.P[0, 0] == 1.0


def test_ekf_huge_but_finite_nis_is_applied() -> None:
    # Only an NIS that overflows float64 makes the update "not applied"; a finite one
    # near the top of the range (1.28e308 here) is an ordinary accepted update.
    y = 1.6e154
    ekf = ExtendedKalmanFilter(np.zeros(1), np.eye(1))
    result = ekf.update(np.array([y]), lambda x: x.copy(), np.eye(1), np.eye(1))
    assert result.accepted
    assert result.nis == pytest.approx(y * (y / 2.0), rel=1e-15)
    assert result.nis > 1e308
    assert ekf.x[0] == pytest.approx(y / 2.0, rel=1e-15)
