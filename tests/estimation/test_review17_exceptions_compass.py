"""CompassCalibration after an exception raised part-way through a call (exception safety).

Python delivers a ``KeyboardInterrupt`` at a call. With ``unwrap=True`` a call
updates two attributes, the multiple of 2π added so far and the last yaw; a
``float()`` call stood between the two stores, so an interrupt there kept the
new correction with the old last yaw, and the next readings were unwrapped from
the wrong one: 2π off for good. Now the interrupted call changes nothing, or
(when it had latched the first reading) only that.

The interrupts are injected where a user could not: ``float`` is shadowed in
the module to raise at its ``k``-th call.
"""

from __future__ import annotations

import builtins
import contextlib
import copy
import math
from typing import Any

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from navkit.estimation import CompassCalibration, _compass


def _state(cal: CompassCalibration) -> tuple[Any, ...]:
    return cal.initial_deg, cal._last, cal._correction


class _FloatInterrupted:
    """``float`` raising ``KeyboardInterrupt`` at its ``n``-th call (then plain again)."""

    def __init__(self, n: int) -> None:
        self.n = n
        self.calls = 0

    def __call__(self, value: Any = 0.0) -> float:
        self.calls += 1
        if self.calls == self.n:
            raise KeyboardInterrupt
        return builtins.float(value)


def test_an_interrupt_between_the_two_stores_keeps_the_unwrapping_right(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    cal = CompassCalibration(unwrap=True)
    cal([0.0, 120.0, 170.0])
    twin = copy.deepcopy(cal)
    before = _state(cal)
    # Across north: the correction changes by 2π. The call's second float() was the
    # one between the two stores.
    stub = _FloatInterrupted(2)
    monkeypatch.setattr(_compass, "float", stub, raising=False)
    with pytest.raises(KeyboardInterrupt):
        cal([190.0, 230.0])
    monkeypatch.undo()
    assert stub.calls == 2
    assert _state(cal) == before
    # Continues as the twin that never saw the interrupted call: no 2π jump.
    np.testing.assert_array_equal(cal([250.0, 300.0]), twin([250.0, 300.0]))


@settings(max_examples=40, deadline=None, database=None)
@given(
    first=st.lists(st.floats(0.0, 359.0), min_size=1, max_size=4),
    second=st.lists(st.floats(0.0, 359.0), min_size=1, max_size=4),
    after=st.lists(st.floats(0.0, 359.0), min_size=1, max_size=4),
    call=st.integers(1, 4),
)
def test_an_interrupted_call_leaves_the_state_before_it_or_after_it(
    first: list[float], second: list[float], after: list[float], call: int
) -> None:
    cal = CompassCalibration(unwrap=True)
    cal(first)
    untouched = copy.deepcopy(cal)
    completed = copy.deepcopy(cal)
    completed(second)
    stub = _FloatInterrupted(call)
    # Not the monkeypatch fixture: hypothesis runs many examples per test call.
    _compass.float = stub  # type: ignore[attr-defined]
    try:
        with contextlib.suppress(KeyboardInterrupt):
            cal(second)
    finally:
        del _compass.float  # type: ignore[attr-defined]
    assert _state(cal) in (_state(untouched), _state(completed))
    twin = untouched if _state(cal) == _state(untouched) else completed
    got, want = cal(after), twin(after)
    assert all(math.isfinite(v) for v in got)
    np.testing.assert_array_equal(got, want)
