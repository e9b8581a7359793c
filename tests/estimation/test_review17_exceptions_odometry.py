"""DiffOdometry and OmniOdometry after an exception raised part-way (exception safety).

Python delivers a ``KeyboardInterrupt`` at a call. A step's new travel (the
motion summed apart from the start) was stored inside the step, before the
caller stored the pose and the counters it goes with: an interrupt between
made ``DiffOdometry`` count the step twice (the next pose 0.446 m instead of
0.320 m) and left ``OmniOdometry``'s pose stale. ``update_batch`` and
``reset`` also stored the pose first, with calls between it and the rest. Now
each call stores its results together, after its last call: interrupted, the
odometry is as before the call or as after it.

Interrupts are injected at the k-th call or C call the update makes, through
``sys.setprofile`` (an exception raised by the profile function propagates from
that point), for every k until the call completes.
"""

from __future__ import annotations

import copy
import sys
from collections.abc import Callable
from typing import Any

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from interrupt_points import interrupted_at
from navkit.estimation import DiffOdometry, OmniOdometry
from navkit.kinematics import DiffDrive, OmniDrive


def _state(odo: Any) -> tuple[Any, ...]:
    return (odo.pose, odo._travel, odo._anchor, getattr(odo, "_last", None))


def _interrupted_at(k: int, call: Callable[[], object]) -> bool:
    """``call`` with a KeyboardInterrupt at its ``k``-th call event; True if raised."""
    return interrupted_at(k, call, events=("call", "c_call"))


def _check_every_point(
    make: Callable[[], Any], prepare: Callable[[Any], None], act: Callable[[Any], object],
    then: Callable[[Any], object],
) -> int:
    """Interrupt ``act`` at each call in turn; return how many points were tried."""
    k = 1
    while True:
        odo = make()
        prepare(odo)
        before = copy.deepcopy(odo)
        after = copy.deepcopy(odo)
        act(after)
        if not _interrupted_at(k, lambda odo=odo: act(odo)):
            assert _state(odo) == _state(after)
            return k
        state = _state(odo)
        assert state in (_state(before), _state(after)), f"interrupted at call {k}: {state}"
        # And it goes on as the twin in the same state does.
        twin = before if state == _state(before) else after
        assert then(odo) == then(twin)
        k += 1


def _diff() -> DiffOdometry:
    return DiffOdometry(DiffDrive(track=0.5, wheel_radius=0.1), ticks_per_rev=1000)


def _omni() -> OmniOdometry:
    return OmniOdometry(OmniDrive.three_wheel(wheel_radius=0.05, base_radius=0.2))


_OMNI_STEP = np.array([0.4, -0.25, 0.1])


def _diff_prepare(odo: DiffOdometry) -> None:
    odo.update(0, 0)
    odo.update(100, 120)


def test_diff_update_interrupted_anywhere_is_taken_or_not() -> None:
    tried = _check_every_point(
        _diff, _diff_prepare, lambda o: o.update(300, 320), lambda o: o.update(500, 520)
    )
    assert tried > 3  # the fast path makes several calls


def test_diff_update_batch_interrupted_anywhere_is_taken_or_not() -> None:
    _check_every_point(
        _diff,
        _diff_prepare,
        lambda o: o.update_batch([300, 420], [320, 400]),
        lambda o: o.update(500, 520),
    )


def test_diff_reset_interrupted_anywhere_is_done_or_not() -> None:
    _check_every_point(
        _diff,
        _diff_prepare,
        lambda o: o.reset([5e6, 4e6, 1.0]),
        lambda o: (o.update(300, 330), o.update(500, 520)),
    )


def test_omni_update_interrupted_anywhere_is_taken_or_not() -> None:
    def prepare(odo: OmniOdometry) -> None:
        odo.update(_OMNI_STEP.copy(), 0.0)

    tried = _check_every_point(
        _omni, prepare, lambda o: o.update(_OMNI_STEP.copy(), 0.3),
        lambda o: o.update(_OMNI_STEP.copy(), 0.5),
    )
    assert tried > 3


def test_omni_update_batch_interrupted_anywhere_is_taken_or_not() -> None:
    def prepare(odo: OmniOdometry) -> None:
        odo.update(_OMNI_STEP.copy(), 0.0)

    _check_every_point(
        _omni,
        prepare,
        lambda o: o.update_batch(np.stack([_OMNI_STEP, -_OMNI_STEP]), [0.3, -0.2]),
        lambda o: o.update(_OMNI_STEP.copy(), 0.5),
    )


@settings(max_examples=15, deadline=None)
@given(
    start=st.tuples(
        st.floats(-1e7, 1e7), st.floats(-1e7, 1e7), st.floats(-3.14, 3.14)
    ),
    ticks=st.lists(st.tuples(st.integers(-3000, 3000), st.integers(-3000, 3000)),
                   min_size=1, max_size=4),
)
def test_diff_update_interrupted_far_from_the_origin(
    start: tuple[float, float, float], ticks: list[tuple[int, int]]
) -> None:
    def make() -> DiffOdometry:
        return DiffOdometry(
            DiffDrive(track=0.5, wheel_radius=0.1), ticks_per_rev=1000, pose=list(start)
        )

    def prepare(odo: DiffOdometry) -> None:
        odo.update(0, 0)
        for left, right in ticks[:-1]:
            odo.update(left, right)

    left, right = ticks[-1]
    _check_every_point(make, prepare, lambda o: o.update(left, right),
                       lambda o: o.update(left + 77, right - 5))


@pytest.mark.parametrize("make", [_diff, _omni])
def test_the_profile_hook_is_gone_after_an_interrupt(make: Callable[[], Any]) -> None:
    odo = make()
    call = (lambda: odo.update(1, 2)) if isinstance(odo, DiffOdometry) else (
        lambda: odo.update(_OMNI_STEP.copy(), 0.1)
    )
    assert _interrupted_at(1, call)
    assert sys.getprofile() is None
