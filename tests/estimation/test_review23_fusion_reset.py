"""PlanarFusion.reset: restart from a given state and time (review 23, FUSION).

robot_localization's ``set_pose`` / reset service: a localisation fix (or a
relocated robot) restarts the filter from a new state and time, keeping its
process noise, gate and ``history`` window. These tests pin that afterwards the
filter is the one the constructor would build, bit for bit (its buffer, the
anchor of a far start, and every later result, with ``history=`` too); that the
steps kept for ``history`` are dropped; that copies and pickles of a reset filter
continue as the filter does; that bad input raises as the constructor does,
with its message, and leaves the filter unchanged; and that an interrupt leaves
the filter either reset or untouched.

The same session made the online updates build their accepted results more
cheaply (``_result._Building``); the last test pins that these are
UpdateResults in every respect, the same as the general path's.
"""

from __future__ import annotations

import copy
import dataclasses
import pickle
from dataclasses import FrozenInstanceError
from typing import Any

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from interrupt_points import delivery_points, interrupted_at
from navkit.estimation import FusionStatus, PlanarFusion, UpdateResult
from navkit.estimation._result import _Building
from navkit.geometry import Pose2D

# Fixed options of the filters compared: the reset filter keeps them.
_OPTIONS: dict[str, Any] = {
    "process_noise": np.array([0.01, 0.02, 0.03, 0.04, 0.05, 0.06]),
    "gate_probability": 0.999,
}


def _feed(fusion: PlanarFusion, t: float, kind: int, value: float) -> Any:
    """One measurement of ``kind`` (0 odometry, 1 yaw, 2 yaw rate, 3 acceleration, 4 predict)."""
    if kind == 0:
        return fusion.update_odometry(t, value, 0.1, v_variance=1e-3, omega_variance=2e-3)
    if kind == 1:
        return fusion.update_yaw(t, value, variance=1e-3)
    if kind == 2:
        return fusion.update_yaw_rate(t, value, variance=1e-4)
    if kind == 3:
        return fusion.update_acceleration(t, value, variance=1e-2)
    last = fusion.t
    if last is not None and t < last:
        return None  # predict refuses an older time (ValueError), both filters alike
    return fusion.predict(t)


def _state(fusion: PlanarFusion) -> tuple[bytes, tuple[float, float], list[Any], float]:
    """Everything a filter's later results depend on, comparable bit for bit."""
    entries = [
        (t, repr(before), saved.tobytes(), args, kind)  # before: NaN when the clock was unset
        for t, before, saved, args, kind in fusion._entries
    ]
    return fusion._buf.tobytes(), fusion._anchor, entries, fusion.history


def _same_results(a: Any, b: Any) -> None:
    if a is None or b is None:  # predict
        assert a is b is None
        return
    assert (a.accepted, a.status, a.reason) == (b.accepted, b.status, b.reason)
    assert np.array_equal(np.array(a.nis), np.array(b.nis), equal_nan=True)
    assert a.residual.tobytes() == b.residual.tobytes()


def _run(fusion: PlanarFusion, steps: list[tuple[float, int, float]]) -> list[Any]:
    return [_feed(fusion, t, kind, value) for t, kind, value in steps]


_STEPS = st.lists(
    st.tuples(
        st.floats(-0.3, 1.0).map(lambda d: round(d, 3)),  # offset from the reset time
        st.integers(0, 4),
        st.floats(-2.0, 2.0),
    ),
    max_size=12,
)


