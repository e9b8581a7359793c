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

A handler installed outside Python (``rclpy.init()`` installs one with
``sigaction`` that wakes the executor and then calls Python's) is invisible to
``signal.getsignal``: putting back what that reports would leave Python's in
its place for good, and a ROS 2 node's ``spin()`` would no longer wake on
Ctrl-C. Where the system's action can be read (POSIX), it is put back as it
was, and a held Ctrl-C raised again for it. An action such a library installs
from another thread while the block runs is kept too, and gets a held Ctrl-C.
"""

from __future__ import annotations

import contextlib
import os
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
    saved = _system_action()  # before ours: an outside handler shows only here
    ours: Any = None
    # Whether the system's action at the end is another's, not Python's (which
    # getsignal cannot tell): the outside one from before the block, or one a
    # C library installed from another thread during it. Raising the signal
    # again hands a held Ctrl-C to that one.
    outside = [False]
    restored: list[bool] = []

    def restore() -> None:
        if restored:
            return
        restored.append(True)
        now = _system_action()
        intruder = False
        if ours is None:
            # A second Ctrl-C before the block's own action was read: ``now`` is it.
            outside[0] = saved is not None and _handler_address(saved) != _handler_address(now)
        else:
            # A C library (rclpy.init() in another thread) may have installed its
            # action during the block: signal.signal below would overwrite it too.
            intruder = now is not None and _handler_address(now) != _handler_address(ours)
        signal.signal(signal.SIGINT, previous)
        if intruder:
            _set_system_action(now)
            outside[0] = True
        elif outside[0]:
            _set_system_action(saved)

    def deliver(frame: FrameType | None) -> None:
        if outside[0]:
            signal.raise_signal(signal.SIGINT)  # to the outside handler, which chains on
        else:
            _deliver(previous, signal.SIGINT, frame)

    def hold(signum: int, frame: FrameType | None) -> None:
        if pending:  # a second Ctrl-C: deliver it now
            restore()
            deliver(frame)
            return
        pending.append(frame)

    try:
        signal.signal(signal.SIGINT, hold)
    except ValueError:  # not the main interpreter
        yield
        return
    action = _system_action()
    if not restored:  # else a second Ctrl-C came first and restore() has decided
        ours = action
        outside[0] = saved is not None and _handler_address(saved) != _handler_address(ours)
    try:
        yield
    finally:
        restore()
        if pending:
            deliver(pending[0])


#: The C library's ``sigaction``, once looked up (None where there is none).
_SIGACTION: list[Any] = []


def _sigaction() -> Any:
    """The C library's ``sigaction`` (POSIX), or None."""
    if not _SIGACTION:
        function = None
        if os.name == "posix":
            try:
                import ctypes

                function = ctypes.CDLL(None, use_errno=True).sigaction
            except (ImportError, OSError, AttributeError):
                function = None
        _SIGACTION.append(function)
    return _SIGACTION[0]


def _system_action() -> Any:
    """``SIGINT``'s ``struct sigaction`` as the system holds it (an opaque buffer), or None."""
    sigaction = _sigaction()
    if sigaction is None:
        return None
    import ctypes

    action = ctypes.create_string_buffer(512)  # larger than any system's struct sigaction
    return action if sigaction(signal.SIGINT, None, action) == 0 else None


def _handler_address(action: Any) -> int | None:
    """The handler of an action from :func:`_system_action` (its first field on POSIX systems)."""
    if action is None:
        return None
    import ctypes

    address: int | None = ctypes.c_void_p.from_buffer(action).value
    return address or 0


def _set_system_action(action: Any) -> None:
    """Make ``action`` (from :func:`_system_action`) ``SIGINT``'s action again."""
    _sigaction()(signal.SIGINT, action, None)


def _deliver(handler: Any, signum: int, frame: FrameType | None) -> None:
    """Hand ``signum`` to ``handler`` as the interpreter would have."""
    if callable(handler):
        handler(signum, frame)
    elif handler == signal.SIG_DFL:
        # The default action (ending the process) is the operating system's: raise
        # the signal again now that its default handler is back.
        signal.raise_signal(signum)
    # SIG_IGN: ignored, as it would have been.
