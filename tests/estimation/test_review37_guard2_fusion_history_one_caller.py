"""A PlanarFusion with ``history`` takes one call at a time (review 37, GUARD2).

With ``history`` the filter keeps its recent steps to fuse late measurements
again in stamp order. A signal handler's update (or another thread's) that ran
inside an update of the main thread corrupted them without an error: between
the main update's step and its record, the handler's step was kept first, so
the steps kept were out of time order and their saved states wrong; during a
late measurement's replay, the handler's update was overwritten by the
replayed buffer (its result said accepted, its measurement was lost). Later
late measurements were then fused wrongly (0.17 to 0.26 m and rad off the
batch of the same measurements). Now every update, ``predict``, ``reset``
and ``update_batch`` of a filter with history refuses to start while another
is under way (``RuntimeError``, saying whose), changing nothing, and the call
under way goes on as alone. Without history the calls are not checked (the
check would cost a third to a half of a step: see the class notes).

The interleavings are forced: a profile hook runs the second call at every
point where CPython runs a signal handler (``interrupt_points.DELIVERY``).
"""

from __future__ import annotations

import copy
import pickle
from collections.abc import Callable
from typing import Any

import numpy as np
import pytest

from interrupt_points import interleaved
from navkit.estimation import MeasurementLog, PlanarFusion
from thread_runs import run_switching_often

ODO = {"v_variance": 1e-2, "omega_variance": 1e-2}
RATE_VAR = 1e-3
# The filter's steps before each case: odometry at 0.1 ... 0.5 s.
BASE_ODOMETRY = [(0.1 * i, 1.0, 0.1 * i) for i in range(1, 6)]


def _base() -> PlanarFusion:
    fusion = PlanarFusion(t0=0.0, history=1.0)
    for t, v, w in BASE_ODOMETRY:
        fusion.update_odometry(t, v, w, **ODO)
    return fusion


def _batch(odometry: list[tuple[float, float, float]], rates: list[tuple[float, float]]) -> Any:
    """The state after the batch of these measurements in stamp order (from_streams)."""
    odo = sorted(odometry)
    streams: dict[str, Any] = {
        "odometry": ([o[0] for o in odo], [o[1] for o in odo], [o[2] for o in odo]),
        "odometry_variance": (ODO["v_variance"], ODO["omega_variance"]),
    }
    if rates:
        rate = sorted(rates)
        streams["yaw_rate"] = ([r[0] for r in rate], [r[1] for r in rate])
        streams["yaw_rate_variance"] = RATE_VAR
    return PlanarFusion(t0=0.0).update_batch(MeasurementLog.from_streams(**streams)).states[-1]


# (main call, handler call), each as (kind, stamp, value): odometry or a yaw rate,
# in order or late (before the filter time 0.5 s).
CASES = {
    "in-order odometry, handler's in-order odometry": (("odo", 0.6, 1.2), ("odo", 0.7, 0.8)),
    "late yaw rate, handler's in-order odometry": (("rate", 0.25, 0.5), ("odo", 0.6, 1.2)),
    "in-order odometry, handler's late yaw rate": (("odo", 0.6, 1.2), ("rate", 0.25, 0.5)),
    "late yaw rate, handler's late yaw rate": (("rate", 0.25, 0.5), ("rate", 0.15, -0.4)),
}


def _call(fusion: PlanarFusion, what: tuple[str, float, float]) -> Callable[[], Any]:
    kind, t, value = what
    if kind == "odo":
        return lambda: fusion.update_odometry(t, value, 0.0, **ODO)
    return lambda: fusion.update_yaw_rate(t, value, variance=RATE_VAR)


def _taken(what: tuple[str, float, float]) -> tuple[list[Any], list[Any]]:
    kind, t, value = what
    return ([(t, value, 0.0)], []) if kind == "odo" else ([], [(t, value)])


