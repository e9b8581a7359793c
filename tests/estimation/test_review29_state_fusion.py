"""PlanarFusion under long random sequences of calls, checked against an in-order replay.

A hypothesis state machine drives one filter (``history`` 0 or a window, with or
without a gate, with or without ``t0``) through random interleavings of the five
``update_*`` kinds, ``predict``, measurements late by up to 1.5 windows, stamps
shared by several kinds, ``reset`` (with and without ``t0``, ``pose`` or ``x0``),
``update_batch`` midway and swaps for a copy or a pickle round trip. The model
keeps the filter as the constructor built it after the last reset (or the filter
after the last batch) and every call taken since: after every call the filter
must equal, bit for bit, that start fed the calls in stamp order (the order at
one stamp of the class notes; predicts first) by a plain ``history=0`` filter,
as the class notes promise. A late measurement is refused exactly when it is
older than the window (ages are whole 10 ms ticks: far from the documented
slack) or than the start; the result of one taken is its own update's as of its
stamp (its NIS that of the replay).
"""

from __future__ import annotations

import copy
import math
from collections.abc import Callable
from typing import Any

import numpy as np
import pytest
from hypothesis import strategies as st
from hypothesis.stateful import RuleBasedStateMachine, initialize, invariant, rule

from navkit.estimation import FusionStatus, MeasurementLog, PlanarFusion, UpdateResult
from stateful_runs import COPIERS, run_machine

TICK = 0.01  # s: every stamp is a whole number of ticks
_COPIERS: tuple[Callable[[PlanarFusion], PlanarFusion], ...] = COPIERS
_KINDS = ("odometry", "speed", "yaw", "yaw_rate", "acceleration")
_VARIANCES = {"odometry": (1e-3, 2e-3), "speed": (1e-3,), "yaw": (1e-3,),
              "yaw_rate": (1e-4,), "acceleration": (1e-2,)}  # fmt: skip
_COLUMNS = {"odometry": (1, 2), "speed": (1,), "yaw": (0,), "yaw_rate": (2,),
            "acceleration": (3,)}  # fmt: skip
# The order of the steps of one stamp (class notes): predict, odometry and speed, yaw,
# yaw rate, acceleration; one kind in the order it came.
_RANK = {"predict": -1, "odometry": 0, "speed": 0, "yaw": 1, "yaw_rate": 2, "acceleration": 3}

# How far a new stamp lies past the newest one, ticks: mostly a few, sometimes beyond
# a window (the steps kept are then trimmed to the newest alone).
_AHEAD = st.one_of(st.integers(0, 4), st.sampled_from([7, 40]))

# A call taken: (stamp in ticks, kind, value 0, value 1, arrival number).
Event = tuple[int, str, float, float, int]


def _feed(fusion: PlanarFusion, t: float, kind: str, a: Any, b: Any) -> UpdateResult | None:
    if kind == "predict":
        fusion.predict(t)
        return None
    if kind == "odometry":
        v_var, w_var = _VARIANCES[kind]
        return fusion.update_odometry(t, a, b, v_variance=v_var, omega_variance=w_var)
    method: Callable[..., UpdateResult] = getattr(fusion, f"update_{kind}")
    return method(t, a, variance=_VARIANCES[kind][0])


def _same(got: PlanarFusion, want: PlanarFusion) -> None:
    assert got.t == want.t
    assert got.x.tobytes() == want.x.tobytes(), (got.x, want.x)
    assert got.P.tobytes() == want.P.tobytes(), (got.P, want.P)


def _log(events: list[tuple[int, str, float, float]], epoch: float) -> MeasurementLog:
    n = len(events)
    values = np.zeros((n, 4))
    variances = np.ones((n, 4))
    observed = np.zeros((n, 4), dtype=bool)
    for i, (_, kind, a, b) in enumerate(events):
        for col, value, var in zip(_COLUMNS[kind], (a, b), _VARIANCES[kind], strict=False):
            values[i, col] = value
            variances[i, col] = var
            observed[i, col] = True
    return MeasurementLog(
        np.array([epoch + e[0] * TICK for e in events]), values, variances, observed
    )


