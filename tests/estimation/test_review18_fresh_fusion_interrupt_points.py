"""PlanarFusion interrupted at every point CPython delivers a KeyboardInterrupt.

Session 21 made a step whose ``KeyboardInterrupt`` arrives as the compiled
online step returns undo an overflowed prediction (``_settle``). CPython also
delivers one on entering any Python function, and after any C call returns. A
step over an overflowing time gap is undone by two such calls after the
step's try: ``_not_applied`` (the updates) and ``undo_step`` (all). Interrupted
on entering either, the filter kept the overflowed prediction: the time
1e300 and a NaN covariance, every later update refused or NaN (found in
session 22). Also ``undo_step`` restored ``x`` and ``P`` before the time:
interrupted between, the estimate was the old one at the new time (1e300),
every later measurement out of order. Now the undo runs under the step's try
and restores the time first, so ``_settle`` finds a part-done undo by the
non-finite ``x``/``P`` and completes it.

The interrupts are injected through ``sys.setprofile`` at every ``call``
(a Python function entered) and ``c_return`` (a C function returned) event of
the update, in turn.
"""

from __future__ import annotations

import contextlib
import copy
from collections.abc import Callable
from typing import Any

import numpy as np
import pytest

from interrupt_points import interrupted_at
from navkit.errors import FilterError
from navkit.estimation import PlanarFusion, _fusion

_CALLS: dict[str, Callable[[PlanarFusion, Any], Any]] = {
    "predict": lambda f, t: f.predict(t),
    "update_odometry": lambda f, t: f.update_odometry(
        t, 1.0, 0.1, v_variance=0.01, omega_variance=0.01
    ),
    "update_speed": lambda f, t: f.update_speed(t, 1.0, variance=0.01),
    "update_yaw": lambda f, t: f.update_yaw(t, 0.3, variance=0.01),
    "update_acceleration": lambda f, t: f.update_acceleration(t, 0.1, variance=0.01),
}


def _fusion_in_motion() -> PlanarFusion:
    fusion = PlanarFusion([0.0, 0.0, 0.0, 1.0, 0.5, 0.0], t0=0.0)
    fusion.update_odometry(0.1, 1.0, 0.1, v_variance=0.01, omega_variance=0.01)
    return fusion


def _estimate(fusion: PlanarFusion) -> tuple[Any, ...]:
    return fusion.t, fusion.x.tobytes(), fusion.P.tobytes()


def _go_on(fusion: PlanarFusion) -> tuple[Any, ...]:
    fusion.update_odometry(0.3, 1.0, 0.1, v_variance=0.01, omega_variance=0.01)
    fusion.update_yaw(0.4, 0.2, variance=0.01)
    return _estimate(fusion)


def _interrupted_at(k: int, call: Callable[[], object]) -> bool:
    """``call`` with a KeyboardInterrupt at its ``k``-th delivery point; True if raised."""

    def quiet() -> None:
        with contextlib.suppress(FilterError):
            call()

    return interrupted_at(k, quiet)


@pytest.mark.parametrize("method", sorted(_CALLS))
@pytest.mark.parametrize("t", [1e300, np.float64(1e300), 0.2, np.float64(0.2)])
def test_interrupted_anywhere_the_filter_is_as_before_or_after(method: str, t: Any) -> None:
    call = _CALLS[method]
    before = _fusion_in_motion()
    after = copy.deepcopy(before)
    with contextlib.suppress(FilterError):
        call(after, t)
    wanted = {_estimate(before): _go_on(copy.deepcopy(before)),
              _estimate(after): _go_on(copy.deepcopy(after))}  # fmt: skip
    k = 1
    while True:
        fusion = _fusion_in_motion()
        if not _interrupted_at(k, lambda fusion=fusion: call(fusion, t)):
            break
        state = _estimate(fusion)
        assert state in wanted, f"interrupted at point {k}: t={fusion.t}"
        assert np.isfinite(fusion.P).all()
        assert _go_on(fusion) == wanted[state]
        k += 1
    assert k > 5  # the points were there to try


@pytest.mark.parametrize("method", sorted(_CALLS))
def test_interrupted_on_entering_the_undo_the_filter_is_unchanged(
    method: str, monkeypatch: pytest.MonkeyPatch
) -> None:
    real = _fusion.undo_step
    entered = []

    def undo_interrupted_on_entry(buf: Any) -> None:
        entered.append(1)
        if len(entered) == 1:
            raise KeyboardInterrupt
        real(buf)

    fusion = _fusion_in_motion()
    before = _estimate(fusion)
    monkeypatch.setattr(_fusion, "undo_step", undo_interrupted_on_entry)
    with pytest.raises(KeyboardInterrupt):
        _CALLS[method](fusion, 1e300)
    monkeypatch.undo()
    assert len(entered) == 2  # the undo interrupted, then the one of _settle
    assert _estimate(fusion) == before
    assert _go_on(fusion) == _go_on(_fusion_in_motion())


@pytest.mark.parametrize("method", sorted(set(_CALLS) - {"predict"}))
@pytest.mark.parametrize("interrupted_undo", [1, 0])
def test_an_update_to_be_undone_is_undone_however_it_is_interrupted(
    method: str, interrupted_undo: int, monkeypatch: pytest.MonkeyPatch
) -> None:
    # NOT_POSITIVE_DEFINITE is all but unreachable with valid inputs: the step is made
    # to report it after a normal update, which undo_step takes back all the same.
    real_step, real_undo = _fusion._step, _fusion.undo_step
    undos = []

    def not_positive_definite(*args: Any) -> tuple[int, float]:
        real_step(*args)
        return int(_fusion.NOT_POSITIVE_DEFINITE), 1.0

    def undo(buf: Any) -> None:
        undos.append(1)
        if len(undos) == interrupted_undo:
            raise KeyboardInterrupt
        real_undo(buf)

    fusion = _fusion_in_motion()
    before = _estimate(fusion)
    monkeypatch.setattr(_fusion, "_step", not_positive_definite)
    monkeypatch.setattr(_fusion, "undo_step", undo)
    with pytest.raises(KeyboardInterrupt if interrupted_undo else FilterError):
        _CALLS[method](fusion, 0.2)
    monkeypatch.undo()
    assert _estimate(fusion) == before  # not the prediction to t=0.2
    assert _go_on(fusion) == _go_on(_fusion_in_motion())