@settings(max_examples=40, deadline=None)
@given(
    before=_STEPS,
    after=_STEPS,
    start=st.lists(st.floats(-1e7, 1e7), min_size=6, max_size=6),
    variances=st.lists(st.floats(1e-6, 10.0), min_size=6, max_size=6),
    t0=st.one_of(st.none(), st.floats(0.0, 100.0)),
    history=st.sampled_from([0.0, 0.4]),
)
def test_a_reset_filter_is_a_new_filter_bit_for_bit(
    before: list[tuple[float, int, float]],
    after: list[tuple[float, int, float]],
    start: list[float],
    variances: list[float],
    t0: float | None,
    history: float,
) -> None:
    # Rates within reason (the far positions exercise the anchor), the reset from
    # wherever the earlier measurements left the filter, late ones included.
    x0 = np.array([*start[:3], *(np.clip(start[3:], -5.0, 5.0))])
    fusion = PlanarFusion(t0=0.0, history=history, **_OPTIONS)
    _run(fusion, [(0.5 + d, kind, v) for d, kind, v in before])
    fusion.reset(x0, np.array(variances), t0=t0)
    fresh = PlanarFusion(x0, np.array(variances), t0=t0, history=history, **_OPTIONS)
    assert _state(fusion) == _state(fresh)
    assert fusion.t == fresh.t
    origin = 0.0 if t0 is None else t0
    later = [(origin + d, kind, v) for d, kind, v in after]
    for got, want in zip(_run(fusion, later), _run(fresh, later), strict=True):
        _same_results(got, want)
    assert _state(fusion) == _state(fresh)


def test_reset_drops_the_steps_kept_for_history() -> None:
    fusion = PlanarFusion(t0=0.0, history=1.0)
    for t in (0.1, 0.2, 0.3):
        fusion.update_odometry(t, 1.0, 0.0, v_variance=1e-4, omega_variance=1e-4)
    assert fusion.update_yaw_rate(0.15, 0.0, variance=1e-4).accepted  # within the window
    fusion.reset(pose=(1.0, 2.0, 0.3), t0=0.3)
    assert fusion._entries == []
    assert fusion.history == 1.0  # the window is kept, its steps are not
    late = fusion.update_yaw_rate(0.25, 0.0, variance=1e-4)
    assert late.status == FusionStatus.OUT_OF_ORDER
    assert fusion.pose == Pose2D(1.0, 2.0, 0.3)
    # Steps after the reset are kept again: a late one among them is fused.
    for t in (0.4, 0.5):
        fusion.update_odometry(t, 1.0, 0.0, v_variance=1e-4, omega_variance=1e-4)
    assert fusion.update_yaw_rate(0.45, 0.0, variance=1e-4).accepted


def test_reset_without_t0_lets_the_next_measurement_set_the_clock() -> None:
    fusion = PlanarFusion(t0=5.0)
    fusion.update_odometry(6.0, 1.0, 0.0, v_variance=1e-4, omega_variance=1e-4)
    fusion.reset([1.0, 0.0, 0.0, 0.0, 0.0, 0.0])
    assert fusion.t is None
    # Earlier than the filter's time before the reset: no longer out of order.
    assert fusion.update_yaw(2.0, 0.1, variance=1e-3).accepted
    assert fusion.t == 2.0


def test_reset_keeps_the_buffer_and_its_views() -> None:
    # x, P and Q are views of the buffer that the compiled step updates in place.
    fusion = PlanarFusion(t0=0.0)
    buf, x = fusion._buf, fusion._x
    fusion.reset([3.0, 0.0, 0.0, 1.0, 0.0, 0.0], t0=1.0)
    assert fusion._buf is buf and fusion._x.base is buf and x[3] == 1.0
    fusion.update_odometry(2.0, 1.0, 0.0, v_variance=1e-4, omega_variance=1e-4)
    assert fusion.pose.x == pytest.approx(4.0, abs=1e-6)


