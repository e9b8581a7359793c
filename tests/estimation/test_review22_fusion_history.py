"""PlanarFusion(history=): late measurements fused in stamp order (review 22, FUSION).

A ROS 2 executor serves each topic's backlog in arrival order, interleaved
across topics, after a stall: a filter taking measurements in stamp order only
refused either all odometry or 996 of 1,000 IMU messages
(``tests/test_review21_ros_node.py``). With ``history`` (s) the filter keeps
its steps of the last ``history`` seconds with the state before each, as
robot_localization's ``smooth_lagged_data`` / ``history_length``: a late
measurement within the window goes back to where it belongs and the later
steps are taken again. These tests pin that online the filter then equals
:meth:`PlanarFusion.update_batch` of the same measurements in stamp order,
after every arrival; that older measurements are still refused
(``OUT_OF_ORDER``); that the history is bounded by time; that copies and
pickles keep it (and continue apart); that an interrupt leaves a consistent
filter; and the retry message when the clock was never set.
"""

from __future__ import annotations

import copy
import math
import pickle
from collections.abc import Callable
from typing import Any

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from hypothesis_twins import slow_twin
from interrupt_points import delivery_points, interrupted_at
from navkit._shared.jit import jit_disabled
from navkit.errors import FilterError
from navkit.estimation import FusionStatus, MeasurementLog, PlanarFusion, _fusion

# A measurement: (stamp, kind, value 0, value 1); the variances are fixed per kind.
Meas = tuple[float, str, float, float]
_VARIANCES = {"odometry": (1e-3, 2e-3), "speed": (1e-3,), "yaw": (1e-3,),
              "yaw_rate": (1e-4,), "acceleration": (1e-2,)}  # fmt: skip
_COLUMNS = {"odometry": (1, 2), "speed": (1,), "yaw": (0,), "yaw_rate": (2,),
            "acceleration": (3,)}  # fmt: skip


def _feed(fusion: PlanarFusion, m: Meas) -> Any:
    t, kind, a, b = m
    if kind == "odometry":
        v_var, w_var = _VARIANCES[kind]
        return fusion.update_odometry(t, a, b, v_variance=v_var, omega_variance=w_var)
    if kind == "predict":
        return fusion.predict(t)
    return getattr(fusion, f"update_{kind}")(t, a, variance=_VARIANCES[kind][0])


def _log(measurements: list[Meas]) -> MeasurementLog:
    """The measurements as a log, in the order given."""
    n = len(measurements)
    values = np.zeros((n, 4))
    variances = np.ones((n, 4))
    observed = np.zeros((n, 4), dtype=bool)
    for i, (_, kind, a, b) in enumerate(measurements):
        for col, value, var in zip(_COLUMNS[kind], (a, b), _VARIANCES[kind], strict=False):
            values[i, col] = value
            variances[i, col] = var
            observed[i, col] = True
    times = np.array([m[0] for m in measurements], dtype=float)
    return MeasurementLog(times, values, variances, observed)


# MeasurementLog.from_streams's order at one stamp: odometry (and speed), yaw, yaw rate,
# acceleration.
_TIE_ORDER = {"odometry": 0, "speed": 0, "yaw": 1, "yaw_rate": 2, "acceleration": 3}


def _in_stamp_order(measurements: list[Meas]) -> list[Meas]:
    # Stable: at one stamp in from_streams's order of the kinds, one kind in the order
    # it came (the stream's own order).
    return sorted(measurements, key=lambda m: (m[0], _TIE_ORDER[m[1]]))


def _batch(measurements: list[Meas], **options: Any) -> PlanarFusion:
    """A fresh filter after update_batch of ``measurements`` in stamp order."""
    fusion = PlanarFusion(**options)
    fusion.update_batch(_log(_in_stamp_order(measurements)))
    return fusion


