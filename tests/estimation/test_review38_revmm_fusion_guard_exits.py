"""PlanarFusion's one-call guard is let go on every way out of a call (review 38, REVMM).

With ``history`` every update, ``predict``, ``reset`` and ``update_batch``
holds the filter (a token in ``_callers``) while it runs, written out inline
in most of them (review 37, GUARD2). A token left behind would refuse every
later call of the filter for good. Reviewed here: each method's fast path,
general path (a NumPy float64 stamp, a stamp equal to the newest step kept),
late measurement (rewind and replay), time gap, and validation error, with a
``KeyboardInterrupt`` at every point where CPython delivers one: the
interrupt (or the validation error) comes out as itself, never as another
exception (a ``ValueError`` from removing a token that was never added), and
the filter is free afterwards.
"""

from __future__ import annotations

import contextlib
from collections.abc import Callable
from typing import Any

import numpy as np
import pytest

from interrupt_points import delivery_points, interrupted_at
from navkit.errors import FilterError
from navkit.estimation import MeasurementLog, PlanarFusion

ODO = {"v_variance": 1e-2, "omega_variance": 1e-2}
LOG = MeasurementLog.from_streams(yaw=([0.9], [0.1]), yaw_variance=1e-3)

CALLS: dict[str, Callable[[PlanarFusion], Any]] = {
    "predict": lambda f: f.predict(0.9),
    "predict, too old": lambda f: f.predict(0.1),
    "predict, time gap": lambda f: f.predict(1e300),
    "reset": lambda f: f.reset(pose=(1.0, 2.0, 0.0), t0=0.9),
    "reset, bad pose": lambda f: f.reset(pose=(1.0, 2.0, 0.0, 3.0), t0=0.9),
    "update_batch": lambda f: f.update_batch(LOG),
    "update_batch, not a log": lambda f: f.update_batch(3),  # type: ignore[arg-type]
    "odometry": lambda f: f.update_odometry(0.6, 1.0, 0.0, **ODO),
    "odometry, float64 stamp": lambda f: f.update_odometry(np.float64(0.6), 1.0, 0.0, **ODO),
    "odometry, late": lambda f: f.update_odometry(0.25, 1.0, 0.0, **ODO),
    "odometry, NaN": lambda f: f.update_odometry(0.6, float("nan"), 0.0, **ODO),
    "speed": lambda f: f.update_speed(0.6, 1.0, variance=1e-2),
    "yaw, late": lambda f: f.update_yaw(0.25, 0.1, variance=1e-3),
    "yaw rate, newest stamp": lambda f: f.update_yaw_rate(0.5, 0.1, variance=1e-3),
    "acceleration, bad variance": lambda f: f.update_acceleration(0.6, 0.1, variance=-1.0),
}


def _base() -> PlanarFusion:
    fusion = PlanarFusion(t0=0.0, history=1.0)
    for i in range(1, 6):
        fusion.update_odometry(0.1 * i, 1.0, 0.1 * i, **ODO)
    return fusion


def _quiet(call: Callable[[PlanarFusion], Any], fusion: PlanarFusion) -> Callable[[], None]:
    def run() -> None:
        with contextlib.suppress(ValueError, TypeError, FilterError):  # bad input, refused
            call(fusion)

    return run


@pytest.mark.parametrize("case", list(CALLS))
def test_the_guard_is_let_go_however_the_call_ends(case: str) -> None:
    call = CALLS[case]
    _quiet(call, _base())()  # the kernels loaded (and compiled) outside the count
    points = delivery_points(_quiet(call, _base()))
    assert points > 5
    for k in range(1, points + 1):
        fusion = _base()
        assert interrupted_at(k, _quiet(call, fusion)), k
        assert fusion._callers == [], f"point {k}"
        # Free: the next call runs.
        assert fusion.update_odometry(2.0, 1.0, 0.0, **ODO).accepted, k
    fusion = _base()
    _quiet(call, fusion)()
    assert fusion._callers == []
