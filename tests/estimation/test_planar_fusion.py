"""PlanarFusion: online API, batch kernel, asynchronous and out-of-order input, bad input."""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import navkit.errors
from kernel_signatures import compiled_signatures
from navkit._shared.jit import jit_disabled
from navkit.errors import FilterError
from navkit.estimation import (
    FusionResult,
    FusionStatus,
    MeasurementLog,
    PlanarFusion,
)
from navkit.geometry import Pose2D


def mixed_log(n: int, seed: int) -> MeasurementLog:
    """Odometry at 50 Hz, yaw at 10 Hz, gyro at 100 Hz, accelerometer at 25 Hz, jittered stamps."""
    rng = np.random.default_rng(seed)

    def stamps(rate: float) -> np.ndarray:
        t = np.arange(0.0, n / 50.0, 1.0 / rate)
        return np.sort(t + rng.uniform(0.0, 0.2 / rate, t.shape))

    t_o, t_y, t_g, t_a = stamps(50), stamps(10), stamps(100), stamps(25)
    return MeasurementLog.from_streams(
        odometry=(
            t_o,
            0.8 + 0.05 * rng.normal(size=t_o.size),
            0.3 + 0.02 * rng.normal(size=t_o.size),
        ),
        odometry_variance=(0.05**2, 0.02**2),
        yaw=(
            t_y,
            np.mod(0.3 * t_y + 0.03 * rng.normal(size=t_y.size) + math.pi, 2 * math.pi) - math.pi,
        ),
        yaw_variance=0.03**2,
        yaw_rate=(t_g, 0.3 + 0.01 * rng.normal(size=t_g.size)),
        yaw_rate_variance=0.01**2,
        acceleration=(t_a, 0.2 * rng.normal(size=t_a.size)),
        acceleration_variance=0.2**2,
    )


def online(fusion: PlanarFusion, log: MeasurementLog) -> np.ndarray:
    states = []
    for t, z, var, obs in zip(log.times, log.values, log.variances, log.observed, strict=True):
        key = tuple(bool(b) for b in obs)
        if key == (False, True, True, False):
            fusion.update_odometry(t, z[1], z[2], v_variance=var[1], omega_variance=var[2])
        elif key == (False, True, False, False):
            fusion.update_speed(t, z[1], variance=var[1])
        elif key == (True, False, False, False):
            fusion.update_yaw(t, z[0], variance=var[0])
        elif key == (False, False, True, False):
            fusion.update_yaw_rate(t, z[2], variance=var[2])
        else:
            fusion.update_acceleration(t, z[3], variance=var[3])
        states.append(fusion.x)
    return np.array(states)


def test_log_merges_streams_in_time_order() -> None:
    log = mixed_log(200, seed=0)
    assert np.all(np.diff(log.times) >= 0.0)
    assert len(log) == log.times.shape[0]
    counts = log.observed.sum(axis=0)
    assert counts[1] == 200  # one speed per odometry message
    assert counts[0] == 40 and counts[3] == 100
    assert counts[2] == 200 + 400  # odometry yaw rate + gyro
    with pytest.raises(ValueError, match="read-only"):
        log.times[0] = 1.0


def test_batch_equals_online_updates() -> None:
    log = mixed_log(500, seed=1)
    batch = PlanarFusion(t0=0.0)
    result = batch.update_batch(log)
    ref = online(PlanarFusion(t0=0.0), log)
    assert np.all(result.status == FusionStatus.ACCEPTED)
    np.testing.assert_allclose(result.states, ref, rtol=0, atol=1e-12)
    assert batch.t == log.times[-1]
    np.testing.assert_array_equal(batch.x, result.states[-1])
    # The filter converged to the simulated motion: v ≈ 0.8 m/s, ω ≈ 0.3 rad/s.
    assert result.states[-1, 3] == pytest.approx(0.8, abs=0.05)
    assert result.states[-1, 4] == pytest.approx(0.3, abs=0.02)
    # Covariances stay symmetric positive definite throughout.
    p = result.covariances
    np.testing.assert_array_equal(p, np.swapaxes(p, 1, 2))
    assert np.all(np.linalg.eigvalsh(p) > 0.0)
    # The result is an immutable container of read-only arrays.
    for arr in (result.times, result.states, result.covariances, result.status, result.nis):
        assert not arr.flags.writeable
    with pytest.raises(AttributeError):
        result.states = result.states  # type: ignore[misc]


