"""Seventh review of navkit.estimation: record inputs, limit errors, documented claims.

Regression tests (the masked or ragged ``observed`` of a log and ``status`` of a
result, the exact values in limit errors) and hypothesis properties checking
documented guarantees against independent NumPy references: the general EKF's
equations, PlanarFusion's motion model, and ``update_batch`` equal to the online
updates row by row whatever happens to the rows.
"""

from __future__ import annotations

import copy
import copyreg
import io
import math
import pickle
import re
from dataclasses import dataclass, fields
from typing import Any

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from hypothesis_twins import slow_twin
from navkit.errors import FilterError
from navkit.estimation import (
    ExtendedKalmanFilter,
    FusionResult,
    FusionStatus,
    MeasurementLog,
    PlanarFusion,
    UpdateResult,
)
from navkit.geometry import wrap_angle

_SMALLEST_NORMAL = 2.2250738585072014e-308


def _one_row_result() -> FusionResult:
    return PlanarFusion(t0=0.0).update_batch(MeasurementLog.from_streams(yaw=([0.1], [0.0])))


# --- regressions -------------------------------------------------------------------------


def test_log_refuses_a_masked_observed_whose_mask_it_would_ignore() -> None:
    # The masked entry says "no reading here"; np.asarray read it as its data (True),
    # so the row silently observed a speed of 0 m/s.
    observed = np.ma.array([[True, True, False, False]], mask=[[False, True, False, False]])
    with pytest.raises(ValueError, match="observed has masked entries"):
        MeasurementLog([0.0], [[0.0, 0.0, 0.0, 0.0]], [[1.0] * 4], observed)
    with pytest.raises(ValueError, match="observed has masked entries"):
        MeasurementLog([0.0], [[0.0, 0.0, 0.0, 0.0]], [[1.0] * 4], [observed[0]])
    # A masked array without masked entries is its data.
    plain = np.ma.array([[True, False, False, False]])
    assert MeasurementLog([0.0], [[0.0] * 4], [[1.0] * 4], plain).observed.tolist() == [
        [True, False, False, False]
    ]


def test_log_names_a_ragged_observed() -> None:
    with pytest.raises(ValueError, match="observed must be a rectangular array"):
        MeasurementLog([0.0, 1.0], [[0.0] * 4] * 2, [[1.0] * 4] * 2, [[True] * 4, [True]])


def test_result_refuses_a_masked_status_and_names_a_ragged_one() -> None:
    base = _one_row_result()
    arrays = (base.times, base.states, base.covariances)
    masked = np.ma.array([FusionStatus.GATED], mask=[True])
    with pytest.raises(ValueError, match="status has masked entries"):
        FusionResult(*arrays, masked, base.nis)
    with pytest.raises(ValueError, match="status must be a rectangular array"):
        FusionResult(*arrays, [[0], []], base.nis)
    assert FusionResult(*arrays, np.ma.array([1]), base.nis).status.tolist() == [1]


def _reported(message: str, pattern: str) -> float:
    found = re.search(pattern, message)
    assert found is not None, message
    return float(found.group(1))


@pytest.mark.parametrize(
    "build",
    [
        lambda v: ExtendedKalmanFilter([0.0], [[v]]),
        lambda v: ExtendedKalmanFilter([0.0], [[1.0]]).predict(lambda x: x, [[1.0]], [[v]]),
        lambda v: ExtendedKalmanFilter([0.0], [[1.0]]).update(
            [0.0], lambda x: x, [[1.0]], [[v]]
        ),
        lambda v: PlanarFusion(P0=[v] * 6),
        lambda v: PlanarFusion(process_noise=np.diag([v] * 6)),
    ],
)
def test_a_covariance_just_past_1e100_is_reported_exactly(build: Any) -> None:
    # The message printed the value with :g, which rounds it back to the limit:
    # "must have magnitude <= 1e+100, got 1e+100".
    limit = 1e100
    build(limit)  # at the limit: accepted
    above = float(np.nextafter(limit, math.inf))
    with pytest.raises(ValueError, match="magnitude <= 1e\\+100") as info:
        build(above)
    assert _reported(str(info.value), r"got (\S+)$") == above