def _assert_same_filter(online: PlanarFusion, batch: PlanarFusion) -> None:
    # Bit for bit: the online steps and the batch rows run the same compiled step.
    assert online.t == batch.t
    np.testing.assert_array_equal(online.x, batch.x)
    np.testing.assert_array_equal(online.P, batch.P)


_MEASUREMENT = st.tuples(
    # Stamp, in units of 10 ms; one in two on a 50 ms grid, so that equal stamps of
    # different kinds (placed in from_streams's tie order) come in most examples.
    st.one_of(st.integers(0, 100), st.integers(0, 20).map(lambda s: 5 * s)),
    st.sampled_from(sorted(_VARIANCES)),
    st.floats(-2.0, 2.0),
    st.floats(-1.0, 1.0),
    st.integers(0, 100),  # delay, in hundredths of the window
)


@settings(max_examples=40, deadline=None)
@given(
    raw=st.lists(_MEASUREMENT, min_size=1, max_size=40),
    window=st.sampled_from([0.02, 0.1, 0.35, 1.0]),
    start=st.sampled_from([None, 0.0]),
    gated=st.booleans(),
)
def test_late_arrivals_within_the_window_equal_the_batch_in_stamp_order(
    raw: list[tuple[int, str, float, float, int]], window: float, start: float | None,
    gated: bool,
) -> None:  # fmt: skip
    # Each measurement arrives after a delay of at most the window, in arrival order;
    # a gate turns some of the larger values away (their decisions must match too).
    arrivals = sorted(
        range(len(raw)), key=lambda i: (raw[i][0] * 0.01 + raw[i][4] * 0.01 * window, i)
    )
    options: dict[str, Any] = {"t0": start, "gate_probability": 0.95 if gated else None}
    online = PlanarFusion(history=window, **options)
    seen: list[Meas] = []
    for i in arrivals:
        stamp, kind, a, b, _ = raw[i]
        m = (stamp * 0.01, kind, a, b)
        result = _feed(online, m)
        # Never refused: nothing arrives later than the window allows.
        assert result.status != FusionStatus.OUT_OF_ORDER, result.reason
        seen.append(m)
        _assert_same_filter(online, _batch(seen, **options))


test_late_arrivals_within_the_window_equal_the_batch_in_stamp_order_thoroughly = slow_twin(
    test_late_arrivals_within_the_window_equal_the_batch_in_stamp_order, max_examples=300
)


def _streams(seconds: float, *, start: float = 0.0) -> tuple[list[Meas], list[Meas]]:
    """/odom at 50 Hz and /imu (yaw rate) at 200 Hz: a robot on a gentle curve."""
    odom = [(start + 0.02 * i, "odometry", 1.0 + 0.01 * math.sin(i), 0.2)
            for i in range(1, int(seconds * 50) + 1)]  # fmt: skip
    imu = [(start + 0.005 * i, "yaw_rate", 0.2 + 0.01 * math.cos(i), 0.0)
           for i in range(1, int(seconds * 200) + 1)]  # fmt: skip
    return odom, imu


@pytest.mark.parametrize("first", ["odom", "imu"])
def test_a_stalled_node_s_backlogs_are_all_taken(first: str) -> None:
    # The review-21 node stand-in's worst case: 5 s backlogs of /odom and /imu, one
    # topic drained entirely before the other. Without history the filter refused all
    # the odometry or 996 of the 1,000 IMU messages; with history=5 it takes every
    # message and ends as the batch in stamp order.
    odom, imu = _streams(5.0)
    order = odom + imu if first == "odom" else imu + odom
    plain = PlanarFusion(t0=0.0)
    assert sum(_feed(plain, m).status == FusionStatus.OUT_OF_ORDER for m in order) >= 249
    online = PlanarFusion(t0=0.0, history=5.0)
    assert all(_feed(online, m).accepted for m in order)
    _assert_same_filter(online, _batch(order, t0=0.0))