def test_copies_and_pickles_of_a_reset_filter_continue_as_it_does() -> None:
    fusion = PlanarFusion(t0=0.0, history=0.5, **_OPTIONS)
    for t in (0.1, 0.2):
        fusion.update_odometry(t, 1.0, 0.2, v_variance=1e-4, omega_variance=1e-4)
    x0 = [4e6, -3e5, 3.0, 0.5, 0.0, 0.0]
    fusion.reset(x0, t0=10.0)
    fresh = PlanarFusion(x0, t0=10.0, history=0.5, **_OPTIONS)
    steps = [(10.1, 0, 1.0), (10.2, 2, 0.1), (10.15, 1, 3.05), (10.3, 3, 0.2)]
    twins = [pickle.loads(pickle.dumps(fusion)), copy.deepcopy(fusion), copy.copy(fusion)]
    for twin in twins:
        assert _state(twin) == _state(fresh)
    want = _run(fresh, steps)
    for twin in [fusion, *twins]:
        for got, expected in zip(_run(twin, steps), want, strict=True):
            _same_results(got, expected)
        assert _state(twin) == _state(fresh)
    # Pickled after steps that are kept for history: the same again.
    again = pickle.loads(pickle.dumps(fusion))
    assert len(again._entries) == 4
    assert _state(again) == _state(fresh)


# (arguments, exception type): each refused by the constructor with the same message.
_BAD: list[tuple[tuple[Any, ...], dict[str, Any], type[Exception]]] = [
    ((np.zeros(5),), {}, ValueError),
    (([0.0, 0.0, float("nan"), 0.0, 0.0, 0.0],), {}, ValueError),
    (("abcdef",), {}, TypeError),
    ((None, np.diag([1.0, 1.0, 1.0, 1.0, 1.0, -1.0])), {}, ValueError),
    ((None, np.ones((6, 6))), {}, ValueError),
    ((None, np.eye(5)), {}, ValueError),
    ((None, np.full(6, 1e-320)), {}, ValueError),
    ((), {"t0": float("inf")}, ValueError),
    ((), {"t0": 2**60}, ValueError),
    ((), {"t0": "1.0"}, TypeError),
    ((), {"t0": True}, TypeError),
    ((np.zeros(6),), {"pose": (0.0, 0.0, 0.0)}, ValueError),
    ((), {"pose": (0.0, 0.0)}, ValueError),
    # The first bad argument in the constructor's order is the one named.
    ((np.zeros(3), np.eye(2)), {"t0": float("nan")}, ValueError),
    ((None, np.eye(2)), {"t0": float("nan")}, ValueError),
]


@pytest.mark.parametrize(("args", "kwargs", "error"), _BAD)
def test_bad_input_raises_as_the_constructor_and_leaves_the_filter_unchanged(
    args: tuple[Any, ...], kwargs: dict[str, Any], error: type[Exception]
) -> None:
    fusion = PlanarFusion([1e6, 2.0, 0.5, 1.0, 0.0, 0.0], t0=0.0, history=0.5)
    for t in (0.1, 0.2, 0.3):
        fusion.update_odometry(t, 1.0, 0.1, v_variance=1e-4, omega_variance=1e-4)
    before = _state(fusion)
    with pytest.raises(error) as constructor:
        PlanarFusion(*args, **kwargs)
    with pytest.raises(error) as reset:
        fusion.reset(*args, **kwargs)
    assert str(reset.value) == str(constructor.value)
    assert _state(fusion) == before
    # And the filter goes on as one never reset.
    twin = PlanarFusion([1e6, 2.0, 0.5, 1.0, 0.0, 0.0], t0=0.0, history=0.5)
    for t in (0.1, 0.2, 0.3):
        twin.update_odometry(t, 1.0, 0.1, v_variance=1e-4, omega_variance=1e-4)
    _same_results(
        fusion.update_yaw(0.25, 0.4, variance=1e-3), twin.update_yaw(0.25, 0.4, variance=1e-3)
    )
    assert _state(fusion) == _state(twin)


def test_reset_does_not_modify_its_inputs() -> None:
    x0 = np.array([1.0, 2.0, 7.0, 0.0, 0.0, 0.0])  # a heading beyond π, wrapped in the filter
    p0 = np.diag([1.0, 2.0, 3.0, 4.0, 5.0, 6.0])
    x0_copy, p0_copy = x0.copy(), p0.copy()
    fusion = PlanarFusion(t0=0.0)
    fusion.reset(x0, p0, t0=1.0)
    assert np.array_equal(x0, x0_copy) and np.array_equal(p0, p0_copy)
    assert fusion.x[2] == pytest.approx(7.0 - 2 * np.pi)
    fusion.update_yaw(1.1, 0.0, variance=1e-3)
    assert np.array_equal(x0, x0_copy) and np.array_equal(p0, p0_copy)


