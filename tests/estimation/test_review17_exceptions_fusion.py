"""PlanarFusion after an exception raised as its compiled step returns (exception safety).

A step whose prediction overflows (a corrupt time stamp: ``TIME_GAP``) is left
by the kernel with the overflowed prediction in place, for the Python layer to
undo before it raises ``FilterError``. Python delivers a ``KeyboardInterrupt``
as a call returns: one delivered as that step returned skipped the undo, and
the filter kept an infinite covariance and the absurd time for good, against
the promise that its state and covariance are never NaN or infinite. Now the
undo runs on the way out; a step that completed (applied, gated or kept as a
prediction) stays as it completed.

The interrupts are injected where a user could not: the module's name of the
step is wrapped to raise once the real step returned.
"""

from __future__ import annotations

import copy
from collections.abc import Callable
from typing import Any

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from navkit.errors import FilterError
from navkit.estimation import PlanarFusion, _fusion

_CALLS: dict[str, Callable[[PlanarFusion, Any, float], Any]] = {
    "predict": lambda f, t, z: f.predict(t),
    "update_odometry": lambda f, t, z: f.update_odometry(
        t, z, 0.1, v_variance=0.01, omega_variance=0.01
    ),
    "update_speed": lambda f, t, z: f.update_speed(t, z, variance=0.01),
    "update_yaw": lambda f, t, z: f.update_yaw(t, z, variance=0.01),
    "update_yaw_rate": lambda f, t, z: f.update_yaw_rate(t, z, variance=0.01),
    "update_acceleration": lambda f, t, z: f.update_acceleration(t, z, variance=0.01),
}


def _fusion_at_rest() -> PlanarFusion:
    fusion = PlanarFusion([0.0, 0.0, 0.0, 1.0, 0.5, 0.0], t0=0.0)
    fusion.update_odometry(0.1, 1.0, 0.1, v_variance=0.01, omega_variance=0.01)
    return fusion


def _estimate(fusion: PlanarFusion) -> tuple[Any, ...]:
    return fusion.t, fusion.x.tolist(), fusion.P.tolist()


def _interrupted(call: Callable[[], Any]) -> None:
    """Run ``call`` with the step raising ``KeyboardInterrupt`` once it returned."""
    real = getattr(_fusion, "_step")  # noqa: B009 - not re-exported

    def step_then_interrupt(*args: Any) -> Any:
        real(*args)
        raise KeyboardInterrupt

    # Not the monkeypatch fixture: hypothesis runs many examples per test call.
    setattr(_fusion, "_step", step_then_interrupt)  # noqa: B010
    try:
        with pytest.raises(KeyboardInterrupt):
            call()
    finally:
        setattr(_fusion, "_step", real)  # noqa: B010


@pytest.mark.parametrize("method", sorted(_CALLS))
@pytest.mark.parametrize("t", [1e300, 1e200])
def test_an_interrupted_step_over_a_huge_time_gap_leaves_the_filter_unchanged(
    method: str, t: float
) -> None:
    fusion = _fusion_at_rest()
    before = _estimate(fusion)
    with pytest.raises(FilterError, match="time gap"):  # what the step does uninterrupted
        _CALLS[method](copy.deepcopy(fusion), t, 1.0)
    _interrupted(lambda: _CALLS[method](fusion, t, 1.0))
    assert _estimate(fusion) == before
    assert np.isfinite(fusion.P).all()
    # The filter goes on as an untouched one.
    twin = _fusion_at_rest()
    for f in (fusion, twin):
        f.update_odometry(0.3, 1.0, 0.1, v_variance=0.01, omega_variance=0.01)
    assert _estimate(fusion) == _estimate(twin)


@settings(max_examples=40, deadline=None, database=None)
@given(
    method=st.sampled_from(sorted(_CALLS)),
    dt=st.sampled_from([0.0, 0.05, 1.0, 1e150, 1e300]),
    z=st.floats(-1e6, 1e6),
    slow_path=st.booleans(),
)
def test_an_interrupted_step_is_undone_or_kept_as_it_completed(
    method: str, dt: float, z: float, slow_path: bool
) -> None:
    fusion = _fusion_at_rest()
    t: Any = 0.1 + dt
    if slow_path and t < 2**52:
        t = int(t) if t == int(t) else np.float64(t)  # not a plain float: the checked way
    before = _estimate(fusion)
    completed = copy.deepcopy(fusion)
    try:
        _CALLS[method](completed, t, z)
        failed = False
    except FilterError:
        failed = True
    _interrupted(lambda: _CALLS[method](fusion, t, z))
    after = _estimate(fusion)
    assert after == (before if failed else _estimate(completed))
    assert np.isfinite(fusion.x).all() and np.isfinite(fusion.P).all()