def test_older_than_the_window_is_refused_and_changes_nothing() -> None:
    odom, _ = _streams(1.0)
    fusion = PlanarFusion(t0=0.0, history=0.25)
    for m in odom:
        _feed(fusion, m)
    before = (fusion.t, fusion.x.tobytes(), fusion.P.tobytes())
    result = fusion.update_yaw_rate(0.7, 0.2, variance=1e-4)  # 0.3 s late
    assert result.status == FusionStatus.OUT_OF_ORDER and not result.accepted
    assert "history=0.25 s" in str(result.reason)
    assert (fusion.t, fusion.x.tobytes(), fusion.P.tobytes()) == before
    # At the window's edge it is taken, and the filter is the batch with it.
    assert fusion.update_yaw_rate(0.75, 0.2, variance=1e-4).accepted
    _assert_same_filter(fusion, _batch([*odom, (0.75, "yaw_rate", 0.2, 0.0)], t0=0.0))


def test_older_than_the_start_or_a_batch_is_refused() -> None:
    # Nothing is kept from before t0, nor the rows of a batch (sort a log instead).
    fusion = PlanarFusion(t0=1.0, history=10.0)
    fusion.update_yaw_rate(1.5, 0.1, variance=1e-4)
    assert fusion.update_yaw_rate(0.9, 0.1, variance=1e-4).status == FusionStatus.OUT_OF_ORDER
    assert fusion.update_yaw_rate(1.2, 0.1, variance=1e-4).accepted
    fusion.update_batch(_log([(2.0, "yaw_rate", 0.1, 0.0)]))
    refused = fusion.update_yaw_rate(1.8, 0.1, variance=1e-4)
    assert refused.status == FusionStatus.OUT_OF_ORDER
    # Without t0 the first measurement sets the clock, and an older one still goes first.
    fusion = PlanarFusion(history=1.0)
    seen = [(5.0, "yaw", 0.3, 0.0), (4.5, "odometry", 1.0, 0.1)]
    for m in seen:
        assert _feed(fusion, m).accepted
    _assert_same_filter(fusion, _batch(seen))


def test_a_late_measurement_goes_before_a_later_predict() -> None:
    fusion = PlanarFusion(t0=0.0, history=1.0)
    seen = [(0.1, "odometry", 1.0, 0.2), (0.2, "odometry", 1.0, 0.2)]
    for m in seen:
        _feed(fusion, m)
    fusion.predict(0.5)
    assert fusion.update_yaw(0.15, 0.05, variance=1e-3).accepted
    expected = _batch([*seen, (0.15, "yaw", 0.05, 0.0)], t0=0.0)
    expected.predict(0.5)
    _assert_same_filter(fusion, expected)


def test_the_history_is_trimmed_by_time() -> None:
    # The kept steps span the window, whatever the run's length: a pickle after 20 s is
    # the size of one after 2 s.
    odom, imu = _streams(20.0)
    run = _in_stamp_order(odom + imu)
    fusion = PlanarFusion(t0=0.0, history=0.5)
    sizes = {}
    for m in run:
        _feed(fusion, m)
        if m[0] in (2.0, 20.0):
            sizes[m[0]] = len(pickle.dumps(fusion))
    assert len(fusion._entries) <= 0.5 * 250 + 2
    assert 0.9 < sizes[20.0] / sizes[2.0] < 1.1
    assert len(pickle.dumps(PlanarFusion(t0=0.0))) < sizes[2.0] / 10  # a plain filter keeps none