def test_a_pivot_just_below_the_smallest_normal_is_reported_exactly() -> None:
    ExtendedKalmanFilter([0.0], [[_SMALLEST_NORMAL]])  # at the limit: accepted
    below = _SMALLEST_NORMAL * (1.0 - 2.0**-20)
    with pytest.raises(ValueError, match="LDLᵀ pivots") as info:
        ExtendedKalmanFilter([0.0], [[below]])
    message = str(info.value)
    assert _reported(message, r"at least (\S+) \(a normal float\)") == _SMALLEST_NORMAL
    assert _reported(message, r"got a pivot of (\S+)$") < _SMALLEST_NORMAL


# --- documented claims against independent references -----------------------------------


def _spd(rng: np.random.Generator, n: int, scale: float) -> np.ndarray:
    a = rng.normal(size=(n, n))
    return scale * (a @ a.T + n * np.eye(n))


@settings(max_examples=50, deadline=None)
@given(
    st.integers(1, 5),
    st.integers(1, 4),
    st.integers(0, 2**32 - 1),
    st.floats(-30.0, 30.0),
)
def test_ekf_step_equals_the_textbook_equations(
    n: int, m: int, seed: int, log_scale: float
) -> None:
    rng = np.random.default_rng(seed)
    scale = 10.0**log_scale
    x0 = 10.0 * rng.normal(size=n)
    p0 = _spd(rng, n, scale)
    angles = tuple(i for i in range(n) if rng.random() < 0.3)
    ekf = ExtendedKalmanFilter(x0, p0, angle_states=angles)
    jac = rng.normal(size=(n, n)) + np.eye(n)
    q = 0.1 * _spd(rng, n, scale)
    ekf.predict(lambda x: jac @ x, jac, q)
    x = jac @ np.array([wrap_angle(v) if i in angles else v for i, v in enumerate(x0)])
    x = np.array([wrap_angle(v) if i in angles else v for i, v in enumerate(x)])
    p = jac @ p0 @ jac.T + q
    np.testing.assert_allclose(ekf.x, x, rtol=1e-9, atol=1e-9 * np.abs(x).max())
    np.testing.assert_allclose(ekf.P, p, rtol=1e-7, atol=1e-9 * np.abs(p).max())
    h = rng.normal(size=(m, n))
    r = _spd(rng, m, scale)
    z = 10.0 * rng.normal(size=m)
    meas_angles = tuple(j for j in range(m) if rng.random() < 0.4)
    try:
        result = ekf.update(z, lambda v: h @ v, h, r, angle_measurements=meas_angles)
    except FilterError:  # documented for ill-conditioned products: nothing to compare
        return
    y = z - h @ x
    y = np.array([wrap_angle(v) if j in meas_angles else v for j, v in enumerate(y)])
    s = h @ p @ h.T + r
    gain = np.linalg.solve(s, h @ p).T
    x_new = x + gain @ y
    identity = np.eye(n) - gain @ h
    p_new = identity @ p @ identity.T + gain @ r @ gain.T
    assert result.accepted
    np.testing.assert_allclose(result.residual, y, rtol=1e-9, atol=1e-12 * np.abs(y).max())
    assert math.isclose(result.nis, float(y @ np.linalg.solve(s, y)), rel_tol=1e-6, abs_tol=1e-9)
    offset = ekf.x - x_new
    for i in angles:
        offset[i] = wrap_angle(offset[i])
        assert -math.pi < ekf.x[i] <= math.pi
    bound = 1e-6 * max(1.0, np.abs(x_new).max()) * max(1.0, np.linalg.cond(s) * 1e-6)
    assert np.all(np.abs(offset) <= bound)
    np.testing.assert_allclose(ekf.P, p_new, rtol=1e-6, atol=1e-9 * np.abs(p_new).max())
    covariance = ekf.P
    assert np.array_equal(covariance, covariance.T)  # "exactly symmetric"
    for j in meas_angles:
        assert -math.pi < result.residual[j] <= math.pi


