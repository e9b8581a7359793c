"""ExtendedKalmanFilter after an exception raised part-way through a step (exception safety).

The model functions raising, returning wrong shapes or NaN leave the filter as
it was (the ``predict`` / ``update`` Raises sections; checked here once more
with the state and a continuation compared to an untouched twin). The defect
found in session 21: ``update`` stores the options it was given
(``angle_measurements``, ``gate``) in a buffer keyed by the objects passed, and
wrote the buffer before the keys. Python delivers a ``KeyboardInterrupt`` as a
call returns, so one delivered as the buffer's writer returned left the new
options under the old keys: the next update passing the old objects ran with
the other options (no angle wrapping, no gate: a residual 2π off, a step the
gate should have refused), silently. The interrupt is injected where a user
could not: the module's name of that writer is wrapped to raise once it
returned.
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
from navkit.estimation import ExtendedKalmanFilter, _ekf

H = np.array([[1.0, 0.0]])
R = np.array([[0.01]])
F = np.array([[1.0, 0.1], [0.0, 1.0]])
Q = 0.01 * np.eye(2)
ANGLES = (0,)


def _h(x: np.ndarray[Any, Any]) -> np.ndarray[Any, Any]:
    return x[:1].copy()


def _f(x: np.ndarray[Any, Any]) -> np.ndarray[Any, Any]:
    out: np.ndarray[Any, Any] = F @ x
    return out


def _filter() -> ExtendedKalmanFilter:
    """A filter near +π that has used both option sets."""
    ekf = ExtendedKalmanFilter([3.0, 0.0], np.eye(2), angle_states=[0])
    ekf.update(np.array([3.1]), _h, H, R)
    ekf.update(np.array([3.1]), _h, H, R, angle_measurements=ANGLES, gate=9.0)
    return ekf


def _same(a: ExtendedKalmanFilter, b: ExtendedKalmanFilter) -> None:
    np.testing.assert_array_equal(a.x, b.x)
    np.testing.assert_array_equal(a.P, b.P)


class _InterruptAfter:
    """A stand-in for ``set_options`` raising ``KeyboardInterrupt`` once it returned."""

    def __init__(self, real: Callable[..., Any]) -> None:
        self.real = real
        self.calls = 0

    def __call__(self, *args: Any) -> Any:
        out = self.real(*args)
        self.calls += 1
        if self.calls == 1:
            raise KeyboardInterrupt
        return out


def test_an_interrupt_as_the_options_are_written_keeps_them_apart(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    ekf, twin = _filter(), _filter()
    stub = _InterruptAfter(getattr(_ekf, "set_options"))  # noqa: B009 - not re-exported
    monkeypatch.setattr(_ekf, "set_options", stub)
    with pytest.raises(KeyboardInterrupt):
        ekf.update(np.array([3.1]), _h, H, R)  # back to the defaults: the buffer changes
    monkeypatch.undo()
    assert stub.calls == 1
    _same(ekf, twin)  # the interrupted update applied nothing
    # -3.1 rad is 0.08 rad from 3.1 across ±π: wrapped, as the twin wraps it (before
    # the fix the residual was -6.2 rad and the state jumped to 1.04 rad).
    got = ekf.update(np.array([-3.1]), _h, H, R, angle_measurements=ANGLES, gate=9.0)
    want = twin.update(np.array([-3.1]), _h, H, R, angle_measurements=ANGLES, gate=9.0)
    np.testing.assert_array_equal(got.residual, want.residual)
    assert abs(float(got.residual[0])) < 0.1
    _same(ekf, twin)
    # And the gate still refuses what it refuses in the twin.
    got = ekf.update(np.array([0.0]), _h, H, R, angle_measurements=ANGLES, gate=9.0)
    want = twin.update(np.array([0.0]), _h, H, R, angle_measurements=ANGLES, gate=9.0)
    assert got.accepted == want.accepted is False
    _same(ekf, twin)


class _Boom(Exception):
    pass


def _raise(*args: Any) -> Any:
    raise _Boom


def _interrupt(*args: Any) -> Any:
    raise KeyboardInterrupt


_FAULTS: dict[str, Callable[[ExtendedKalmanFilter], Any]] = {
    "f raises": lambda e: e.predict(_raise, F, Q),
    "F raises": lambda e: e.predict(_f, _raise, Q),
    "f interrupted": lambda e: e.predict(_interrupt, F, Q),
    "f modifies x, then raises": lambda e: e.predict(
        lambda x: (x.__setitem__(0, 99.0), _raise())[1], F, Q
    ),
    "f NaN": lambda e: e.predict(lambda x: np.array([np.nan, 0.0]), F, Q),
    "f wrong shape": lambda e: e.predict(lambda x: np.zeros(3), F, Q),
    "Q not symmetric": lambda e: e.predict(_f, F, np.array([[1.0, 0.5], [0.0, 1.0]])),
    "h raises": lambda e: e.update(np.array([0.1]), _raise, H, R),
    "H interrupted": lambda e: e.update(np.array([0.1]), _h, _interrupt, R),
    "h NaN": lambda e: e.update(np.array([0.1]), lambda x: np.array([np.nan]), H, R),
    "h wrong shape": lambda e: e.update(np.array([0.1]), lambda x: x, H, R),
    "R not positive": lambda e: e.update(np.array([0.1]), _h, H, -R),
    "gate not positive": lambda e: e.update(np.array([0.1]), _h, H, R, gate=-1.0),
    "angle index out of range": lambda e: e.update(
        np.array([0.1]), _h, H, R, angle_measurements=[3]
    ),
    "H overflows S": lambda e: e.update(np.array([0.1]), _h, np.array([[1e200, 0.0]]), R),
}


@settings(max_examples=40, deadline=None, database=None)
@given(
    fault=st.sampled_from(sorted(_FAULTS)),
    zs=st.lists(st.floats(-3.0, 3.0), min_size=1, max_size=4),
    angles=st.booleans(),
)
def test_a_failed_step_leaves_the_filter_as_an_untouched_twin(
    fault: str, zs: list[float], angles: bool
) -> None:
    ekf = _filter()
    twin = copy.deepcopy(ekf)
    expected = (_Boom, KeyboardInterrupt, ValueError, TypeError, FilterError, RuntimeError)
    with pytest.raises(expected) as info:
        _FAULTS[fault](ekf)
    assert not isinstance(info.value, RuntimeError)  # not a nested-call refusal
    _same(ekf, twin)
    options: dict[str, Any] = {"angle_measurements": ANGLES, "gate": 9.0} if angles else {}
    for z in zs:
        for e in (ekf, twin):
            e.predict(_f, F, Q)
        got = ekf.update(np.array([z]), _h, H, R, **options)
        want = twin.update(np.array([z]), _h, H, R, **options)
        assert got.accepted == want.accepted
        np.testing.assert_array_equal(got.residual, want.residual)
        _same(ekf, twin)