def _machine(windows: tuple[int, ...], epoch: float) -> type[RuleBasedStateMachine]:
    """A machine keeping ``history`` of one of ``windows`` ticks; stamps from ``epoch`` s."""

    def T(stamp: int) -> float:
        return epoch + stamp * TICK

    value = st.floats(-4.0, 4.0, allow_nan=False)

    class FusionMachine(RuleBasedStateMachine):
        fusion: PlanarFusion
        options: dict[str, Any]
        window: int
        # The filter the calls since the last reset or batch start from (history=0).
        start_filter: PlanarFusion
        # Stamps (ticks) older than this are refused; None: the clock was unset at start.
        floor: int | None
        events: list[Event]
        arrivals: int

        @initialize(
            window=st.sampled_from(windows),
            gated=st.booleans(),
            t0=st.none() | st.integers(0, 20),
        )
        def start(self, window: int, gated: bool, t0: int | None) -> None:
            self.window = window
            self.options = {"gate_probability": 0.95 if gated else None}
            self.fusion = PlanarFusion(
                t0=None if t0 is None else T(t0), history=window * TICK, **self.options
            )
            self.start_filter = PlanarFusion(t0=None if t0 is None else T(t0), **self.options)
            self.floor = t0
            self.events = []
            self.arrivals = 0

        def _now(self) -> int | None:
            """The newest stamp taken (ticks), the filter's time."""
            stamps = [e[0] for e in self.events]
            if stamps:
                return max(stamps)
            return self.floor

        def _replay(self, upto: int | None = None) -> tuple[PlanarFusion, Any]:
            """The start fed the calls in stamp order; and the result of arrival ``upto``."""
            model = copy.deepcopy(self.start_filter)
            found: Any = None
            # Without history the calls are taken as they came (a late one is refused).
            order = sorted(
                self.events,
                key=lambda e: (e[0], _RANK[e[1]] if self.window else 0, e[4]),
            )
            for t, kind, a, b, n in order:
                result = _feed(model, T(t), kind, a, b)
                if n == upto:
                    found = result
            return model, found

        @rule(
            kind=st.sampled_from(_KINDS),
            ahead=_AHEAD,
            a=value,
            b=value,
            numpy=st.booleans(),
        )
        def measure(self, kind: str, ahead: int, a: float, b: float, numpy: bool) -> None:
            now = self._now()
            self._take(kind, ahead if now is None else now + ahead, a, b, numpy)

        @rule(
            kind=st.sampled_from(_KINDS),
            late=st.integers(0, 3 * max(windows) // 2),
            a=value,
            b=value,
            numpy=st.booleans(),
        )
        def measure_late(self, kind: str, late: int, a: float, b: float, numpy: bool) -> None:
            now = self._now()
            self._take(kind, 30 - late if now is None else now - late, a, b, numpy)

        def _take(self, kind: str, stamp: int, a: float, b: float, numpy: bool) -> None:
            now = self._now()
            before = (self.fusion.t, self.fusion.x.tobytes(), self.fusion.P.tobytes())
            # NumPy scalars take the general (validating) way, plain floats the fast one.
            conv: Callable[[float], Any] = np.float64 if numpy else float
            result = _feed(self.fusion, conv(T(stamp)), kind, conv(a), conv(b))
            assert result is not None
            late = now is not None and stamp < now
            refused = (
                late
                and now is not None
                and (now - stamp > self.window or (self.floor is not None and stamp < self.floor))
            )
            if refused:
                assert result.status == FusionStatus.OUT_OF_ORDER, (stamp, now, result)
                after = (self.fusion.t, self.fusion.x.tobytes(), self.fusion.P.tobytes())
                assert after == before
                return
            assert result.status != FusionStatus.OUT_OF_ORDER, (stamp, now, result.reason)
            self.arrivals += 1
            self.events.append((stamp, kind, a, b, self.arrivals))
            _, own = self._replay(self.arrivals)
            assert own is not None
            assert result.status == own.status
            assert result.nis == own.nis or (math.isnan(result.nis) and math.isnan(own.nis))
            np.testing.assert_array_equal(result.residual, own.residual)

        @rule(ahead=_AHEAD)
        def predict(self, ahead: int) -> None:
            now = self._now()
            stamp = ahead if now is None else now + ahead
            self.fusion.predict(T(stamp))
            if now is None:
                # Before the first measurement it only sets the clock.
                self.floor = stamp
                self.start_filter.predict(T(stamp))
                return
            # A predict to a stamp already taken changes nothing (class notes).
            if not any(e[0] == stamp for e in self.events):
                self.arrivals += 1
                self.events.append((stamp, "predict", 0.0, 0.0, self.arrivals))

        @rule(late=st.integers(1, 5))
        def predict_refused(self, late: int) -> None:
            now = self._now()
            if now is None:
                return
            before = (self.fusion.t, self.fusion.x.tobytes(), self.fusion.P.tobytes())
            with pytest.raises(ValueError, match="older than the filter time"):
                self.fusion.predict(T(now - late))
            assert (self.fusion.t, self.fusion.x.tobytes(), self.fusion.P.tobytes()) == before

        @rule(
            how=st.sampled_from(["none", "pose", "x0"]),
            t0=st.none() | st.integers(-5, 5),
            data=st.data(),
        )
        def reset(self, how: str, t0: int | None, data: st.DataObject) -> None:
            now = self._now()
            args: dict[str, Any] = {}
            if how == "pose":
                args["pose"] = data.draw(st.tuples(value, value, value))
            elif how == "x0":
                args["x0"] = data.draw(st.lists(value, min_size=6, max_size=6))
                args["P0"] = data.draw(st.sampled_from([None, [1e-3, 1e-3, 1e-2, 0.5, 0.5, 0.5]]))
            stamp = None if t0 is None else (0 if now is None else now) + t0
            self.fusion.reset(t0=None if stamp is None else T(stamp), **args)
            # The constructor's filter from these arguments (reset's promise).
            self.start_filter = PlanarFusion(
                t0=None if stamp is None else T(stamp), **self.options, **args
            )
            self.floor = stamp
            self.events = []

        @rule(
            rows=st.lists(
                st.tuples(st.integers(-3, 6), st.sampled_from(_KINDS), value, value), max_size=5
            )
        )
        def batch(self, rows: list[tuple[int, str, float, float]]) -> None:
            now = self._now()
            base = 0 if now is None else now
            log = _log([(base + dt, kind, a, b) for dt, kind, a, b in rows], epoch)
            model, _ = self._replay()
            got = self.fusion.update_batch(log)
            want = model.update_batch(log)
            for name in ("states", "covariances", "status", "nis"):
                assert getattr(got, name).tobytes() == getattr(want, name).tobytes(), name
            _same(self.fusion, model)
            if not rows:
                return  # nothing fused, nothing dropped: the history is kept
            self.start_filter = model
            self.events = []
            # The rows are not kept: older than the filter's time is refused.
            self.floor = None if model.t is None else round((model.t - epoch) / TICK)

        @rule(how=st.integers(0, len(_COPIERS) - 1), kind=st.sampled_from(_KINDS))
        def swap_for_copy(self, how: int, kind: str) -> None:
            old, self.fusion = self.fusion, _COPIERS[how](self.fusion)
            assert self.fusion.history == old.history
            # The original going on must not reach the copy (checked by the invariant).
            now = self._now()
            _feed(old, T(0 if now is None else now + 1), kind, 0.5, 0.25)
            old.reset(pose=(1.0, 2.0, 3.0))

        @invariant()
        def equals_the_in_order_replay(self) -> None:
            model, _ = self._replay()
            _same(self.fusion, model)

    return FusionMachine


# Windows in ticks: 0 (stamp order only), 5 and 30 (a late measurement rewinds a few
# steps or many).
# From 0 s and from an epoch stamp (2026), where float64 stamps lie 2.4e-7 s apart and
# a window's age is taken within the documented slack.
_MACHINES = [_machine((0, 5, 30), 0.0), _machine((0, 5, 30), 1.78e9)]


@pytest.mark.parametrize("machine", _MACHINES, ids=["from 0 s", "epoch"])
def test_random_call_sequences_equal_the_in_order_replay(
    machine: type[RuleBasedStateMachine],
) -> None:
    run_machine(machine, examples=60, steps=25)


@pytest.mark.slow
@pytest.mark.parametrize("machine", _MACHINES, ids=["from 0 s", "epoch"])
def test_random_call_sequences_equal_the_in_order_replay_long(
    machine: type[RuleBasedStateMachine],
) -> None:
    run_machine(machine, examples=300, steps=50)