def test_fusion_result_constructor_validates_and_copies() -> None:
    states = np.zeros((2, 6))
    result = FusionResult(
        np.array([0.0, 1.0]),
        states,
        np.stack([np.eye(6)] * 2),
        np.array([FusionStatus.ACCEPTED, FusionStatus.GATED], dtype=np.int8),
        np.array([0.5, math.nan]),
    )
    states[0, 0] = 5.0  # the result holds its own copy
    assert result.states[0, 0] == 0.0
    assert not result.states.flags.writeable
    assert result.accepted.tolist() == [True, False]
    assert result.final_pose == Pose2D(0.0, 0.0, 0.0)
    good = (np.zeros(1), np.zeros((1, 6)), np.eye(6)[None], np.zeros(1, np.int8), np.zeros(1))
    with pytest.raises(ValueError, match="states"):
        FusionResult(good[0], np.zeros((1, 5)), *good[2:])
    with pytest.raises(ValueError, match="covariances"):
        FusionResult(good[0], good[1], np.eye(6), *good[3:])
    with pytest.raises(ValueError, match="status"):
        FusionResult(*good[:3], np.full(1, 7, np.int8), good[4])
    with pytest.raises(TypeError, match="status"):
        FusionResult(*good[:3], np.zeros(1), good[4])
    with pytest.raises(ValueError, match="nis"):
        FusionResult(*good[:4], np.zeros(2))


def test_out_of_order_measurement_is_rejected_with_reason() -> None:
    fusion = PlanarFusion()
    assert fusion.t is None
    assert fusion.update_odometry(10.0, 1.0, 0.0, v_variance=1e-3, omega_variance=1e-3).accepted
    assert fusion.t == 10.0
    fusion.update_odometry(10.5, 1.0, 0.0, v_variance=1e-3, omega_variance=1e-3)
    x, p = fusion.x, fusion.P
    late = fusion.update_yaw(10.2, 0.5, variance=1e-3)
    assert not late.accepted
    assert late.reason is not None and "out of order" in late.reason
    assert math.isnan(late.nis)
    np.testing.assert_array_equal(fusion.x, x)
    np.testing.assert_array_equal(fusion.P, p)
    assert fusion.t == 10.5
    with pytest.raises(ValueError, match="older"):
        fusion.predict(10.0)
    # Same time is fine (several sensors stamped together).
    assert fusion.update_yaw(10.5, 0.01, variance=1e-3).accepted


def test_batch_marks_rows_older_than_the_filter() -> None:
    fusion = PlanarFusion(t0=5.0)
    log = MeasurementLog(
        [4.0, 5.5, 5.2, 6.0],
        [[0.0, 1.0, 0.0, 0.0]] * 4,
        [[1.0, 1e-3, 1.0, 1.0]] * 4,
        np.array([[False, True, False, False]] * 4),
    )
    result = fusion.update_batch(log)
    assert result.status.tolist() == [
        FusionStatus.OUT_OF_ORDER,
        FusionStatus.ACCEPTED,
        FusionStatus.OUT_OF_ORDER,
        FusionStatus.ACCEPTED,
    ]
    assert result.accepted.tolist() == [False, True, False, True]
    np.testing.assert_array_equal(result.states[2], result.states[1])
    assert fusion.t == 6.0


def test_yaw_residual_wraps_and_prediction_follows_heading() -> None:
    fusion = PlanarFusion([0.0, 0.0, math.pi - 0.05, 0.0, 0.0, 0.0], t0=0.0)
    res = fusion.update_yaw(0.0, -math.pi + 0.05, variance=1e-9)
    assert res.residual[0] == pytest.approx(0.1)
    assert -math.pi < fusion.x[2] <= math.pi
    assert abs(fusion.x[2]) == pytest.approx(math.pi, abs=0.06)
    # Driving at 1 m/s for 2 s with heading ~π moves the robot along -x.
    fusion.update_speed(0.0, 1.0, variance=1e-6)
    fusion.predict(2.0)
    assert fusion.pose.x == pytest.approx(-2.0, abs=0.02)
    assert isinstance(fusion.pose, Pose2D)


