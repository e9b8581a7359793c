"""Issue 12 in navkit.estimation: documented ranges, strict types, never NaN, records copy."""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from hypothesis_twins import slow_twin
from navkit.errors import FilterError
from navkit.estimation import (
    CompassCalibration,
    DiffOdometry,
    ExtendedKalmanFilter,
    FusionResult,
    FusionStatus,
    MeasurementLog,
    OmniOdometry,
    PlanarFusion,
    UpdateResult,
    compass_to_yaw,
)
from navkit.kinematics import DiffDrive, OmniDrive

ODOM = {"v_variance": 1e-3, "omega_variance": 1e-3}


def odometry_log(times: list[float]) -> MeasurementLog:
    n = len(times)
    values = np.column_stack((np.zeros(n), np.full(n, 1.0), np.full(n, 0.1), np.zeros(n)))
    observed = np.tile([False, True, True, False], (n, 1))
    return MeasurementLog(times, values, np.full((n, 4), 1e-3), observed)


# --------------------------------------------------------------------------- PlanarFusion


@pytest.mark.parametrize("bad_row", [0, 2, 4])
def test_batch_skips_a_corrupt_time_gap_and_continues(bad_row: int) -> None:
    times = [0.1, 0.2, 0.3, 0.4, 0.5]
    good = PlanarFusion(t0=0.0).update_batch(odometry_log(times))
    corrupt = times.copy()
    corrupt.insert(bad_row, 1e300)
    # A row at 1e300 s is older than nothing, so it sits anywhere in an unsorted log.
    fusion = PlanarFusion(t0=0.0)
    result = fusion.update_batch(odometry_log(corrupt))
    assert result.status[bad_row] == FusionStatus.TIME_GAP
    assert math.isnan(result.nis[bad_row])
    assert np.isfinite(result.states).all() and np.isfinite(result.covariances).all()
    keep = [i for i in range(len(corrupt)) if i != bad_row]
    if bad_row < len(times):  # the rows after it continue from the last good state
        np.testing.assert_array_equal(result.states[keep], good.states)
        np.testing.assert_array_equal(result.covariances[keep], good.covariances)
        np.testing.assert_array_equal(result.status[keep], good.status)
        assert fusion.t == 0.5
    # The skipped row shows the unchanged state.
    before = result.states[bad_row - 1] if bad_row else np.zeros(6)
    np.testing.assert_array_equal(result.states[bad_row], before)
    # ... and the filter stays usable.
    assert fusion.update_odometry(1.0, 1.0, 0.1, **ODOM).accepted
    assert np.isfinite(fusion.x).all() and np.isfinite(fusion.P).all()


def test_online_time_gap_raises_and_keeps_the_state() -> None:
    fusion = PlanarFusion(t0=0.0)
    fusion.update_odometry(0.1, 1.0, 0.1, **ODOM)
    x, p = fusion.x, fusion.P
    with pytest.raises(FilterError, match=r"time gap of .* overflows float64; the filter is"):
        fusion.update_odometry(1e300, 1.0, 0.1, **ODOM)
    np.testing.assert_array_equal(fusion.x, x)
    np.testing.assert_array_equal(fusion.P, p)
    assert fusion.t == 0.1
    with pytest.raises(FilterError, match="time gap"):
        fusion.predict(1e300)
    np.testing.assert_array_equal(fusion.x, x)
    assert fusion.update_odometry(0.2, 1.0, 0.1, **ODOM).accepted


def test_time_differences_that_overflow_are_a_time_gap() -> None:
    fusion = PlanarFusion(t0=-1.7e308)
    with pytest.raises(FilterError, match="time gap of inf s"):
        fusion.update_yaw(1.7e308, 0.0, variance=1e-3)
    assert fusion.t == -1.7e308


def test_update_odometry_with_huge_values_is_not_applied() -> None:
    fusion = PlanarFusion(t0=0.0)
    fusion.update_odometry(0.1, 1.0, 0.1, **ODOM)
    result = fusion.update_odometry(0.2, 1e308, -1e308, **ODOM)
    # Before issue 12: nis=nan, accepted=True and a state of ±inf.
    assert not result.accepted
    assert result.nis == math.inf
    assert result.reason is not None and result.reason.startswith("overflow")
    assert np.isfinite(fusion.x).all() and np.isfinite(fusion.P).all()
    assert fusion.t == 0.2  # the prediction is kept, as for a gated measurement
    assert fusion.update_odometry(0.3, 1.0, 0.1, **ODOM).accepted