test_ekf_step_equals_the_textbook_equations_thoroughly = slow_twin(
    test_ekf_step_equals_the_textbook_equations, max_examples=150
)


_KIND_COMPONENTS = {
    "odometry": (1, 2),
    "speed": (1,),
    "yaw": (0,),
    "yaw_rate": (2,),
    "acceleration": (3,),
}


def _online(fusion: PlanarFusion, kind: str, t: float, z: tuple[float, float],
            var: tuple[float, float]) -> Any:  # fmt: skip
    if kind == "odometry":
        return fusion.update_odometry(t, z[0], z[1], v_variance=var[0], omega_variance=var[1])
    return getattr(fusion, f"update_{kind}")(t, z[0], variance=var[0])


def _reference_predict(
    x: np.ndarray, p: np.ndarray, q: np.ndarray, dt: float
) -> tuple[np.ndarray, np.ndarray]:
    """The documented motion model and its Jacobian, written out."""
    theta, v, omega, a = x[2:]
    phi = theta + 0.5 * omega * dt
    s = v * dt + 0.5 * a * dt * dt
    c, sn = math.cos(phi), math.sin(phi)
    out = x.copy()
    out[0] += s * c
    out[1] += s * sn
    out[2] = wrap_angle(theta + omega * dt)
    out[3] = v + a * dt
    jac = np.eye(6)
    jac[0, 2:] = [-s * sn, dt * c, -0.5 * dt * s * sn, 0.5 * dt * dt * c]
    jac[1, 2:] = [s * c, dt * sn, 0.5 * dt * s * c, 0.5 * dt * dt * sn]
    jac[2, 4] = dt
    jac[3, 5] = dt
    return out, jac @ p @ jac.T + q * dt


@settings(max_examples=40, deadline=None)
@given(
    st.lists(
        st.tuples(
            st.sampled_from(sorted(_KIND_COMPONENTS)),
            st.floats(0.0, 0.5),
            st.tuples(st.floats(-5.0, 5.0), st.floats(-5.0, 5.0)),
            st.tuples(st.floats(1e-4, 1.0), st.floats(1e-4, 1.0)),
        ),
        min_size=1,
        max_size=10,
    ),
    st.integers(0, 2**32 - 1),
)
def test_fusion_equals_the_documented_model(rows: list[Any], seed: int) -> None:
    x = np.random.default_rng(seed).normal(size=6)
    x[2] = wrap_angle(x[2])
    fusion = PlanarFusion(x, t0=0.0)
    p, q = fusion.P, fusion._q.copy()
    t = 0.0
    for kind, dt, z, var in rows:
        t += dt
        comps = _KIND_COMPONENTS[kind]
        result = _online(fusion, kind, t, z, var)
        x, p = _reference_predict(x, p, q, dt)
        h = np.zeros((len(comps), 6))
        for row, comp in enumerate(comps):
            h[row, comp + 2] = 1.0
        y = np.array(z[: len(comps)]) - h @ x
        if comps == (0,):
            y[0] = wrap_angle(y[0])
        r = np.diag(var[: len(comps)])
        s = h @ p @ h.T + r
        gain = np.linalg.solve(s, h @ p).T
        x = x + gain @ y
        x[2] = wrap_angle(x[2])
        identity = np.eye(6) - gain @ h
        p = identity @ p @ identity.T + gain @ r @ gain.T
        assert result.accepted
        np.testing.assert_allclose(result.residual, y, rtol=1e-7, atol=1e-9)
        assert math.isclose(result.nis, float(y @ np.linalg.solve(s, y)), rel_tol=1e-6,
                            abs_tol=1e-9)  # fmt: skip
        offset = fusion.x - x
        offset[2] = wrap_angle(offset[2])
        assert np.all(np.abs(offset) <= 1e-7 * max(1.0, np.abs(x).max()))
        np.testing.assert_allclose(fusion.P, p, rtol=1e-6, atol=1e-9 * np.abs(p).max())