def test_gate_rejects_outlier_but_keeps_prediction() -> None:
    fusion = PlanarFusion(t0=0.0, gate_probability=0.99)
    for i in range(1, 50):
        assert fusion.update_yaw(0.02 * i, 0.0, variance=1e-4).accepted
    x_before = fusion.x
    res = fusion.update_yaw(1.0, 1.5, variance=1e-4)
    assert not res.accepted
    assert res.nis > 6.63  # chi-square 99% quantile, 1 degree of freedom
    assert res.reason is not None and "gate" in res.reason
    assert fusion.t == 1.0
    assert fusion.x[2] == pytest.approx(x_before[2], abs=1e-9)
    # The same outlier is applied without a gate.
    ungated = PlanarFusion(t0=0.0)
    assert ungated.update_yaw(1.0, 1.5, variance=1e-4).accepted


def test_numerical_failure_raises_and_leaves_state() -> None:
    # Variances at the top of their range overflow in a long prediction; the update must
    # not apply (before issue 12 this was P0 = 1e300, now refused on construction).
    fusion = PlanarFusion(P0=np.full(6, 1e100), t0=0.0)
    x, p = fusion.x, fusion.P
    with pytest.raises(FilterError, match="overflows float64"):
        fusion.update_yaw(1e60, 0.5, variance=1.0)
    assert FilterError is navkit.errors.FilterError
    np.testing.assert_array_equal(fusion.x, x)
    np.testing.assert_array_equal(fusion.P, p)
    assert fusion.t == 0.0
    with pytest.raises(ValueError, match="P0 entries must have magnitude <= 1e\\+100"):
        PlanarFusion(P0=np.full(6, 1e300))


@pytest.mark.parametrize(
    ("call", "error", "match"),
    [
        (
            lambda f: f.update_odometry(1.0, math.nan, 0.0, v_variance=1e-3, omega_variance=1e-3),
            ValueError,
            "v must be finite",
        ),
        (
            lambda f: f.update_odometry(1.0, 1.0, 0.0, v_variance=-1e-3, omega_variance=1e-3),
            ValueError,
            "v_variance",
        ),
        (
            lambda f: f.update_odometry(1.0, 1.0, 0.0, v_variance=1e-3, omega_variance=0.0),
            ValueError,
            "omega_variance",
        ),
        (lambda f: f.update_yaw(math.inf, 0.0, variance=1e-3), ValueError, "t must be finite"),
        (lambda f: f.update_yaw(1.0, "north", variance=1e-3), TypeError, "yaw"),
        (lambda f: f.update_yaw_rate(1.0, math.nan, variance=1e-3), ValueError, "omega"),
        (
            lambda f: f.update_acceleration(1.0, 0.0, variance=math.nan),
            ValueError,
            "variance must be finite",
        ),
        (lambda f: f.update_speed(1.0, 1.0, variance=0.0), ValueError, "variance must be in"),
        (lambda f: f.predict(math.nan), ValueError, "t must be finite"),
        (lambda f: f.update_batch("log"), TypeError, "MeasurementLog"),
        # Every variance is keyword-only.
        (lambda f: f.update_odometry(1.0, 1.0, 0.0, 1e-3, 1e-3), TypeError, "positional"),
        (lambda f: f.update_speed(1.0, 1.0, 1e-3), TypeError, "positional"),
        (lambda f: f.update_yaw(1.0, 0.0, 1e-3), TypeError, "positional"),
        (lambda f: f.update_yaw_rate(1.0, 0.0, 1e-3), TypeError, "positional"),
        (lambda f: f.update_acceleration(1.0, 0.0, 1e-3), TypeError, "positional"),
    ],
)
def test_bad_measurements_raise_and_leave_state(
    call: object, error: type[Exception], match: str
) -> None:
    fusion = PlanarFusion(t0=0.0)
    fusion.update_odometry(0.5, 1.0, 0.1, v_variance=1e-3, omega_variance=1e-3)
    x, p, t = fusion.x, fusion.P, fusion.t
    with pytest.raises(error, match=match):
        call(fusion)  # type: ignore[operator]
    np.testing.assert_array_equal(fusion.x, x)
    np.testing.assert_array_equal(fusion.P, p)
    assert fusion.t == t