def test_batch_marks_overflowing_rows_and_keeps_the_prediction() -> None:
    log = MeasurementLog.from_streams(
        odometry=([0.1, 0.2, 0.3], [1.0, 1e308, 1.0], [0.1, -1e308, 0.1])
    )
    result = PlanarFusion(t0=0.0).update_batch(log)
    assert result.status.tolist() == [FusionStatus.ACCEPTED, FusionStatus.OVERFLOW,
                                      FusionStatus.ACCEPTED]
    assert result.nis[1] == math.inf
    assert np.isfinite(result.states).all() and np.isfinite(result.covariances).all()


@pytest.mark.parametrize(
    ("call", "name"),
    [
        (lambda f: f.update_yaw(1.0, 0.0, variance=1e-101), "variance must be in"),
        (lambda f: f.update_yaw(1.0, 0.0, variance=1e101), "variance must be in"),
        (lambda f: f.update_odometry(1.0, 1.0, 0.0, v_variance=5e-324, omega_variance=1e-3),
         "v_variance must be in"),
        (lambda f: f.update_odometry(1.0, 1.0, 0.0, v_variance=1e-3, omega_variance=1e300),
         "omega_variance must be in"),
    ],
)
def test_measurement_variances_outside_their_range_are_refused(call, name) -> None:  # type: ignore[no-untyped-def]
    fusion = PlanarFusion(t0=0.0)
    x = fusion.x
    with pytest.raises(ValueError, match=name):
        call(fusion)
    np.testing.assert_array_equal(fusion.x, x)
    assert fusion.t == 0.0


@pytest.mark.parametrize(
    ("make", "error", "match"),
    [
        (lambda: PlanarFusion(P0=np.full(6, 1e101)), ValueError, "P0 entries must have magnitude"),
        (lambda: PlanarFusion(P0=np.eye(6) * 1e300), ValueError, "P0 entries"),
        (lambda: PlanarFusion(process_noise=np.full(6, 1e200)), ValueError, "process_noise"),
        (lambda: PlanarFusion(P0=np.eye(6) * (1 + 1j)), TypeError, "P0"),
        (lambda: PlanarFusion(x0=["0"] * 6), TypeError, "x0"),
        (lambda: MeasurementLog.from_streams(yaw=([0.0], [0.0]), yaw_variance=1e-200), ValueError,
         "yaw_variance must be in"),
        (lambda: MeasurementLog.from_streams(odometry=([0.0], [1.0], [0.0]),
                                             odometry_variance=(1e-3,)), ValueError,
         "odometry_variance must be a pair"),
        (lambda: MeasurementLog.from_streams(odometry=([0.0], [1.0], [0.0]),
                                             odometry_variance=1e-3), TypeError,
         "odometry_variance must be a pair"),
        # A 0-d array is an ndarray without a length: it raised an unnamed len() error.
        (lambda: MeasurementLog.from_streams(odometry=([0.0], [1.0], [0.0]),
                                             odometry_variance=np.array(1e-3)), TypeError,
         "odometry_variance must be a pair"),
        (lambda: MeasurementLog([0.0], [[0.0, 1.0, 0.0, 0.0]], [[1.0, 1e120, 1.0, 1.0]],
                                [[False, True, False, False]]), ValueError, "variances must be in"),
        (lambda: MeasurementLog([0.0], [[0.0, 1.0 + 1j, 0.0, 0.0]], np.ones((1, 4)),
                                [[False, True, False, False]]), TypeError, "values"),
    ],
)
def test_construction_checks_ranges_and_types(make, error, match) -> None:  # type: ignore[no-untyped-def]
    with pytest.raises(error, match=match):
        make()


def test_fusion_status_lookup_takes_integer_codes_only() -> None:
    assert FusionStatus(4) is FusionStatus.TIME_GAP
    assert FusionStatus(np.int8(5)) is FusionStatus.OVERFLOW
    for bad in (True, np.bool_(True), 1.0, 1 + 0j, "1"):
        with pytest.raises(TypeError, match="integer code"):
            FusionStatus(bad)
    with pytest.raises(ValueError):
        FusionStatus(17)