@pytest.mark.parametrize("case", list(CASES))
def test_a_handlers_update_at_every_point_is_refused_or_fused_in_stamp_order(case: str) -> None:
    main, other = CASES[case]
    points = interleaved(0, _call(_base(), main), lambda: None)["points"]
    assert points > 5
    refused = 0
    for k in range(1, points + 1):
        fusion = _base()
        out = interleaved(k, _call(fusion, main), _call(fusion, other))
        odometry, rates = list(BASE_ODOMETRY), []
        for who, what in (("m", main), ("h", other)):
            result = out.get(who)
            if isinstance(result, RuntimeError):
                refused += 1
                assert "in the same thread (from a signal handler?)" in str(result)
                continue
            if result is None:
                continue  # fewer points this time: the handler did not run
            assert result.accepted, (k, who, result.reason)
            odo, rate = _taken(what)
            odometry += odo
            rates += rate
        assert isinstance(out["m"], RuntimeError) or out["m"].accepted
        assert fusion._callers == []
        # The steps kept are right: a later late measurement is fused as in the batch.
        assert fusion.update_yaw_rate(0.35, -0.3, variance=RATE_VAR).accepted
        want = _batch(odometry, [*rates, (0.35, -0.3)])
        np.testing.assert_allclose(fusion.x, want, rtol=0, atol=1e-12, err_msg=f"k={k}")
    assert refused > 0


def _state(fusion: PlanarFusion) -> tuple[Any, ...]:
    kept = [(e[0], e[1], e[2].tobytes(), e[3], e[4]) for e in fusion._entries]
    return fusion._buf.tobytes(), kept


def test_the_refusal_names_both_calls_and_changes_nothing() -> None:
    fusion = _base()
    alone = _base()
    alone.update_odometry(0.6, 1.2, 0.0, **ODO)
    messages: list[str] = []

    def handler() -> None:
        before = _state(fusion)
        try:
            fusion.update_yaw(0.55, 0.3, variance=1e-3)
        except RuntimeError as error:
            messages.append(str(error))
            assert _state(fusion) == before
            raise

    points = interleaved(0, _call(_base(), ("odo", 0.6, 1.2)), lambda: None)["points"]
    for k in range(1, points + 1):
        fusion = _base()
        out = interleaved(k, _call(fusion, ("odo", 0.6, 1.2)), handler)
        assert fusion._callers == []
        if isinstance(out.get("h"), RuntimeError):
            assert _state(fusion) == _state(alone)
    assert messages
    assert messages[0] == (
        "PlanarFusion.update_yaw was called during this PlanarFusion's own "
        "update_odometry, in the same thread (from a signal handler?): a PlanarFusion "
        "takes one call at a time"
    )


