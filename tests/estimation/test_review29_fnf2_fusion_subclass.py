"""User subclasses of ``PlanarFusion`` (review 29, FNF2): what its subclassing Notes claim.

A subclass with slots or an instance ``__dict__`` copies and pickles (every
protocol) as itself, with what it adds and with the steps kept for late
measurements, reprs under its own name, and steps as the base does, bit for
bit, online (late measurements too) and in ``update_batch``. An override of a
public update or of ``predict`` is called by its own callers only: the base's
methods (the replay of a late measurement, the batch) call none of them.
These pass as the code stands (they pin the Notes; no code changed): the
override test fails against a scratch copy whose ``_apply`` calls ``self.predict``.
"""

from __future__ import annotations

import copy
import pickle
from collections.abc import Callable
from typing import Any

import numpy as np
import pytest

from navkit.estimation import MeasurementLog, PlanarFusion


class Counted(PlanarFusion):
    """Slots of its own and every public step overridden, counted."""

    __slots__ = ("calls", "label")

    def __init__(self, **kwargs: Any) -> None:
        super().__init__(**kwargs)
        self.label = "counted"
        self.calls: dict[str, int] = {}

    def _count(self, name: str) -> None:
        self.calls[name] = self.calls.get(name, 0) + 1

    def predict(self, t: float) -> None:
        self._count("predict")
        super().predict(t)

    def update_odometry(self, t: float, v: float, omega: float, **kw: Any) -> Any:
        self._count("update_odometry")
        return super().update_odometry(t, v, omega, **kw)

    def update_speed(self, t: float, v: float, *, variance: float) -> Any:
        self._count("update_speed")
        return super().update_speed(t, v, variance=variance)

    def update_yaw(self, t: float, yaw: float, *, variance: float) -> Any:
        self._count("update_yaw")
        return super().update_yaw(t, yaw, variance=variance)

    def update_yaw_rate(self, t: float, omega: float, *, variance: float) -> Any:
        self._count("update_yaw_rate")
        return super().update_yaw_rate(t, omega, variance=variance)

    def update_acceleration(self, t: float, a: float, *, variance: float) -> Any:
        self._count("update_acceleration")
        return super().update_acceleration(t, a, variance=variance)


class WithDict(Counted):
    """No slots of its own: an instance ``__dict__``."""


COPIES: list[Callable[[Any], Any]] = [
    copy.copy,
    copy.deepcopy,
    *(
        lambda obj, protocol=protocol: pickle.loads(pickle.dumps(obj, protocol=protocol))
        for protocol in range(pickle.HIGHEST_PROTOCOL + 1)
    ),
]


def _feed(fusion: PlanarFusion, start: int, stop: int) -> None:
    """Odometry at 50 Hz, a gyro, a compass and a speed; every fourth yaw rate late."""
    for i in range(start, stop):
        t = 0.02 * (i + 1)
        fusion.update_odometry(t, 1.0, 0.2, v_variance=1e-3, omega_variance=1e-3)
        fusion.update_yaw_rate(t - (0.05 if i % 4 == 3 else 0.0), 0.21, variance=1e-4)
        if i % 5 == 0:
            fusion.update_yaw(t, 0.2 * t, variance=1e-2)
            fusion.update_acceleration(t, 0.01, variance=1e-2)
        if i % 7 == 0:
            fusion.update_speed(t, 1.01, variance=1e-2)
        if i % 9 == 0:
            fusion.predict(t + 0.005)


def _same(a: PlanarFusion, b: PlanarFusion) -> None:
    assert a.t == b.t
    np.testing.assert_array_equal(a.x, b.x)
    np.testing.assert_array_equal(a.P, b.P)


@pytest.mark.parametrize("make_copy", COPIES)
@pytest.mark.parametrize("cls", [Counted, WithDict])
def test_a_subclass_copies_as_itself_and_steps_as_the_base(
    cls: type[Counted], make_copy: Callable[[Any], Any]
) -> None:
    kwargs: dict[str, Any] = {"pose": (1.0, -2.0, 0.3), "t0": 0.0, "history": 0.2}
    mine, base = cls(**kwargs), PlanarFusion(**kwargs)
    if cls is WithDict:
        mine.note = [1]  # type: ignore[attr-defined]
    _feed(mine, 0, 30)
    _feed(base, 0, 30)
    _same(mine, base)
    twin = make_copy(mine)
    assert type(twin) is cls and twin.label == "counted"
    assert twin.calls == mine.calls
    if make_copy is not copy.copy:  # a shallow copy shares the dict, as Python's does
        assert twin.calls is not mine.calls
    if cls is WithDict:
        assert twin.note == [1]  # type: ignore[attr-defined]
    assert repr(twin) == repr(mine) == repr(base).replace("PlanarFusion(", f"{cls.__name__}(", 1)
    _same(twin, base)
    # It goes on as the base does, late measurements into the steps it kept included.
    _feed(twin, 30, 50)
    _feed(base, 30, 50)
    _same(twin, base)
    _feed(mine, 30, 50)
    _same(mine, base)


def test_a_subclass_batch_is_the_base_batch_bit_for_bit() -> None:
    t = 0.02 * np.arange(1, 41)
    log = MeasurementLog.from_streams(
        odometry=(t, np.ones(40), np.full(40, 0.2)),
        odometry_variance=(1e-3, 1e-3),
        yaw_rate=(t, np.full(40, 0.21)),
        yaw_rate_variance=1e-4,
    )
    mine, base = Counted(t0=0.0), PlanarFusion(t0=0.0)
    ours, theirs = mine.update_batch(log), base.update_batch(log)
    np.testing.assert_array_equal(ours.states, theirs.states)
    np.testing.assert_array_equal(ours.covariances, theirs.covariances)
    _same(mine, base)
    assert mine.calls == {}  # the batch calls none of the public steps


def test_an_override_changes_only_its_own_callers() -> None:
    fusion = Counted(t0=0.0, history=0.5)
    fusion.update_odometry(0.1, 1.0, 0.0, v_variance=1e-3, omega_variance=1e-3)
    fusion.update_odometry(0.2, 1.0, 0.0, v_variance=1e-3, omega_variance=1e-3)
    # A late yaw goes back and replays the odometry step after it: not through the
    # public update_odometry (nor predict), which a subclass may have overridden.
    assert fusion.update_yaw(0.15, 0.0, variance=1e-3).accepted
    fusion.update_speed(0.3, 1.0, variance=1e-2)
    fusion.predict(0.4)
    assert fusion.calls == {
        "update_odometry": 2,
        "update_yaw": 1,
        "update_speed": 1,
        "predict": 1,
    }
