"""Review 40 (REVD): what navkit's signal holds leave of a program's signal set-up.

* A program's ``signal.siginterrupt(signum, False)`` (``SA_RESTART``: C code's
  slow system calls restarted, not failed with ``EINTR``, when the signal
  comes) was lost at the end of every hold of that signal: each hold put the
  program's handler back with ``signal.signal``, which sets the system's
  action's flags afresh. The holds are begun by every compile or cache load in
  the main thread (:class:`StepHolds`, every signal with a Python handler), by
  every ``os.fork`` (:func:`held_for_fork`) and by navkit's deferrals of
  Ctrl-C (:func:`interrupts_deferred`). The system's action is now put back
  byte for byte (handler, mask, flags).
* Two signals held in one step, the first delivered after it installing another
  handler for the second (which then goes to that one, as it would have without
  the hold): the second's hold waited for good for its signal to come back, so
  the holds were never ended, and numba's lock steps held nothing for the rest
  of the process (compile_gc begins new holds only once the old have ended).
* A signal held in a step is made pending again at every delivery point of the
  step (``_thread.interrupt_main``), and each time Python writes its number to
  the wakeup fd (``signal.set_wakeup_fd``: asyncio, trio, Qt event loops) once
  more: hundreds of bytes for one signal, and with ``warn_on_full_buffer`` (the
  default) a full buffer printed "Exception ignored when trying to write to the
  signal wakeup fd" at every delivery point after. A strict xfail until review 41
  (WAKEUP): the signal is now handed on once, after the step, by a profile
  function (``interrupts._watch``), not made pending again.
"""

from __future__ import annotations

import ctypes
import os
import signal
import socket
import sys
from collections.abc import Iterator
from typing import Any

import pytest

from navkit._shared import interrupts

pytestmark = [
    pytest.mark.skipif(
        not sys.platform.startswith("linux") or ctypes.sizeof(ctypes.c_void_p) != 8,
        reason="glibc's struct sigaction of 64-bit Linux read",
    ),
]


def _action(signum: int) -> tuple[bytes, bytes, int]:
    """``signum``'s handler, first 64 signals of its mask and its flags (glibc's layout).

    glibc's ``struct sigaction`` on 64-bit Linux: the handler (8 bytes), a
    128-byte ``sigset_t`` of which the kernel fills 8 (the rest is left as glibc's
    stack had it), then ``int sa_flags``.
    """
    libc = ctypes.CDLL(None, use_errno=True)
    buffer = (ctypes.c_char * 512)()
    assert libc.sigaction(signum, None, buffer) == 0
    raw = bytes(buffer)
    return raw[:8], raw[8:16], int.from_bytes(raw[136:140], sys.byteorder)


def _on_signal(signum: int, frame: Any) -> None:
    """A program's handler (noting nothing: the tests look at the action)."""


@pytest.fixture
def restartable() -> Iterator[int]:
    """SIGUSR1 with a Python handler and SA_RESTART (``siginterrupt(False)``), undone after."""
    signum = int(signal.SIGUSR1)
    before = signal.signal(signum, _on_signal)
    try:
        plain = _action(signum)
        signal.siginterrupt(signum, False)
        assert _action(signum) != plain  # the flag shows in the action
        yield signum
    finally:
        signal.signal(signum, before)


def test_step_holds_keep_a_programs_sa_restart(restartable: int) -> None:
    before = _action(restartable)
    holds = interrupts.StepHolds(critical=lambda frame: False, under_way=lambda: True)
    assert holds.begin()
    assert restartable in [hold.signum for hold in holds.holds]
    holds.end()
    assert signal.getsignal(restartable) is _on_signal
    assert _action(restartable) == before


def test_fork_hold_keeps_a_programs_sa_restart(restartable: int) -> None:
    before = _action(restartable)
    record: list[Any] = []
    hold = interrupts.held_for_fork(sys._getframe(), record)
    assert signal.getsignal(restartable) is not _on_signal  # held
    interrupts.release_in_parent(hold)
    assert signal.getsignal(restartable) is _on_signal
    assert _action(restartable) == before