@pytest.mark.parametrize(
    "name",
    ["predict", "reset", "update_batch", "update_speed", "update_acceleration", "update_yaw"],
)
def test_every_method_of_a_filter_with_history_is_refused_during_another(name: str) -> None:
    fusion = _base()
    calls: dict[str, Callable[[], Any]] = {
        "predict": lambda: fusion.predict(0.9),
        "reset": lambda: fusion.reset(pose=(1.0, 2.0, 0.0), t0=0.9),
        "update_batch": lambda: fusion.update_batch(
            MeasurementLog.from_streams(yaw=([0.9], [0.1]), yaw_variance=1e-3)
        ),
        "update_speed": lambda: fusion.update_speed(0.9, 1.0, variance=1e-2),
        "update_acceleration": lambda: fusion.update_acceleration(0.9, 0.1, variance=1e-2),
        "update_yaw": lambda: fusion.update_yaw(0.9, 0.1, variance=1e-3),
    }
    seen: list[BaseException] = []

    def inside() -> None:
        try:
            calls[name]()
        except RuntimeError as error:
            seen.append(error)

    alone = _base()
    alone.update_yaw_rate(0.45, 0.2, variance=RATE_VAR)  # a late one: rewound and replayed
    # A point inside the late measurement's replay: the step kept at 0.5 s taken again.
    points = interleaved(0, _call(_base(), ("rate", 0.45, 0.2)), lambda: None)["points"]
    out = interleaved(points // 2, _call(fusion, ("rate", 0.45, 0.2)), inside)
    assert len(seen) == 1, out
    assert f"PlanarFusion.{name} was called during this PlanarFusion's own update_yaw_rate" in (
        str(seen[0])
    )
    assert out["m"].accepted
    assert fusion.x.tobytes() == alone.x.tobytes() and fusion.t == 0.5
    assert fusion._callers == []


def test_copies_and_pickles_of_a_filter_in_use_are_not_in_use() -> None:
    fusion = _base()
    copies: list[PlanarFusion] = []

    def take() -> None:
        copies.extend((copy.copy(fusion), copy.deepcopy(fusion)))
        copies.append(pickle.loads(pickle.dumps(fusion)))

    points = interleaved(0, _call(_base(), ("rate", 0.45, 0.2)), lambda: None)["points"]
    interleaved(points // 2, _call(fusion, ("rate", 0.45, 0.2)), take)
    assert len(copies) == 3
    for other in copies:
        assert other._callers == []
        assert other.update_odometry(0.6, 1.0, 0.0, **ODO).accepted


def test_two_threads_on_one_filter_with_history_are_refused_or_fused_in_stamp_order() -> None:
    fusion = PlanarFusion(t0=0.0, history=100.0)
    odometry: list[tuple[float, float, float]] = []
    rates: list[tuple[float, float]] = []
    outcomes: list[list[str]] = [[], []]

    def feed(k: int) -> None:
        for i in range(1, 1500):
            t = 0.01 * i + 0.003 * k
            try:
                if k == 0:
                    result = fusion.update_odometry(t, 1.0 + 0.1 * (i % 3), 0.05, **ODO)
                else:
                    result = fusion.update_yaw_rate(t, 0.02 * (i % 5), variance=RATE_VAR)
            except RuntimeError as error:
                outcomes[k].append("refused" if "another thread" in str(error) else repr(error))
                continue
            except Exception as error:  # what a corrupted history may raise
                outcomes[k].append(repr(error))
                continue
            outcomes[k].append("accepted" if result.accepted else str(result.reason))
            if result.accepted:
                if k == 0:
                    odometry.append((t, 1.0 + 0.1 * (i % 3), 0.05))
                else:
                    rates.append((t, 0.02 * (i % 5)))

    run_switching_often(feed)
    for seen in outcomes:
        assert set(seen) <= {"accepted", "refused"}, sorted(set(seen))[:3]
    assert fusion._callers == []
    # Every accepted measurement is in the estimate, in stamp order (odometry values
    # in the batch take the omega column; see _batch).
    streams = MeasurementLog.from_streams(
        odometry=([o[0] for o in odometry], [o[1] for o in odometry], [o[2] for o in odometry]),
        odometry_variance=(ODO["v_variance"], ODO["omega_variance"]),
        yaw_rate=([r[0] for r in rates], [r[1] for r in rates]),
        yaw_rate_variance=RATE_VAR,
    )
    want = PlanarFusion(t0=0.0).update_batch(streams).states[-1]
    np.testing.assert_allclose(fusion.x, want, rtol=0, atol=1e-9)


def test_without_history_the_calls_are_not_checked() -> None:
    # Documented: the check would cost a third to a half of a step, so a filter
    # without history keeps no callers and a handler's update inside one runs.
    fusion = PlanarFusion(t0=0.0)
    fusion.update_odometry(0.1, 1.0, 0.0, **ODO)
    out = interleaved(
        3,
        lambda: fusion.update_odometry(0.2, 1.0, 0.0, **ODO),
        lambda: fusion.update_yaw_rate(0.3, 0.1, variance=RATE_VAR),
    )
    assert not isinstance(out.get("h"), RuntimeError)
    assert fusion._callers == []