@settings(max_examples=25, deadline=None)
@given(
    st.lists(
        st.tuples(
            st.floats(0.0, 1e3),  # time step
            st.floats(-1e3, 1e3),  # speed
            st.floats(-1e3, 1e3),  # yaw rate
            st.floats(1e-100, 1e100),  # variance
        ),
        min_size=1,
        max_size=20,
    )
)
def test_in_range_measurements_never_give_nan(
    rows: list[tuple[float, float, float, float]],
) -> None:
    fusion = PlanarFusion(t0=0.0)
    t = 0.0
    for dt, v, w, var in rows:
        t += dt
        x, p = fusion.x, fusion.P
        try:
            result = fusion.update_odometry(t, v, w, v_variance=var, omega_variance=var)
        except FilterError:
            # A variance some 1e16 times below the state's loses positive definiteness
            # in float64: a clear error, and the filter is unchanged.
            np.testing.assert_array_equal(fusion.x, x)
            np.testing.assert_array_equal(fusion.P, p)
            continue
        assert not math.isnan(result.nis)
        assert np.isfinite(fusion.x).all() and np.isfinite(fusion.P).all()


test_in_range_measurements_never_give_nan_thoroughly = slow_twin(
    test_in_range_measurements_never_give_nan, max_examples=60
)


@settings(max_examples=60, deadline=None)
@given(st.lists(st.floats(allow_nan=False, allow_infinity=False), min_size=1, max_size=30))
def test_batch_with_any_finite_times_is_finite(times: list[float]) -> None:
    result = PlanarFusion().update_batch(odometry_log(times))
    assert np.isfinite(result.states).all() and np.isfinite(result.covariances).all()


# --------------------------------------------------------------------------- EKF


def test_ekf_covariance_near_the_float_limit_is_refused_not_stored_as_inf() -> None:
    with pytest.raises(ValueError, match="P0 entries must have magnitude <= 1e\\+100"):
        ExtendedKalmanFilter([0.0, 0.0], np.eye(2) * 1e308)
    ekf = ExtendedKalmanFilter([0.0, 0.0], np.eye(2) * 1e100)
    np.testing.assert_array_equal(ekf.P, np.eye(2) * 1e100)
    with pytest.raises(ValueError, match="Q entries"):
        ekf.predict(lambda x: x, np.eye(2), np.eye(2) * 1e101)
    with pytest.raises(ValueError, match="R entries"):
        ekf.update([0.0], lambda x: x[:1], [[1.0, 0.0]], [[1e200]])


@pytest.mark.parametrize(
    ("call", "name"),
    [
        (lambda e: e.predict(lambda x: x, np.eye(2), np.eye(2) * (1 + 1j)), "Q"),
        (lambda e: e.predict(lambda x: x * (1 + 1j), np.eye(2), np.eye(2) * 0.1), "f\\(x\\)"),
        (lambda e: e.predict(lambda x: [str(v) for v in x], np.eye(2), np.eye(2)), "f\\(x\\)"),
        (lambda e: e.predict(lambda x: x, lambda x: np.eye(2).astype(complex), np.eye(2)), "F"),
        (lambda e: e.predict(lambda x: x, np.eye(2), "0.1"), "Q"),
        (lambda e: e.update([0.1], lambda x: x[:1] + 0j, [[1.0, 0.0]], [[0.1]]), "h\\(x\\)"),
        (lambda e: e.update([0.1], lambda x: x[:1], lambda x: [[True, False]], [[0.1]]), "H"),
        (lambda e: e.update([0.1 + 0j], lambda x: x[:1], [[1.0, 0.0]], [[0.1]]), "z"),
        (lambda e: e.update([0.1], lambda x: x[:1], [[1.0, 0.0]], [[0.1 + 0j]]), "R"),
        (lambda e: e.update([0.1], lambda x: x[:1], [[1.0, 0.0]], [[0.1]], gate="3"), "gate"),
    ],
)
def test_ekf_refuses_complex_strings_and_bools_even_from_callbacks(call, name) -> None:  # type: ignore[no-untyped-def]
    ekf = ExtendedKalmanFilter([0.0, 1.0], np.eye(2))
    # Cache a valid Q and R first: the reuse fast path must not let bad values through.
    ekf.predict(lambda x: x, np.eye(2), np.eye(2) * 0.1)
    ekf.update([0.0], lambda x: x[:1], [[1.0, 0.0]], [[0.1]])
    x, p = ekf.x, ekf.P
    with pytest.raises(TypeError, match=name):
        call(ekf)
    np.testing.assert_array_equal(ekf.x, x)
    np.testing.assert_array_equal(ekf.P, p)


