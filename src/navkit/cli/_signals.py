"""Ctrl-C and termination signals while a command runs: one line, no worker noise.

Python's defaults serve a command with worker processes badly:

* Ctrl-C reaches the whole process group. A worker (forked by ``navkit run
  --workers N`` or ``navkit warmup``) waiting for its next trial then died of
  ``KeyboardInterrupt`` with a traceback of the pool's internals on standard
  error, beside the command's own ``navkit: interrupted``.
* ``SIGTERM`` or ``SIGHUP`` (``kill``, a CI job's time limit, a closed terminal,
  ``docker stop``) killed the command at once: no cleanup of temporary files,
  and the pool's workers, blocked forever on a queue no one would write to
  again, were left behind as orphans.

:func:`handled_signals` makes the command end on each of these signals as on
Ctrl-C: an exception in the main thread, so that pools are shut down and
temporary files removed, then exit code ``128 + signal`` and one line. A
worker process forked meanwhile inherits the handler and ends quietly instead
(:class:`WorkerStopped`).

The first of these signals decides how the command ends. Another one during
the clean-up (a Ctrl-C as the temporary files are removed after a ``SIGTERM``)
still raises, so that a clean-up that waits can be cut short, but as the
first: the command reports and exits as that one ended it (``terminated
(SIGTERM)``, 143, not ``interrupted``, 130). In Python the later exception
would replace the first; a command that dies of a signal (Python's default for
``SIGTERM``) reports the one that killed it, and the programs that clean up on
signals (GNU ``sort``, ``csplit``) hold their other signals back while they
clean up after the first and then die of it, so that the shell's ``128 +
signal`` names the first too. A Ctrl-C that navkit holds back through a short
step (:func:`~navkit._shared.interrupts.interrupts_deferred`) counts as
arriving when it is delivered, just after the step.
"""

from __future__ import annotations

import contextlib
import os
import signal
import sys
import threading
from collections.abc import Iterator
from collections.abc import Set as AbstractSet
from types import FrameType

__all__ = ["Terminated", "WorkerStopped", "handled_signals"]


class Terminated(KeyboardInterrupt):
    """The command received ``SIGTERM``, ``SIGHUP`` or ``SIGBREAK``: it ends as on Ctrl-C.

    A :class:`KeyboardInterrupt`, so that the library's clean-up on Ctrl-C
    (pools shut down, temporary files removed) runs for it too.

    Parameters
    ----------
    signum : int
        The signal's number.
    """

    def __init__(self, signum: int) -> None:
        super().__init__(signum)
        self.signum = signum

    @property
    def exit_code(self) -> int:
        """``128 + signal``, what a shell reports for a command a signal ended."""
        return 128 + self.signum

    @property
    def name(self) -> str:
        """The signal's name (``"SIGTERM"``)."""
        return signal.Signals(self.signum).name


class WorkerStopped(SystemExit, KeyboardInterrupt):
    """A signal in a worker process the command forked.

    A :class:`SystemExit` where the worker waits for work: multiprocessing
    then ends the worker quietly rather than printing a traceback. A
    :class:`KeyboardInterrupt` where it runs a trial: the pool sends it back to
    the command, which stops as on Ctrl-C.
    """


def _stop_worker(signum: int, frame: FrameType | None) -> None:
    raise WorkerStopped(128 + signum)


@contextlib.contextmanager
def handled_signals() -> Iterator[None]:
    """Within the block, ``SIGINT``, ``SIGTERM`` and ``SIGHUP`` raise in this process.

    On Windows ``SIGBREAK`` (Ctrl-Break) does too, in place of ``SIGHUP``.
    ``SIGINT`` raises :class:`KeyboardInterrupt` (as by default), the others
    :class:`Terminated`; in a process forked within the block, any of them
    raises :class:`WorkerStopped`. Once one has, every later one within the
    block raises as the first did (``KeyboardInterrupt`` or
    :class:`Terminated` of the first signal): the first decides how the
    command ends. A signal whose handler is not Python's default (set by the
    program embedding the command) is left alone, as is every signal outside
    the main thread, where handlers cannot be set. The previous handlers are
    restored afterwards.
    """
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    owner = os.getpid()
    first: list[int] = []  # the block's first signal, which decides how the command ends

    def handle(signum: int, frame: FrameType | None) -> None:
        if os.getpid() != owner:
            _stop_worker(signum, frame)
        if not first:
            first.append(signum)
        if first[0] == signal.SIGINT:
            raise KeyboardInterrupt
        raise Terminated(first[0])

    defaults = {signal.SIGINT: signal.default_int_handler, signal.SIGTERM: signal.SIG_DFL}
    if hasattr(signal, "SIGHUP"):  # not on Windows
        defaults[signal.SIGHUP] = signal.SIG_DFL
    if hasattr(signal, "SIGBREAK"):  # Windows' Ctrl-Break, which else ends it at once
        defaults[signal.SIGBREAK] = signal.SIG_DFL
    previous = {}
    try:
        for signum, default in defaults.items():
            if signal.getsignal(signum) is default:
                previous[signum] = signal.signal(signum, handle)
        yield
    finally:
        # A signal between two restores would raise out of this loop and leave
        # navkit's handler on the signals not yet restored: hold them until done.
        mask: AbstractSet[int] | None = None
        if sys.platform != "win32" and previous and hasattr(signal, "pthread_sigmask"):
            mask = signal.pthread_sigmask(signal.SIG_BLOCK, previous)  # (Windows has no masks)
        try:
            for signum, handler in previous.items():
                signal.signal(signum, handler)
        finally:
            if sys.platform != "win32" and mask is not None:  # the caller's own mask, as it was
                signal.pthread_sigmask(signal.SIG_SETMASK, mask)