@pytest.mark.parametrize("how", ["copy", "deepcopy", *(f"pickle{p}" for p in range(6))])
def test_copies_keep_the_history_and_continue_apart(how: str) -> None:
    odom, imu = _streams(0.5)
    fusion = PlanarFusion(t0=0.0, history=0.5)
    for m in odom:
        _feed(fusion, m)
    before = (fusion.x.tobytes(), fusion.P.tobytes())
    if how.startswith("pickle"):
        twin = pickle.loads(pickle.dumps(fusion, protocol=int(how[-1])))
    else:
        twin = getattr(copy, how)(fusion)
    assert twin.history == 0.5
    for m in imu:  # all late: taken only through the copied history
        assert _feed(twin, m).accepted
    _assert_same_filter(twin, _batch(odom + imu, t0=0.0))
    assert (fusion.x.tobytes(), fusion.P.tobytes()) == before
    # And the original still takes them, to the same filter.
    for m in imu:
        _feed(fusion, m)
    np.testing.assert_array_equal(fusion.x, twin.x)
    np.testing.assert_array_equal(fusion.P, twin.P)


def test_old_pickles_without_history_load() -> None:
    fusion = PlanarFusion(t0=0.0)
    _feed(fusion, (0.1, "yaw", 0.1, 0.0))
    function, args = fusion.__reduce__()[:2]
    old = function(*args[:4])  # as a pickle made before history existed
    assert old.history == 0.0 and old.t == 0.1
    np.testing.assert_array_equal(old.x, fusion.x)


@pytest.mark.parametrize(
    ("value", "error"),
    [(-0.1, ValueError), (math.inf, ValueError), (math.nan, ValueError), ("1", TypeError),
     (True, TypeError), (None, TypeError)],
)  # fmt: skip
def test_bad_history_is_refused_by_name(value: Any, error: type[Exception]) -> None:
    with pytest.raises(error, match="history"):
        PlanarFusion(history=value)


def test_history_zero_is_the_plain_filter() -> None:
    odom, imu = _streams(0.2)
    plain, zero = PlanarFusion(t0=0.0), PlanarFusion(t0=0.0, history=0.0)
    for m in odom + imu:
        a, b = _feed(plain, m), _feed(zero, m)
        assert (a.status, a.reason) == (b.status, b.reason)
    assert plain._buf.tobytes() == zero._buf.tobytes()
    assert zero.history == 0.0 and not zero._entries


def _late_call(fusion: PlanarFusion) -> Callable[[], object]:
    return lambda: fusion.update_yaw_rate(0.13, 0.25, variance=1e-4)


@pytest.mark.skipif(jit_disabled(), reason="NUMBA_DISABLE_JIT=1: interrupts land inside the step")
@pytest.mark.parametrize("case", ["late", "new", "tie"])
def test_an_interrupt_anywhere_leaves_a_consistent_filter(case: str) -> None:
    # Interrupted at any point an interrupt can be delivered, the filter either took
    # the measurement or did not; and either its history is whole, or it was dropped
    # (a later late measurement refused), never one that disagrees with the filter.
    # "tie": a yaw stamped as the newest step, a yaw rate, goes before it (undone, and
    # taken as a late one).
    odom, _ = _streams(0.3)
    if case == "tie":
        odom.append((odom[-1][0], "yaw_rate", 0.1, 0.0))
    base = PlanarFusion(t0=0.0, history=1.0)
    for m in odom:
        _feed(base, m)
    m1: Meas = {"late": (0.13, "yaw_rate", 0.25, 0.0), "new": (0.31, "yaw_rate", 0.25, 0.0),
                "tie": (odom[-1][0], "yaw", 0.02, 0.0)}[case]  # fmt: skip
    m2: Meas = (0.05, "yaw", 0.02, 0.0)
    took = _batch([*odom, m1], t0=0.0)
    points = delivery_points(lambda: _feed(copy.deepcopy(base), m1))
    assert points > 5
    for k in range(1, points + 1):
        fusion = copy.deepcopy(base)
        interrupted_at(k, lambda f=fusion: _feed(f, m1))  # type: ignore[misc]
        assert fusion._buf[_fusion.BUF_UNDO] == 0.0
        if fusion.t == took.t and np.array_equal(fusion.x, took.x):
            seen = [*odom, m1]
        else:
            _assert_same_filter(fusion, _batch(odom, t0=0.0))
            seen = list(odom)
        second = _feed(fusion, m2)
        if second.accepted:
            _assert_same_filter(fusion, _batch([*seen, m2], t0=0.0))
        else:
            assert second.status == FusionStatus.OUT_OF_ORDER
            _assert_same_filter(fusion, _batch(seen, t0=0.0))