@pytest.mark.parametrize(
    ("kwargs", "error", "match"),
    [
        ({"x0": [0.0] * 5}, ValueError, "x0"),
        ({"x0": [0.0, 0.0, math.nan, 0.0, 0.0, 0.0]}, ValueError, "x0"),
        ({"P0": -np.eye(6)}, ValueError, "P0 must be positive definite"),
        ({"P0": [1.0, 1.0, 0.0, 1.0, 1.0, 1.0]}, ValueError, "P0 diagonal"),
        ({"process_noise": -np.ones(6)}, ValueError, "process_noise diagonal"),
        (
            {"process_noise": np.ones((6, 6)) - 2 * np.eye(6)},
            ValueError,
            "process_noise must be positive semi",
        ),
        ({"process_noise": np.eye(3)}, ValueError, "process_noise"),
        ({"gate_probability": 1.5}, ValueError, "gate_probability"),
        ({"t0": math.nan}, ValueError, "t0"),
    ],
)
def test_bad_construction(kwargs: dict[str, object], error: type[Exception], match: str) -> None:
    with pytest.raises(error, match=match):
        PlanarFusion(**kwargs)  # type: ignore[arg-type]


def test_constructor_options_are_keyword_only() -> None:
    with pytest.raises(TypeError, match="positional"):
        PlanarFusion(np.zeros(6), np.ones(6), np.ones(6))  # type: ignore[call-arg]
    assert PlanarFusion(np.zeros(6), np.ones(6), process_noise=np.ones(6), t0=2.0).t == 2.0


def test_bad_logs() -> None:
    obs = np.array([[True, False, False, False]])
    with pytest.raises(ValueError, match="values must be finite where observed"):
        MeasurementLog([0.0], [[math.nan, 0, 0, 0]], [[1.0, 1, 1, 1]], obs)
    # NaN is fine where a component is not observed.
    MeasurementLog([0.0], [[0.0, math.nan, 0, 0]], [[1.0, math.nan, 1, 1]], obs)
    with pytest.raises(ValueError, match="variances"):
        MeasurementLog([0.0], [[0.0, 0, 0, 0]], [[0.0, 1, 1, 1]], obs)
    with pytest.raises(ValueError, match="at least one component"):
        MeasurementLog([0.0], [[0.0, 0, 0, 0]], [[1.0, 1, 1, 1]], ~obs & False)
    with pytest.raises(TypeError, match="observed must be a boolean"):
        MeasurementLog([0.0], [[0.0, 0, 0, 0]], [[1.0, 1, 1, 1]], obs.astype(int))
    with pytest.raises(ValueError, match="times"):
        MeasurementLog([math.nan], [[0.0, 0, 0, 0]], [[1.0, 1, 1, 1]], obs)
    with pytest.raises(ValueError, match=r"values must have length 2"):
        MeasurementLog([0.0, 1.0], [[0.0, 0, 0, 0]], [[1.0, 1, 1, 1]], np.repeat(obs, 2, axis=0))
    with pytest.raises(ValueError, match="at least one measurement stream"):
        MeasurementLog.from_streams()
    with pytest.raises(ValueError, match=r"yaw\[1\]"):
        MeasurementLog.from_streams(yaw=([0.0, 1.0], [0.0]))
    with pytest.raises(ValueError, match="odometry must be a tuple of 2 or 3"):
        MeasurementLog.from_streams(odometry=([0.0],))
    with pytest.raises(ValueError, match="yaw_variance"):
        MeasurementLog.from_streams(yaw=([0.0], [0.0]), yaw_variance=-1.0)
    with pytest.raises(ValueError, match="yaw_rate"):
        MeasurementLog.from_streams(yaw_rate=([0.0], [math.nan]))


