"""navkit.cli._signals: leaving the block restores handlers and the caller's signal mask."""

from __future__ import annotations

import signal
import threading

import pytest

from navkit.cli._signals import handled_signals

pytestmark = pytest.mark.skipif(
    not hasattr(signal, "pthread_sigmask")
    or threading.current_thread() is not threading.main_thread(),
    reason="needs POSIX signal masks in the main thread",
)


def test_restore_keeps_the_callers_mask_and_handlers() -> None:
    before = signal.pthread_sigmask(signal.SIG_BLOCK, [signal.SIGHUP])  # the caller blocks SIGHUP
    try:
        handlers = {s: signal.getsignal(s) for s in (signal.SIGINT, signal.SIGTERM, signal.SIGHUP)}
        with handled_signals():
            assert signal.getsignal(signal.SIGTERM) is not handlers[signal.SIGTERM]
        mask = signal.pthread_sigmask(signal.SIG_BLOCK, [])
        assert signal.SIGHUP in mask  # still blocked, as the caller left it
        assert signal.SIGTERM not in mask and signal.SIGINT not in mask
        assert {s: signal.getsignal(s) for s in handlers} == handlers
    finally:
        signal.pthread_sigmask(signal.SIG_SETMASK, before)


def test_a_signal_raised_during_restore_reaches_the_restored_handler() -> None:
    # A SIGTERM sent while the handlers are put back is held until all are back,
    # so it meets the caller's handler, not navkit's.
    seen: list[int] = []

    def callers(signum: int, frame: object) -> None:
        seen.append(signum)

    previous = signal.signal(signal.SIGTERM, signal.SIG_DFL)
    try:
        with handled_signals():
            pass
        signal.signal(signal.SIGTERM, callers)
        with handled_signals():
            pass  # navkit leaves the caller's own handler alone
        signal.raise_signal(signal.SIGTERM)
        assert seen == [signal.SIGTERM]
    finally:
        signal.signal(signal.SIGTERM, previous)
