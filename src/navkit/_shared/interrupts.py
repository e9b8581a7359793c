"""Ctrl-C held back while a step that must not be cut in two runs (private).

Python raises :class:`KeyboardInterrupt` wherever the main thread happens to be
when Ctrl-C arrives. Most of navkit leaves its objects as before or after a
call whatever the point (see the methods' ``Raises`` sections), but one step
cannot be undone: importing numba. An import cut short leaves numba's modules
half made in ``sys.modules``, and every later navkit kernel call in that
process then failed ("partially initialized module 'numba' has no attribute
'core'"): a notebook user who pressed Ctrl-C during a slow first call had to
restart the kernel. An interrupt landing in one of llvmlite's C callbacks
meanwhile was swallowed instead ("Exception ignored on calling ctypes callback
function"), so the user's Ctrl-C was lost.

:func:`interrupts_deferred` holds a ``SIGINT`` back until the step is done and
then hands it to the handler that was installed before, as if it had arrived
just after: a :class:`KeyboardInterrupt` with the default handler, or the
handler of the program (a CLI, a ROS 2 node) that installed its own. A second
Ctrl-C while the step runs is delivered at once: the user insists.
"""

from __future__ import annotations

import contextlib
import signal
import threading
from collections.abc import Iterator
from types import FrameType
from typing import Any

__all__ = ["interrupts_deferred"]


@contextlib.contextmanager
def interrupts_deferred() -> Iterator[None]:
    """Hold ``SIGINT`` back while the block runs; deliver it when the block ends.

    Only the main thread of the main interpreter receives Python signals and can
    install handlers: anywhere else this does nothing (an interrupt there lands
    in the main thread, not in the block). Nor does it where the ``SIGINT``
    handler was not installed from Python (``signal.getsignal`` returns None).

    Examples
    --------
    >>> from navkit._shared.interrupts import interrupts_deferred
    >>> with interrupts_deferred():
    ...     total = sum(range(10))  # a Ctrl-C here would arrive after the block
    >>> total
    45
    """
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    previous: Any = signal.getsignal(signal.SIGINT)
    if previous is None:
        yield
        return
    pending: list[FrameType | None] = []

    def hold(signum: int, frame: FrameType | None) -> None:
        if pending:  # a second Ctrl-C: deliver it now
            signal.signal(signal.SIGINT, previous)
            _deliver(previous, signum, frame)
            return
        pending.append(frame)

    try:
        signal.signal(signal.SIGINT, hold)
    except ValueError:  # not the main interpreter
        yield
        return
    try:
        yield
    finally:
        signal.signal(signal.SIGINT, previous)
        if pending:
            _deliver(previous, signal.SIGINT, pending[0])


def _deliver(handler: Any, signum: int, frame: FrameType | None) -> None:
    """Hand ``signum`` to ``handler`` as the interpreter would have."""
    if callable(handler):
        handler(signum, frame)
    elif handler == signal.SIG_DFL:
        # The default action (ending the process) is the operating system's: raise
        # the signal again now that its default handler is back.
        signal.raise_signal(signum)
    # SIG_IGN: ignored, as it would have been.