test_fusion_equals_the_documented_model_thoroughly = slow_twin(
    test_fusion_equals_the_documented_model, max_examples=100
)


_STEPS = st.sampled_from([0.0, 0.01, -0.05, 1e300, 1e20, 5e-324]) | st.floats(-1.0, 2.0)
_VALUES = st.sampled_from([0.0, 1e308, -1e308, 1e150, math.pi, -math.pi]) | st.floats(-10, 10)
_VARIANCES = st.sampled_from([1e-100, 1e100, 1e-3, 1.0])
# What the online API reports for each FusionStatus the batch can give.
_ONLINE_STATUS = {"rejected": 1, "out of order": 3, "overflow": 5}


@settings(max_examples=50, deadline=None)
@given(
    st.lists(
        st.tuples(
            st.sampled_from(sorted(_KIND_COMPONENTS)),
            _STEPS,
            st.tuples(_VALUES, _VALUES),
            st.tuples(_VARIANCES, _VARIANCES),
        ),
        min_size=1,
        max_size=10,
    ),
    st.sampled_from([None, 0.9]),
    st.sampled_from([None, 0.0, 1e300]),
    st.integers(0, 2**32 - 1),
)
def test_batch_equals_online_row_by_row_whatever_the_rows(
    rows: list[Any], gate_probability: float | None, t0: float | None, seed: int
) -> None:
    """Same numbers and statuses, through gating, out-of-order rows, time gaps and overflows.

    The one documented difference: an update that would lose positive
    definiteness raises online (filter unchanged) and keeps the prediction in a
    batch; the comparison stops there.
    """
    x0 = np.random.default_rng(seed).normal(size=6)
    online = PlanarFusion(x0, t0=t0, gate_probability=gate_probability)
    batch = PlanarFusion(x0, t0=t0, gate_probability=gate_probability)
    t = 0.0 if t0 is None else t0
    times, values, variances, observed, expected = [], [], [], [], []
    for kind, dt, z, var in rows:
        t = min(t + dt, 1e308)
        row_values, row_variances, row_observed = np.zeros(4), np.ones(4), np.zeros(4, bool)
        for comp, value, variance in zip(_KIND_COMPONENTS[kind], z, var, strict=False):
            row_values[comp], row_variances[comp], row_observed[comp] = value, variance, True
        times.append(t)
        values.append(row_values)
        variances.append(row_variances)
        observed.append(row_observed)
        try:
            result = _online(online, kind, t, z, var)
        except FilterError as error:
            status = (
                FusionStatus.TIME_GAP if "time gap" in str(error) else
                FusionStatus.NOT_POSITIVE_DEFINITE
            )  # fmt: skip
            nis = math.nan
        else:
            nis = result.nis
            status = FusionStatus.ACCEPTED
            if not result.accepted:
                status = next(
                    FusionStatus(code)
                    for start, code in _ONLINE_STATUS.items()
                    if result.reason.startswith(start)
                )
        expected.append((status, online.x, online.P, nis))
    out = batch.update_batch(MeasurementLog(times, values, variances, observed))
    assert np.all(np.isfinite(out.states)) and np.all(np.isfinite(out.covariances))
    for i, (status, x, p, nis) in enumerate(expected):
        assert out.status[i] == status
        if status == FusionStatus.NOT_POSITIVE_DEFINITE:
            return
        assert np.array_equal(out.states[i], x)
        assert np.array_equal(out.covariances[i], p)
        assert np.array_equal(out.nis[i], nis, equal_nan=True)
    assert batch.t == online.t


test_batch_equals_online_row_by_row_whatever_the_rows_thoroughly = slow_twin(
    test_batch_equals_online_row_by_row_whatever_the_rows, max_examples=300
)


# --- copies of the records ----------------------------------------------------------------