def test_empty_log() -> None:
    fusion = PlanarFusion(t0=1.0)
    result = fusion.update_batch(
        MeasurementLog(np.empty(0), np.empty((0, 4)), np.empty((0, 4)), np.empty((0, 4), bool))
    )
    assert result.states.shape == (0, 6)
    assert fusion.t == 1.0
    with pytest.raises(ValueError, match="empty"):
        _ = result.final_pose


measurement = st.tuples(
    st.floats(0.0, 0.5),  # time step, s
    st.sampled_from(["odometry", "speed", "yaw", "yaw_rate", "acceleration"]),
    st.floats(-10.0, 10.0),  # value
    st.floats(1e-8, 1e2),  # variance
)


@settings(max_examples=40, deadline=None)
@given(st.lists(measurement, min_size=1, max_size=60))
def test_covariance_stays_symmetric_positive_definite(
    sequence: list[tuple[float, str, float, float]],
) -> None:
    fusion = PlanarFusion(t0=0.0)
    t = 0.0
    for dt, kind, value, var in sequence:
        t += dt
        if kind == "odometry":
            res = fusion.update_odometry(t, value, 0.1 * value, v_variance=var, omega_variance=var)
        else:
            res = getattr(fusion, f"update_{kind}")(t, value, variance=var)
        assert res.accepted
        p = fusion.P
        np.testing.assert_array_equal(p, p.T)
        assert np.linalg.eigvalsh(p)[0] > 0.0
        assert -math.pi < fusion.x[2] <= math.pi
    assert fusion.t == t


def test_copies_and_pickles_are_independent() -> None:
    """Each copy gets its own buffer: x, P and the clock follow its own updates only."""
    import copy
    import pickle

    fusion = PlanarFusion(t0=0.0, gate_probability=0.99)
    fusion.update_odometry(0.1, 1.0, 0.0, v_variance=1e-3, omega_variance=1e-3)
    x_before, p_before = fusion.x.copy(), fusion.P.copy()
    reference = PlanarFusion(t0=0.0, gate_probability=0.99)
    reference.update_odometry(0.1, 1.0, 0.0, v_variance=1e-3, omega_variance=1e-3)
    reference.update_odometry(1.1, 1.0, 0.2, v_variance=1e-3, omega_variance=1e-3)
    x_want, p_want = reference.x.copy(), reference.P.copy()
    gated = reference.update_yaw(1.2, 3.0, variance=1e-6)
    assert not gated.accepted
    for twin in (copy.copy(fusion), copy.deepcopy(fusion), pickle.loads(pickle.dumps(fusion))):
        assert type(twin) is PlanarFusion and twin.t == 0.1
        np.testing.assert_array_equal(twin.x, x_before)
        twin.update_odometry(1.1, 1.0, 0.2, v_variance=1e-3, omega_variance=1e-3)
        assert twin.t == 1.1 and fusion.t == 0.1  # the original did not move
        np.testing.assert_array_equal(twin.x, x_want)  # the twin's views follow it
        np.testing.assert_array_equal(twin.P, p_want)
        np.testing.assert_array_equal(fusion.x, x_before)
        np.testing.assert_array_equal(fusion.P, p_before)
        assert twin.update_yaw(1.2, 3.0, variance=1e-6).reason == gated.reason  # same gates


_FORTRAN_AND_C_LOGS = """
import numpy as np
from navkit.estimation import MeasurementLog, PlanarFusion
t = np.linspace(0.1, 0.5, 5)
columns = np.stack([np.full(5, 0.2), np.ones(5), np.full(5, 0.1), np.zeros(5)])
variances = np.full((4, 5), 1e-3)
observed = np.ones((4, 5), dtype=bool)
PlanarFusion(t0=0.0).update_batch(MeasurementLog(t, columns.T, variances.T, observed.T))
ref = MeasurementLog(t, columns.T.copy(), variances.T.copy(), observed.T.copy())
PlanarFusion(t0=0.0).update_batch(ref)
"""