def test_deferral_keeps_sigints_sa_restart() -> None:
    before_handler = signal.getsignal(signal.SIGINT)
    try:
        signal.signal(signal.SIGINT, _on_signal)
        signal.siginterrupt(signal.SIGINT, False)
        before = _action(signal.SIGINT)
        with interrupts.interrupts_deferred():
            assert signal.getsignal(signal.SIGINT) is not _on_signal
        assert signal.getsignal(signal.SIGINT) is _on_signal
        assert _action(signal.SIGINT) == before
    finally:
        signal.signal(signal.SIGINT, before_handler)


def test_a_signal_comes_once_and_an_outside_action_is_still_put_back(
    restartable: int,
) -> None:
    # The action put back is the one from before, whatever Python's signal.signal makes.
    came: list[int] = []

    def note(signum: int, frame: Any) -> None:
        came.append(signum)

    signal.signal(restartable, note)
    signal.siginterrupt(restartable, False)
    before = _action(restartable)
    inside = [True]
    holds = interrupts.StepHolds(critical=lambda frame: inside[0], under_way=lambda: True)
    assert holds.begin()
    os.kill(os.getpid(), restartable)
    for _ in range(5):
        len(str(came))  # delivery points inside the step: held
    assert came == []
    inside[0] = False
    len(str(came))  # the step done: delivered at the next point
    holds.end()
    assert came == [restartable]
    assert _action(restartable) == before


def test_a_held_signal_writes_the_wakeup_fd_once() -> None:
    signum = int(signal.SIGUSR2)
    came: list[int] = []

    def note(number: int, frame: Any) -> None:
        came.append(number)

    reader, writer = socket.socketpair()
    reader.setblocking(False)
    writer.setblocking(False)
    before = signal.signal(signum, note)
    old_fd = signal.set_wakeup_fd(writer.fileno(), warn_on_full_buffer=False)
    try:
        inside = [True]
        holds = interrupts.StepHolds(critical=lambda frame: inside[0], under_way=lambda: True)
        assert holds.begin()
        os.kill(os.getpid(), signum)
        for _ in range(20):
            len(str(came))  # delivery points inside the step
        inside[0] = False
        len(str(came))
        holds.end()
        assert came == [signum]
        written = reader.recv(1 << 16)
    finally:
        signal.set_wakeup_fd(old_fd)
        signal.signal(signum, before)
        reader.close()
        writer.close()
    assert written == bytes([signum])  # as without the hold: one byte for one signal


def test_holds_end_when_a_held_signals_handler_is_replaced_before_it_comes_back() -> None:
    # SIGUSR2 and SIGUSR1 held in one step; after the step Python runs SIGUSR1's
    # handler first (signal order), which installs another SIGUSR2 handler: the
    # pending SIGUSR2 goes to that one, never back to its hold. Waiting for it, the
    # hold never ended, StepHolds.restored stayed False, and compile_gc's next lock
    # take found the old holds "in place" and held nothing for the rest of the process.
    came: list[tuple[str, int]] = []

    def replaced(signum: int, frame: Any) -> None:
        came.append(("old", signum))

    def replacement(signum: int, frame: Any) -> None:
        came.append(("new", signum))

    def first(signum: int, frame: Any) -> None:
        came.append(("first", signum))
        signal.signal(signal.SIGUSR2, replacement)

    usr1 = signal.signal(signal.SIGUSR1, first)
    usr2 = signal.signal(signal.SIGUSR2, replaced)
    try:
        inside = [True]
        holds = interrupts.StepHolds(critical=lambda frame: inside[0], under_way=lambda: True)
        assert holds.begin()
        os.kill(os.getpid(), signal.SIGUSR2)
        os.kill(os.getpid(), signal.SIGUSR1)
        for _ in range(3):
            len(str(came))  # inside the step: held
        assert came == []
        inside[0] = False
        for _ in range(3):
            len(str(came))  # delivered
        holds.end()
        assert came == [("first", signal.SIGUSR1), ("new", signal.SIGUSR2)]
        assert holds.restored
        assert signal.getsignal(signal.SIGUSR1) is first
        assert signal.getsignal(signal.SIGUSR2) is replacement
    finally:
        signal.signal(signal.SIGUSR1, usr1)
        signal.signal(signal.SIGUSR2, usr2)