@pytest.mark.parametrize("late", [0.5, 2e6 + 0.05])
def test_a_late_measurement_after_a_long_pause_is_taken_as_in_the_batch(
    late: float, monkeypatch: pytest.MonkeyPatch
) -> None:
    # After a month without measurements the update at the resumption is redone from a
    # loaded prediction (see test_review21_found_fusion_long_gap); taken again behind
    # a late measurement (0.5: before the pause), it is redone the same way, as
    # update_batch does; a late measurement after it goes behind it.
    loads = []
    real_load = _fusion._load
    monkeypatch.setattr(_fusion, "_load", lambda buf: loads.append(1) or real_load(buf))
    x0 = [0.0, 0.0, 0.0, 0.0, 0.01, 0.0]
    gap = 2e6
    seen = [(gap, "yaw", 0.3, 0.0), (gap + 0.1, "yaw_rate", 0.1, 0.0), (late, "yaw", 0.0, 0.0)]
    fusion = PlanarFusion(x0, t0=0.0, history=3e6)
    assert all(_feed(fusion, m).accepted for m in seen)
    assert len(loads) == (2 if late < gap else 1)  # the retry, taken again before
    _assert_same_filter(fusion, _batch(seen, x0=x0, t0=0.0))


def test_the_failed_retry_message_without_a_clock(monkeypatch: pytest.MonkeyPatch) -> None:
    # It said "after a prediction over nan s" for a first measurement (clock not set).
    PlanarFusion(t0=0.0).update_yaw(0.1, 0.0, variance=1e-3)  # the entry compiled
    real = _fusion._step

    def failing(buf: np.ndarray, t: float, first: int, count: int, *rest: float) -> Any:
        status, nis = real(buf, t, first, count, *rest)
        if count > 0 and status == 0:  # every update loses definiteness, marked as the kernel does
            buf[_fusion.BUF_UNDO] = _fusion.NOT_POSITIVE_DEFINITE
            return _fusion.NOT_POSITIVE_DEFINITE, math.nan
        return status, nis

    monkeypatch.setattr(_fusion, "_step", failing)
    fusion = PlanarFusion()
    with pytest.raises(FilterError, match=r"\(without a prediction \(the first measurement\)\)"):
        fusion.update_yaw(3.0, 0.1, variance=1e-3)
    assert fusion.t is None
    fusion = PlanarFusion(t0=1.0)
    with pytest.raises(FilterError, match=r"after a prediction over 2 s"):
        fusion.update_yaw(3.0, 0.1, variance=1e-3)


def test_a_filter_error_keeps_the_history(monkeypatch: pytest.MonkeyPatch) -> None:
    # FilterError leaves the filter as before the call, so the steps kept still hold:
    # a late measurement after it is taken as before.
    monkeypatch.setattr(_fusion, "_load", lambda buf: None)  # the retry fails too
    x0 = [0.0, 0.0, 0.0, 0.0, 0.01, 0.0]
    fusion = PlanarFusion(x0, t0=0.0, history=10.0)
    assert fusion.update_yaw(0.5, 0.0, variance=1e-3).accepted
    with pytest.raises(FilterError, match="not positive definite"):
        fusion.update_yaw(2e6, 0.3, variance=1e-4)
    assert fusion.update_yaw(0.2, 0.0, variance=1e-3).accepted
    _assert_same_filter(fusion, _batch([(0.5, "yaw", 0.0, 0.0), (0.2, "yaw", 0.0, 0.0)],
                                       x0=x0, t0=0.0))  # fmt: skip