def test_fortran_ordered_log_uses_the_one_compiled_batch_kernel() -> None:
    """A log built from transposed (4, T) arrays is stored C-ordered (no second compile)."""
    t = np.linspace(0.1, 0.5, 5)
    columns = np.stack([np.full(5, 0.2), np.ones(5), np.full(5, 0.1), np.zeros(5)])
    variances = np.full((4, 5), 1e-3)
    observed = np.ones((4, 5), dtype=bool)
    log = MeasurementLog(t, columns.T, variances.T, observed.T)  # Fortran-ordered views
    for arr in (log.times, log.values, log.variances, log.observed):
        assert arr.flags.c_contiguous
    ref = MeasurementLog(t, columns.T.copy(), variances.T.copy(), observed.T.copy())
    result = PlanarFusion(t0=0.0).update_batch(log)
    np.testing.assert_array_equal(result.states, PlanarFusion(t0=0.0).update_batch(ref).states)
    if jit_disabled():  # plain functions: no signatures to count
        return
    # The same two logs in a fresh process: this one's planar_run keeps the signatures
    # of every earlier test's direct calls (writable copies of a log's read-only
    # arrays, say), which ran before this test under another order or split of the
    # suite (xdist).
    compiled = compiled_signatures(_FORTRAN_AND_C_LOGS, ["navkit.estimation._fusion_kernels"])
    assert len(compiled.get("_fusion_kernels.planar_run", [])) == 1, compiled


@pytest.mark.parametrize("name", ["P0", "process_noise"])
def test_a_diagonal_is_checked_like_the_full_matrix(name: str) -> None:
    """A subnormal variance given as a diagonal is refused, as in the (6, 6) matrix.

    It used to pass the diagonal's sign check and make the filter's first update
    fail (FilterError) instead of the constructor.
    """
    diagonal = np.array([1e-320, 1.0, 1.0, 1.0, 1.0, 1.0])
    if name == "P0":
        with pytest.raises(ValueError, match="P0 must be positive definite"):
            PlanarFusion(P0=np.diag(diagonal))
        with pytest.raises(ValueError, match="P0 must be positive definite"):
            PlanarFusion(P0=diagonal)
    else:
        # Semi-definite process noise: a subnormal entry (or a zero) is fine either way.
        log = mixed_log(50, seed=3)
        by_vector = PlanarFusion(t0=0.0, process_noise=diagonal).update_batch(log)
        by_matrix = PlanarFusion(t0=0.0, process_noise=np.diag(diagonal)).update_batch(log)
        np.testing.assert_array_equal(by_vector.covariances, by_matrix.covariances)
    # Zero process noise on some states: the diagonal and the matrix give the same filter.
    q = np.array([0.0, 0.0, 0.06, 0.0, 0.02, 0.0])
    log = mixed_log(50, seed=3)
    by_vector = PlanarFusion(t0=0.0, process_noise=q).update_batch(log)
    by_matrix = PlanarFusion(t0=0.0, process_noise=np.diag(q)).update_batch(log)
    np.testing.assert_array_equal(by_vector.covariances, by_matrix.covariances)
    assert np.all(by_vector.status == FusionStatus.ACCEPTED)


def test_log_and_result_copies_and_pickles_stay_read_only(
    duplicate: Callable[[Any], Any],
) -> None:
    """The records' arrays are read-only in every copy, not only in the original.

    pickle and deepcopy used to restore them writable: a copied log could then be
    changed after its validation (a negative variance was silently taken as "not
    observed" by the batch kernel).
    """
    log = mixed_log(20, seed=5)
    result = PlanarFusion(t0=0.0).update_batch(log)
    twin_log = duplicate(log)
    twin_result = duplicate(result)
    assert type(twin_log) is MeasurementLog and type(twin_result) is FusionResult
    for twin, original in ((twin_log, log), (twin_result, result)):
        for name in type(original).__dataclass_fields__:
            arr = getattr(twin, name)
            assert not arr.flags.writeable, name
            assert arr.flags.c_contiguous, name
            np.testing.assert_array_equal(arr, getattr(original, name))
    with pytest.raises(ValueError, match="read-only"):
        twin_log.variances[0, :] = -1.0
    np.testing.assert_array_equal(
        PlanarFusion(t0=0.0).update_batch(twin_log).states, result.states
    )
