"""``PlanarFusion`` subclasses that override its properties (review 30, FNF).

The filter's own methods read its state directly, never through a property:
a subclass that overrides ``t``, ``x``, ``P``, ``pose`` or ``history`` steps
as the base does, bit for bit, on every path (the compiled fast path, the
general path given other than plain floats, ``predict``, the first
measurement that sets the clock, late measurements, ``update_batch``), and
its ``repr`` shows the filter's own time and state. Before the fix,
``predict`` and the general path read ``self.t`` (an override of ``t``
changed the arithmetic) and ``repr`` read ``self.t`` and ``self.x``.
"""

from __future__ import annotations

from typing import Any

import numpy as np
import pytest

from navkit.estimation import MeasurementLog, PlanarFusion
from navkit.geometry import Pose2D


class LateClock(PlanarFusion):
    """Reports a time 0.5 s behind the filter's (e.g. a display offset)."""

    @property
    def t(self) -> float | None:
        t = super().t
        return None if t is None else t - 0.5


class NoClock(PlanarFusion):
    """Reports no time at all."""

    @property
    def t(self) -> float | None:
        return None


class ShiftedState(PlanarFusion):
    """Reports the state in another frame."""

    @property
    def x(self) -> Any:
        return super().x + 100.0

    @property
    def P(self) -> Any:
        return super().P * 4.0

    @property
    def pose(self) -> Pose2D:
        return Pose2D(0.0, 0.0, 0.0)

    @property
    def history(self) -> float:
        return 0.0


OVERRIDES = [LateClock, NoClock, ShiftedState]


def _own(fusion: PlanarFusion) -> tuple[Any, Any, Any]:
    """The filter's time, state and covariance as the base class reads them."""
    return (
        PlanarFusion.t.__get__(fusion),
        PlanarFusion.x.__get__(fusion),
        PlanarFusion.P.__get__(fusion),
    )


def _same(a: PlanarFusion, b: PlanarFusion) -> None:
    ta, xa, pa = _own(a)
    tb, xb, pb = _own(b)
    assert ta == tb
    np.testing.assert_array_equal(xa, xb)
    np.testing.assert_array_equal(pa, pb)


def _feed(fusion: PlanarFusion) -> list[Any]:
    """Every path: plain floats, numpy and int inputs, predict, late and refused stamps."""
    out: list[Any] = []
    # No t0: the first measurement, given as numpy floats, sets the clock.
    out.append(fusion.update_yaw(np.float64(0.01), np.float64(0.0), variance=1e-2))
    for i in range(1, 40):
        t = 0.02 * i
        out.append(fusion.update_odometry(t, 1.0, 0.2, v_variance=1e-3, omega_variance=1e-3))
        if i % 3 == 0:  # the general path: numpy scalars and ints
            out.append(fusion.update_yaw_rate(np.float64(t), 0, variance=np.float64(1e-4)))
        if i % 4 == 0:  # late, within the history window
            out.append(fusion.update_yaw_rate(t - 0.03, 0.21, variance=1e-4))
            out.append(fusion.update_speed(np.float64(t - 0.01), 1, variance=1e-2))
        if i % 5 == 0:
            fusion.predict(t + 0.005)
            fusion.predict(np.float64(t + 0.01))
        if i % 7 == 0:  # older than the window: refused
            out.append(fusion.update_acceleration(np.float64(t - 1.0), 0.0, variance=1e-2))
    with pytest.raises(ValueError, match="older than the filter time"):
        fusion.predict(0.0)
    return [(r.accepted, r.nis, r.residual.tolist(), r.reason) for r in out]


@pytest.mark.parametrize("cls", OVERRIDES)
def test_an_overridden_property_changes_no_arithmetic(cls: type[PlanarFusion]) -> None:
    mine, base = cls(history=0.1), PlanarFusion(history=0.1)
    assert _feed(mine) == _feed(base)
    _same(mine, base)
    log = MeasurementLog.from_streams(
        odometry=(0.8 + 0.02 * np.arange(1, 11), np.ones(10), np.zeros(10)),
        yaw=([0.85, 0.9], [0.1, 0.1]),
    )
    a, b = mine.update_batch(log), base.update_batch(log)
    np.testing.assert_array_equal(a.states, b.states)
    np.testing.assert_array_equal(a.status, b.status)
    _same(mine, base)


@pytest.mark.parametrize("cls", OVERRIDES)
def test_an_overridden_property_changes_only_its_callers(cls: type[PlanarFusion]) -> None:
    mine = cls(pose=(1.0, 2.0, 0.5), t0=3.0, history=0.2)
    base = PlanarFusion(pose=(1.0, 2.0, 0.5), t0=3.0, history=0.2)
    # The repr shows the filter's own time and state, under the subclass's name.
    assert repr(mine) == repr(base).replace("PlanarFusion(", f"{cls.__name__}(", 1)
    if cls is LateClock:
        assert mine.t == 2.5
    elif cls is NoClock:
        assert mine.t is None
    else:
        assert mine.x[0] == 101.0 and mine.history == 0.0