def test_ekf_reuses_a_cached_noise_given_as_a_list() -> None:
    ekf = ExtendedKalmanFilter([0.0, 1.0], np.eye(2))
    ekf.predict(lambda x: x, np.eye(2), [[0.1, 0.0], [0.0, 0.1]])
    ekf.predict(lambda x: x, np.eye(2), [[0.1, 0.0], [0.0, 0.1]])
    np.testing.assert_allclose(ekf.P, np.eye(2) * 1.2)


def test_ekf_overflowing_updates_are_not_applied() -> None:
    ekf = ExtendedKalmanFilter([0.0], [[1.0]])
    # The residual overflows: z - h(x) = 1e308 - (-1e308).
    res = ekf.update([1e308], lambda x: x - 1e308, [[1.0]], [[1.0]])
    assert not res.accepted and res.nis == math.inf and res.residual.shape == (0,)
    assert res.reason is not None and "the residual" in res.reason
    # The NIS overflows.
    res = ekf.update([1e200], lambda x: x, [[1.0]], [[1.0]])
    assert not res.accepted and res.nis == math.inf and "the NIS" in str(res.reason)
    assert ekf.x.tolist() == [0.0] and ekf.P.tolist() == [[1.0]]
    # The updated state overflows.
    big = ExtendedKalmanFilter([1.7976931348623157e308], [[1e100]])
    big.predict(lambda x: x, [[1e100]], [[0.0]])
    res = big.update([1e304], lambda x: 0.0 * x, [[1.0]], [[1.0]])
    assert not res.accepted and math.isfinite(res.nis) and "the updated state" in str(res.reason)
    assert big.x.tolist() == [1.7976931348623157e308]


def test_ekf_predicted_covariance_overflow_is_a_filter_error() -> None:
    ekf = ExtendedKalmanFilter([0.0], [[1e100]])
    with pytest.raises(FilterError, match="predicted covariance is not finite"):
        ekf.predict(lambda x: x, [[1e200]], [[0.0]])
    assert ekf.P.tolist() == [[1e100]]


# --------------------------------------------------------------------------- records


def test_records_built_from_lists_copy_and_never_freeze_the_callers_arrays() -> None:
    residual = np.array([0.5, -0.2])
    result = UpdateResult(True, 1.0, residual)
    assert residual.flags.writeable and not result.residual.flags.writeable
    residual[0] = 9.0
    assert result.residual[0] == 0.5
    assert UpdateResult(False, 2.0, [0.5], "gated").residual.tolist() == [0.5]
    # As the attribute says: an accepted measurement has no reason not to be applied.
    with pytest.raises(ValueError, match="reason must be None when accepted"):
        UpdateResult(True, 2.0, [0.5], "gated")

    times = np.array([0.0, 0.1])
    values = np.zeros((2, 4))
    variances = np.ones((2, 4))
    observed = np.ones((2, 4), dtype=bool)
    log = MeasurementLog(times, values, variances, observed)
    for arr in (times, values, variances, observed):
        assert arr.flags.writeable
    times[0] = -5.0
    assert log.times[0] == 0.0
    from_lists = MeasurementLog([0.0], [[0.0, 1.0, 0.0, 0.0]], [[1.0] * 4],
                                [[False, True, False, False]])
    assert from_lists.values[0, 1] == 1.0 and not from_lists.values.flags.writeable

    states = np.zeros((2, 6))
    cov = np.tile(np.eye(6), (2, 1, 1))
    status = np.zeros(2, dtype=np.int8)
    nis = np.array([0.5, math.nan])
    fr = FusionResult(times, states, cov, status, nis)
    for arr in (states, cov, status, nis):
        assert arr.flags.writeable
    states[0, 0] = 3.0
    assert fr.states[0, 0] == 0.0
    listed = FusionResult([0.0], [[0.0] * 6], [np.eye(6).tolist()], [0], [math.inf])
    assert listed.nis[0] == math.inf and listed.accepted.tolist() == [True]


