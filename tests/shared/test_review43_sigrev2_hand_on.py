"""A held signal handed on by the pending call is handed on exactly once (review 43, SIGREV2).

``interrupts._hand_on`` hands a held signal to the handler in place when the
pending call runs. Where that is no longer the hold's own (the program's, put
back meanwhile), it clears the hold's ``again`` itself: a signal made pending
again by ``_Due.__bool__`` after another signal's exception is one whose
``again`` is still set. Cleared before the C call ``callable(handler)``, another
signal landing as that call returned (a delivery point) and raising there lost
the held one: its handler never called, its ``again`` already cleared. So did
the hold's own handler (``StepHold.hold``), which cleared it before the C calls
of its tests and restore, and before its ``callable()`` of the handler. These
checks land another signal's exception (a ``KeyboardInterrupt`` from the profile
function of ``interrupt_points.interrupted_at``) at every delivery point of the
hand-on and count: the held signal is handed on, or left to be made pending
again, exactly once.
"""

from __future__ import annotations

import signal
import sys
from collections.abc import Callable, Iterator
from typing import Any

import pytest

from interrupt_points import delivery_points, interrupted_at
from navkit._shared import interrupts

pytestmark = pytest.mark.skipif(sys.platform == "win32", reason="POSIX signals")


@pytest.fixture
def usr1() -> Iterator[Callable[[Any], None]]:
    """Install a handler for SIGUSR1 (put back after)."""
    before = signal.getsignal(signal.SIGUSR1)
    yield lambda handler: signal.signal(signal.SIGUSR1, handler)
    signal.signal(signal.SIGUSR1, before)


def _held() -> interrupts.StepHold:
    hold = interrupts.StepHold(
        critical=lambda frame: False, under_way=lambda: True, signum=signal.SIGUSR1
    )
    hold.again = True  # held in a step, due: its handler is the program's again
    return hold


def _hand_on(hold: interrupts.StepHold, delivered: list[bool]) -> None:
    """Hand ``hold`` on; note in ``delivered`` a KeyboardInterrupt from the handler itself.

    The other signal's (from ``interrupted_at``'s profile function) is raised on;
    landing as the handler's propagates, it has the handler's as its context.
    """
    try:
        interrupts._hand_on([hold], sys._getframe())
    except KeyboardInterrupt as error:
        landed = False
        caught: BaseException | None = error
        while caught is not None:
            tb = caught.__traceback__
            while tb is not None and tb.tb_next is not None:
                tb = tb.tb_next
            if tb is not None and tb.tb_frame.f_code.co_name == "profile":
                landed = True
            elif caught.__class__ is KeyboardInterrupt:  # (no call: no delivery point)
                delivered.append(True)  # Python's handler's (C code: no frame of its own)
            caught = caught.__context__
        if landed:
            raise


def test_a_signal_handed_to_a_raising_handler_put_back_is_handed_on_once(
    usr1: Callable[[Any], None],
) -> None:
    # Python's own Ctrl-C handler (C code, raising KeyboardInterrupt) put back.
    usr1(signal.default_int_handler)
    counted = _held()
    points = delivery_points(lambda: _hand_on(counted, []))
    assert points >= 3
    for k in range(1, points + 1):
        hold, delivered = _held(), []
        landed = interrupted_at(k, lambda hold=hold, d=delivered: _hand_on(hold, d))
        assert landed or delivered, k
        assert len(delivered) + hold.again == 1, (k, delivered, hold.again)


def test_a_signal_handed_to_a_returning_handler_put_back_is_handed_on_once(
    usr1: Callable[[Any], None],
) -> None:
    seen: dict[int, Any] = {}
    usr1(seen.__setitem__)  # a program's handler (C code) that returns
    counted = _held()
    points = delivery_points(lambda: _hand_on(counted, []))
    assert points >= 3
    for k in range(1, points + 1):
        seen.clear()
        hold = _held()
        assert interrupted_at(k, lambda hold=hold: _hand_on(hold, []))
        assert (signal.SIGUSR1 in seen) + hold.again == 1, (k, seen, hold.again)


def test_a_signal_whose_handler_is_gone_is_not_handed_on_again(
    usr1: Callable[[Any], None],
) -> None:
    usr1(signal.SIG_IGN)  # none to hand it to: done
    hold, delivered = _held(), []
    _hand_on(hold, delivered)
    assert not delivered
    assert not hold.again


def _begun(handler: Any, *, under_way: bool = True) -> interrupts.StepHold:
    """A hold of SIGUSR1 (the program's ``handler`` in place) whose signal is due."""
    signal.signal(signal.SIGUSR1, handler)
    hold = interrupts.StepHold(
        critical=lambda frame: False, under_way=lambda: under_way, signum=signal.SIGUSR1
    )
    assert hold.begin()
    hold.again = True  # held in a step, due: handed to the hold's own handler
    return hold


def _ended(hold: interrupts.StepHold, handler: Any) -> None:
    """Take ``hold`` away whatever the landing left (the program's handler back)."""
    hold.restored = True
    signal.signal(signal.SIGUSR1, handler)


@pytest.mark.parametrize("under_way", [True, False])
def test_a_signal_handed_to_its_holds_handler_is_delivered_once(
    usr1: Callable[[Any], None], under_way: bool
) -> None:
    # The hold's own handler delivers a due signal (to the program's handler, or
    # Python's KeyboardInterrupt): it cleared 'again' first, then made C calls
    # (callable(), the restore's) before the delivery, where another signal's
    # exception landing lost it.
    seen: dict[int, Any] = {}
    for handler in (seen.__setitem__, signal.default_int_handler):
        counted = _begun(handler, under_way=under_way)
        points = delivery_points(lambda counted=counted: _hand_on(counted, []))
        _ended(counted, handler)
        assert points >= 3
        for k in range(1, points + 1):
            seen.clear()
            hold, delivered = _begun(handler, under_way=under_way), []
            try:
                interrupted_at(k, lambda hold=hold, d=delivered: _hand_on(hold, d))
            finally:
                _ended(hold, handler)
            handed = len(delivered) + (signal.SIGUSR1 in seen)
            assert handed + hold.again == 1, (handler, k, handed, hold.again)