def test_an_interrupted_reset_has_happened_or_not() -> None:
    base = PlanarFusion(t0=0.0, history=0.5)
    for t in (0.1, 0.2, 0.3):
        base.update_odometry(t, 1.0, 0.1, v_variance=1e-4, omega_variance=1e-4)
    x0 = [5e6, 1.0, 0.2, 0.3, 0.0, 0.0]
    untouched = _state(base)
    done = copy.deepcopy(base)
    done.reset(x0, t0=1.0)
    reset = _state(done)
    probe = copy.deepcopy(base)
    points = delivery_points(lambda: probe.reset(x0, t0=1.0))
    assert points > 5
    outcomes = []
    for k in range(1, points + 1):
        fusion = copy.deepcopy(base)
        assert interrupted_at(k, lambda f=fusion: f.reset(x0, t0=1.0))  # type: ignore[misc]
        # Interrupted before the stores: untouched; after them (the end of the one-call
        # check of a filter with history, review 37): reset. Never part-way.
        outcomes.append(_state(fusion) == untouched)
        assert outcomes[-1] or _state(fusion) == reset
        assert fusion._callers == []
    # Untouched at every point up to the stores, reset at every one after them.
    assert outcomes == sorted(outcomes, reverse=True) and outcomes.count(True) > 5
    fusion = copy.deepcopy(base)
    assert not interrupted_at(points + 1, lambda: fusion.reset(x0, t0=1.0))
    assert _state(fusion) == reset


# ------------------------------------------------------------------------ results
# The online updates build their accepted results as _result._Building instances
# turned UpdateResults (plain slot stores, then __class__): they must be
# UpdateResults in every respect, as the validating constructor's are.


def _accepted_results() -> list[tuple[Any, Any]]:
    """(fast path result, general path result) of each update kind, same filter state."""
    calls = [
        lambda f, c: f.update_odometry(c(0.1), c(1.0), c(0.2), v_variance=c(1e-2),
                                       omega_variance=c(1e-2)),
        lambda f, c: f.update_speed(c(0.1), c(1.0), variance=c(1e-2)),
        lambda f, c: f.update_yaw(c(0.1), c(0.3), variance=c(1e-2)),
        lambda f, c: f.update_yaw_rate(c(0.1), c(0.3), variance=c(1e-2)),
        lambda f, c: f.update_acceleration(c(0.1), c(0.3), variance=c(1e-2)),
    ]  # fmt: skip
    return [
        (update(PlanarFusion(t0=0.0), float), update(PlanarFusion(t0=0.0), np.float64))
        for update in calls
    ]


def test_accepted_results_are_update_results_in_every_respect() -> None:
    assert _Building.__slots__ == UpdateResult.__slots__
    for fast, general in _accepted_results():
        for result in (fast, general):
            assert type(result) is UpdateResult
            assert result.accepted and result.reason is None
            assert result.status is FusionStatus.ACCEPTED
            assert result.residual.flags.writeable and result.residual.base is None
        assert repr(fast) == repr(general)
        assert fast.nis == general.nis
        assert fast.residual.tobytes() == general.residual.tobytes()
        reference = UpdateResult(True, fast.nis, fast.residual, None, FusionStatus.ACCEPTED)
        assert repr(reference) == repr(fast)
        with pytest.raises(FrozenInstanceError):
            fast.nis = 1.0  # type: ignore[misc]
        again = pickle.loads(pickle.dumps(fast))
        assert type(again) is UpdateResult and repr(again) == repr(fast)
        assert not again.residual.flags.writeable
        assert repr(copy.copy(fast)) == repr(fast)
        assert dataclasses.replace(fast, nis=2.0).nis == 2.0
        assert dataclasses.asdict(fast)["status"] is FusionStatus.ACCEPTED