@pytest.mark.parametrize(
    ("field", "value", "match"),
    [
        ("states", np.full((1, 6), math.nan), "states"),
        ("covariances", np.full((1, 6, 6), math.inf), "covariances"),
        ("nis", [-1.0], "nis must be >= 0"),
        ("nis", [-math.inf], "nis must be >= 0"),
        ("status", [True], "status"),
    ],
)
def test_fusion_result_refuses_non_finite_states_and_negative_nis(
    field: str, value: object, match: str
) -> None:
    args = {
        "times": [0.0],
        "states": np.zeros((1, 6)),
        "covariances": np.eye(6)[None],
        "status": [0],
        "nis": [1.0],
    }
    args[field] = value
    with pytest.raises((TypeError, ValueError), match=match):
        FusionResult(**args)  # type: ignore[arg-type]


# --------------------------------------------------------------------------- compass, odometry


def test_compass_flags_must_be_bools_and_huge_readings_stay_finite() -> None:
    with pytest.raises(TypeError, match="unwrap must be a bool"):
        compass_to_yaw([1.0, 2.0], unwrap="no")  # type: ignore[arg-type]
    with pytest.raises(TypeError, match="unwrap must be a bool"):
        CompassCalibration(unwrap=1)  # type: ignore[arg-type]
    with pytest.raises(TypeError, match="raw_deg"):
        compass_to_yaw(np.array([1 + 1j]))
    # raw - initial + 360 overflows: both are reduced modulo 360 first (before: NaN).
    yaw = compass_to_yaw(1e308, initial_deg=-1e308)
    assert yaw == compass_to_yaw(1e308 % 360.0, initial_deg=-1e308 % 360.0)
    assert math.isfinite(compass_to_yaw(-1.7e308, initial_deg=1.7e308))


def test_odometry_overflow_is_a_value_error_and_leaves_the_pose() -> None:
    omni = OmniOdometry(OmniDrive.three_wheel(wheel_radius=1e6, base_radius=0.2),
                        pose=(1e308, 0.0, 0.0))
    for increments in ([-5e301, -5e301, 1e302], [-1e305, -1e305, 2e305]):
        with pytest.raises(ValueError, match="wheel_increments: the odometry overflows"):
            omni.update(increments, 0.0)
        assert omni.pose.x == 1e308
    # Within the documented ranges a differential drive moves at most ~6e25 m per reading.
    diff = DiffOdometry(DiffDrive(track=0.3, wheel_radius=1e6), ticks_per_rev=1,
                        pose=(1.7976931348623157e308, 0.0, 0.0))
    diff.update(0, 0)
    assert diff.update(2**62, 2**62).x == 1.7976931348623157e308
    with pytest.raises(ValueError, match="ticks_per_rev must be in"):
        DiffOdometry(DiffDrive(track=0.3, wheel_radius=0.05), ticks_per_rev=0.1)


def test_copied_update_results_keep_a_read_only_residual(
    duplicate: Callable[[Any], Any],
) -> None:
    result = UpdateResult(False, 2.5, np.array([1.0, -2.0]), "rejected by the gate")
    twin = duplicate(result)
    assert type(twin) is UpdateResult
    assert (twin.accepted, twin.nis, twin.reason) == (False, 2.5, "rejected by the gate")
    np.testing.assert_array_equal(twin.residual, [1.0, -2.0])
    with pytest.raises(ValueError, match="read-only"):
        twin.residual[0] = 9.0


def test_copying_a_filter_result_leaves_the_original_alone(
    duplicate: Callable[[Any], Any],
) -> None:
    ekf = ExtendedKalmanFilter([0.0], [[1.0]])
    result = ekf.update([1.0], lambda x: x, [[1.0]], [[1.0]])
    writeable = result.residual.flags.writeable
    twin = duplicate(result)
    assert result.residual.flags.writeable == writeable  # a shallow copy changes no flag
    assert not twin.residual.flags.writeable
    np.testing.assert_array_equal(twin.residual, result.residual)
    assert twin.nis == result.nis and twin.accepted
