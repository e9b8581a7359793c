"""PlanarFusion after a long time without measurements (review 21, known defects).

After weeks without a measurement (2e6 s at the default process noise, with a
yaw rate of 0.01 rad/s in the state) the predicted covariance is positive
definite only in exact arithmetic: heading and yaw rate, speed and
acceleration, position and heading are correlated to within rounding, and
every update raised ``FilterError`` ("covariance is not positive definite"),
so a robot paused for a month could not be resumed without a new filter. Such
an update is now redone from its prediction with every variance raised by
2**-40 of itself; online and in ``update_batch`` alike.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from navkit.estimation import FusionStatus, MeasurementLog, PlanarFusion, _fusion

_KINDS = ("speed", "odometry", "yaw", "yaw_rate", "acceleration")


def _update(fusion: PlanarFusion, kind: str, t: float, value: float = 0.3):  # type: ignore[no-untyped-def]
    if kind == "odometry":
        return fusion.update_odometry(t, value, 0.1, v_variance=1e-4, omega_variance=1e-4)
    return getattr(fusion, f"update_{kind}")(t, value, variance=1e-4)


def _kernel_loses_definiteness(fusion: PlanarFusion, kind: str, t: float) -> bool:
    """Whether the compiled step alone (no loaded retry) fails this update."""
    first, count, gate, _ = fusion._kinds[kind]
    z1 = 0.1 if count == 2 else 0.0
    buf = fusion._buf.copy()
    status, _ = _fusion._step(buf, t, first, count, 0.3, z1, 1e-4, 1e-4, gate)
    return bool(status == _fusion.NOT_POSITIVE_DEFINITE)


@pytest.mark.parametrize("kind", _KINDS)
def test_a_month_paused_then_resumed(kind: str) -> None:
    # 2e6 s (23 days) at the default process noise, the yaw rate last estimated at
    # 0.01 rad/s: every kind but the speed lost definiteness in the compiled step.
    gap = 2e6
    fusion = PlanarFusion([0.0, 0.0, 0.0, 0.0, 0.01, 0.0], t0=0.0)
    if kind not in ("speed", "odometry"):
        assert _kernel_loses_definiteness(fusion, kind, gap)
    result = _update(fusion, kind, gap)
    assert result.accepted and fusion.t == gap
    np.linalg.cholesky(fusion.P)
    # And the filter goes on as after any start: 1 s of readings at 100 Hz.
    for i in range(1, 101):
        t = gap + 0.01 * i
        assert fusion.update_odometry(t, 1.0, 0.2, v_variance=1e-4, omega_variance=1e-4).accepted
        assert fusion.update_yaw(t, 0.3 + 0.002 * i, variance=1e-4).accepted
    assert abs(fusion.x[3] - 1.0) < 0.01 and abs(fusion.x[4] - 0.2) < 0.01
    assert abs(fusion.x[2] - 0.5) < 0.01


@settings(max_examples=60, deadline=None)
@given(
    log_gap=st.floats(5.0, 12.0),
    v=st.sampled_from([0.0, 1.0, 1e3]),
    omega=st.floats(-3.0, 3.0),
    kind=st.sampled_from(_KINDS),
    identity=st.booleans(),
)
def test_a_reading_after_any_long_gap_is_taken(
    log_gap: float, v: float, omega: float, kind: str, identity: bool
) -> None:
    gap = 10.0**log_gap
    fusion = PlanarFusion([0.0, 0.0, 0.0, v, omega, 0.0], P0=np.eye(6) if identity else None,
                          t0=0.0)  # fmt: skip
    result = _update(fusion, kind, gap)
    assert result.accepted, result.reason
    assert math.isfinite(result.nis) and np.isfinite(fusion.x).all()
    np.linalg.cholesky(fusion.P)
    assert fusion._buf[_fusion.BUF_UNDO] == 0.0


def test_the_retry_changes_nothing_but_the_loaded_variances() -> None:
    # The retried update is the update of the prediction with its variances raised
    # by 2**-40 of themselves, bit for bit.
    fusion = PlanarFusion([0.0, 0.0, 0.0, 0.0, 0.01, 0.0], t0=0.0)
    twin = PlanarFusion([0.0, 0.0, 0.0, 0.0, 0.01, 0.0], t0=0.0)
    assert fusion.update_yaw(2e6, 0.3, variance=1e-4).accepted
    twin.predict(2e6)
    twin._p[np.diag_indices(6)] += twin._p.diagonal() * 2.0**-40
    assert twin.update_yaw(2e6, 0.3, variance=1e-4).accepted
    np.testing.assert_array_equal(fusion.x, twin.x)
    np.testing.assert_array_equal(fusion.P, twin.P)


def test_a_failed_retry_leaves_the_filter_unchanged(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(_fusion, "_load", lambda buf: None)  # the retry is the step again
    fusion = PlanarFusion([0.0, 0.0, 0.0, 0.0, 0.01, 0.0], t0=5.0)
    before = (fusion.t, fusion.x.tobytes(), fusion.P.tobytes())
    with pytest.raises(_fusion.FilterError, match=r"not positive definite \(after a prediction"
                       r" over 2e\+06 s\); the filter is unchanged"):  # fmt: skip
        fusion.update_yaw(5.0 + 2e6, 0.3, variance=1e-4)
    assert (fusion.t, fusion.x.tobytes(), fusion.P.tobytes()) == before


def test_an_interrupt_after_the_retry_undoes_the_whole_call(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    # The retried buffer saves the state from before the call: an interrupt as the
    # call returns (after the copy) is undone to it, never to the loaded prediction.
    real_load = _fusion._load
    fusion = PlanarFusion([0.0, 0.0, 0.0, 0.0, 0.01, 0.0], t0=0.0)
    before = (fusion.t, fusion.x.tobytes(), fusion.P.tobytes())
    original_copyto = np.copyto

    def copy_then_interrupt(dst, src, *args, **kwargs):  # type: ignore[no-untyped-def]
        original_copyto(dst, src, *args, **kwargs)
        if dst is fusion._buf:
            raise KeyboardInterrupt

    monkeypatch.setattr(_fusion, "_load", real_load)
    monkeypatch.setattr(_fusion.np, "copyto", copy_then_interrupt)
    with pytest.raises(KeyboardInterrupt):
        fusion.update_yaw(2e6, 0.3, variance=1e-4)
    monkeypatch.undo()
    assert (fusion.t, fusion.x.tobytes(), fusion.P.tobytes()) == before
    assert fusion.update_yaw(2e6, 0.3, variance=1e-4).accepted


def test_update_batch_takes_the_long_gap_as_the_online_updates(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    gap = 2e6
    x0 = [0.0, 0.0, 0.0, 0.0, 0.01, 0.0]
    # The first reading after the gap is a yaw: the row the kernel alone
    # does not take; then a second gap, which needs no retry.
    t_odo = np.array([gap + 0.1, gap + 0.2])
    t_yaw = np.array([0.1, gap, gap + 0.15, gap + 0.2 + 1e7])
    log = MeasurementLog.from_streams(
        odometry=(t_odo, np.full(2, 1.0), np.full(2, 0.2)),
        yaw=(t_yaw, np.array([0.0, 0.5, 0.52, 0.1])),
    )
    loads = []
    real_load = _fusion._load
    monkeypatch.setattr(_fusion, "_load", lambda buf: loads.append(1) or real_load(buf))
    batch = PlanarFusion(x0, t0=0.0)
    result = batch.update_batch(log)
    assert (result.status == FusionStatus.ACCEPTED).all(), result.status
    assert len(loads) == 1  # the row after the first gap was redone
    online = PlanarFusion(x0, t0=0.0)
    for i in range(len(log)):
        t = float(log.times[i])
        v = log.values[i]
        var = log.variances[i]
        if log.observed[i, 1]:
            online.update_odometry(t, float(v[1]), float(v[2]), v_variance=float(var[1]),
                                   omega_variance=float(var[2]))  # fmt: skip
        else:
            online.update_yaw(t, float(v[0]), variance=float(var[0]))
        np.testing.assert_array_equal(result.states[i], online.x)
        np.testing.assert_array_equal(result.covariances[i], online.P)
    assert len(loads) == 2  # and so was the online update
    assert batch.t == online.t == gap + 0.2 + 1e7
    np.testing.assert_array_equal(batch.P, online.P)


def test_update_batch_keeps_a_row_whose_retry_fails(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(_fusion, "_load", lambda buf: None)
    log = MeasurementLog.from_streams(yaw=(np.array([2e6, 2e6 + 0.1]), np.array([0.3, 0.3])))
    fusion = PlanarFusion([0.0, 0.0, 0.0, 0.0, 0.01, 0.0], t0=0.0)
    result = fusion.update_batch(log)
    assert result.status[0] == FusionStatus.NOT_POSITIVE_DEFINITE
    twin = PlanarFusion([0.0, 0.0, 0.0, 0.0, 0.01, 0.0], t0=0.0)
    twin.predict(2e6)  # the row keeps its prediction, not loaded
    np.testing.assert_array_equal(result.covariances[0], twin.P)
    assert fusion.t == 2e6 + 0.1
