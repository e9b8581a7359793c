"""Review 41 (HOLDFIX): ``StepHolds`` outside the span, and handlers installed during it.

The probes in ``test_review41_revsig_step_holds.py`` show the defects through
numba's compiler lock; these check the holds' own rules in this process:

* a signal found outside the span (``under_way`` false: before the lock is
  taken) whose handler returns keeps its hold in place (the compile after needs
  it); one whose handler raises ends every hold of its ``StepHolds``;
* ``StepHolds.extend`` holds a signal whose Python handler was installed
  since ``begin`` (once, however often it is called), and leaves alone what
  ``begin`` leaves alone (asyncio's handler) without growing;
* a hold refers to its group weakly: the holds are freed without the collector.
"""

from __future__ import annotations

import asyncio.unix_events
import gc
import signal
import sys
import weakref
from collections.abc import Iterator
from types import FrameType
from typing import Any

import pytest

from navkit._shared.interrupts import StepHold, StepHolds

pytestmark = pytest.mark.skipif(sys.platform == "win32", reason="POSIX signals")

_SIGNUMS = (signal.SIGINT, signal.SIGALRM, signal.SIGTERM, signal.SIGUSR1, signal.SIGUSR2)


@pytest.fixture
def handlers_back() -> Iterator[None]:
    """Put every handler these tests touch back as it was."""
    before = {signum: signal.getsignal(signum) for signum in _SIGNUMS}
    try:
        yield
    finally:
        for signum, handler in before.items():
            signal.signal(signum, handler)


def _outside_the_span() -> StepHolds:
    return StepHolds(critical=lambda frame: False, under_way=lambda: False)


def _held_for(signum: int) -> Any:
    """The program's handler behind navkit's hold of ``signum`` (None where not held)."""
    handler = signal.getsignal(signum)
    owner = getattr(handler, "__self__", None)
    return owner.previous if isinstance(owner, StepHold) else None


@pytest.mark.usefixtures("handlers_back")
def test_a_handler_that_returns_outside_the_span_keeps_the_holds() -> None:
    came: list[int] = []

    def note(signum: int, frame: FrameType | None) -> None:
        came.append(signum)

    signal.signal(signal.SIGUSR1, note)
    holds = _outside_the_span()
    assert holds.begin()
    signal.raise_signal(signal.SIGUSR1)
    len(())  # a delivery point
    assert came == [signal.SIGUSR1]
    assert _held_for(signal.SIGUSR1) is note  # was: the hold ended, SIGUSR1 unheld
    assert not holds.restored
    holds.end()
    assert signal.getsignal(signal.SIGUSR1) is note
    assert holds.restored


@pytest.mark.usefixtures("handlers_back")
@pytest.mark.parametrize("raising", [signal.SIGINT, signal.SIGALRM], ids=["SIGINT", "SIGALRM"])
def test_a_handler_that_raises_outside_the_span_ends_every_hold(raising: int) -> None:
    def alarm(signum: int, frame: FrameType | None) -> None:
        raise TimeoutError

    def note(signum: int, frame: FrameType | None) -> None:
        pass

    signal.signal(signal.SIGINT, signal.default_int_handler)
    signal.signal(signal.SIGALRM, alarm)
    signal.signal(signal.SIGTERM, note)
    holds = _outside_the_span()
    assert holds.begin()
    assert [_held_for(s) for s in (signal.SIGALRM, signal.SIGTERM)] == [alarm, note]
    with pytest.raises((KeyboardInterrupt, TimeoutError)):
        signal.raise_signal(raising)
        len(())
    assert holds.restored  # was False: the other holds stayed in place
    assert signal.getsignal(signal.SIGINT) is signal.default_int_handler
    assert signal.getsignal(signal.SIGALRM) is alarm
    assert signal.getsignal(signal.SIGTERM) is note


@pytest.mark.usefixtures("handlers_back")
def test_extend_holds_a_handler_installed_since_once() -> None:
    def stop(signum: int, frame: FrameType | None) -> None:
        raise SystemExit(3)

    signal.signal(signal.SIGUSR2, signal.SIG_DFL)
    holds = StepHolds(critical=lambda frame: False, under_way=lambda: True)
    holds.begin()
    try:
        count = len(holds.holds)
        assert _held_for(signal.SIGUSR2) is None
        signal.signal(signal.SIGUSR2, stop)  # as a handler run in the compile would
        holds.extend()
        assert _held_for(signal.SIGUSR2) is stop
        holds.extend()
        holds.extend()
        assert len(holds.holds) == count + 1
    finally:
        holds.end()
    assert signal.getsignal(signal.SIGUSR2) is stop
    assert holds.restored


class _Unhashable:
    """A program's handler object that compares by value (so cannot be hashed)."""

    __hash__ = None  # type: ignore[assignment]

    def __eq__(self, other: object) -> bool:
        return isinstance(other, _Unhashable)

    def __call__(self, signum: int, frame: FrameType | None) -> None:
        pass


@pytest.mark.usefixtures("handlers_back")
def test_extend_leaves_asyncio_alone_and_takes_any_callable() -> None:
    noop = asyncio.unix_events._sighandler_noop  # type: ignore[attr-defined]
    handler = _Unhashable()
    signal.signal(signal.SIGUSR1, handler)
    holds = StepHolds(critical=lambda frame: False, under_way=lambda: True)
    holds.begin()
    try:
        count = len(holds.holds)
        signal.signal(signal.SIGUSR2, noop)  # asyncio's: woken by the fd already
        for _ in range(3):
            holds.extend()
        assert len(holds.holds) == count  # nothing begun, nothing kept
        assert signal.getsignal(signal.SIGUSR2) is noop
        assert _held_for(signal.SIGUSR1) is handler
    finally:
        holds.end()
    assert signal.getsignal(signal.SIGUSR1) is handler


@pytest.mark.usefixtures("handlers_back")
def test_the_holds_are_freed_without_the_collector() -> None:
    signal.signal(signal.SIGUSR1, lambda signum, frame: None)
    holds = StepHolds(critical=lambda frame: False, under_way=lambda: True)
    holds.begin()
    holds.end()
    alive = weakref.ref(holds)
    enabled = gc.isenabled()
    gc.disable()
    try:
        del holds
        assert alive() is None  # no cycle: a hold refers to its group weakly
    finally:
        if enabled:
            gc.enable()