@dataclass(frozen=True, slots=True, eq=False)
class _TaggedResult(UpdateResult):
    tag: str = ""


@dataclass(frozen=True, slots=True, eq=False)
class _TaggedLog(MeasurementLog):
    tag: str = ""


@dataclass(frozen=True, slots=True, eq=False)
class _TaggedFusionResult(FusionResult):
    tag: str = ""


class _NotedResult(UpdateResult):
    pass


class _NotedLog(MeasurementLog):
    pass


class _NotedFusionResult(FusionResult):
    pass


def _records() -> list[tuple[Any, type, type]]:
    """(an instance, its slotted subclass with a field, its subclass with a __dict__)."""
    log = MeasurementLog.from_streams(
        odometry=([0.0, 0.1], [1.0, 1.0], [0.0, 0.1]), yaw=([0.05], [0.2])
    )
    result = PlanarFusion(t0=0.0).update_batch(log)
    update = UpdateResult(False, 2.5, [1.0, -2.0], "rejected by the gate")
    return [
        (update, _TaggedResult, _NotedResult),
        (log, _TaggedLog, _NotedLog),
        (result, _TaggedFusionResult, _NotedFusionResult),
    ]


_COPIES = {
    "copy": copy.copy,
    "deepcopy": copy.deepcopy,
    "pickle": lambda obj: pickle.loads(pickle.dumps(obj)),
}


def _assert_same_record(copied: Any, original: Any) -> None:
    assert type(copied) is type(original)
    for field in fields(original):
        value, expected = getattr(copied, field.name), getattr(original, field.name)
        if isinstance(expected, np.ndarray):
            assert not value.flags.writeable, field.name
            assert np.array_equal(value, expected, equal_nan=True), field.name
        else:
            assert value == expected, field.name


@pytest.mark.parametrize("how", sorted(_COPIES))
@pytest.mark.parametrize("index", range(3))
def test_record_subclasses_copy_whole_with_read_only_arrays(how: str, index: int) -> None:
    # A slotted dataclass subclass got the dataclass's generated __setstate__, which
    # gave deep copies and pickles writeable arrays; a subclass's __dict__ attributes
    # were dropped by every copy.
    original, tagged_class, noted_class = _records()[index]
    values = [getattr(original, field.name) for field in fields(original)]
    tagged = tagged_class(*values, tag="kept")
    noted = noted_class(*values)
    object.__setattr__(noted, "note", ["kept"])
    for record in (original, tagged, noted):
        copied = _COPIES[how](record)
        _assert_same_record(copied, record)
    assert _COPIES[how](tagged).tag == "kept"
    assert _COPIES[how](noted).note == ["kept"]


def test_copying_a_filter_result_leaves_its_residual_as_it_was() -> None:
    result = ExtendedKalmanFilter([0.0], [[1.0]]).update([0.5], lambda x: x, [[1.0]], [[1.0]])
    writeable = result.residual.flags.writeable
    for how in sorted(_COPIES):
        copied = _COPIES[how](result)
        assert not copied.residual.flags.writeable
        assert copied.residual is not result.residual
        assert result.residual.flags.writeable == writeable


@pytest.mark.parametrize("index", range(3))
def test_pickles_in_the_default_layout_still_load_read_only(index: int) -> None:
    # What pickles of the records looked like before they had a __reduce__: the
    # class, then its field values as the state (restored by __setstate__).
    original = _records()[index][0]
    cls = type(original)
    state = [np.array(getattr(original, field.name), copy=True)
             if isinstance(getattr(original, field.name), np.ndarray)
             else getattr(original, field.name) for field in fields(original)]  # fmt: skip
    buffer = io.BytesIO()
    pickler = pickle.Pickler(buffer, protocol=2)
    pickler.dispatch_table = {cls: lambda obj: (copyreg.__newobj__, (cls,), state)}
    pickler.dump(original)
    _assert_same_record(pickle.loads(buffer.getvalue()), original)
