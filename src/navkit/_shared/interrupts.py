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

:class:`StepHold` holds a Ctrl-C only while the main thread is inside given
short steps of a longer span (numba's and llvmlite's handling of their locks
during a compile, see :mod:`navkit._shared.compile_gc`), delivering it at once
elsewhere.
"""

from __future__ import annotations

import _thread
import collections
import contextlib
import functools
import importlib
import os
import signal
import sys
import threading
import time
import weakref
from collections.abc import Callable, Iterator
from types import FrameType
from typing import Any, cast

__all__ = [
    "StepHold",
    "StepHolds",
    "held_for_fork",
    "interrupts_deferred",
    "release_in_child",
    "release_in_parent",
    "release_others_in_child",
    "rewatch",
]


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
    hold = _Hold(insist=True)
    if not hold.start():
        yield
        return
    try:
        yield
    finally:
        hold.restore()
        if hold.pending:
            hold.deliver(hold.pending[0])


class _Hold:
    """``SIGINT`` held back from :meth:`start` to :meth:`restore` (the parts of a deferral).

    ``insist``: a second Ctrl-C is delivered at once (the user insists), else
    every one is held. ``signum``: another signal held the same way (a fork's
    hold holds every signal with a Python handler, see :func:`held_for_fork`).
    """

    def __init__(self, *, insist: bool, signum: int = signal.SIGINT) -> None:
        self.insist = insist
        self.signum = signum
        #: The frames the held Ctrl-Cs interrupted (the first is delivered).
        self.pending: list[FrameType | None] = []
        self.previous: Any = None
        self.saved: Any = None
        self.ours: Any = None
        # Whether the system's action at the end is another's, not Python's (which
        # getsignal cannot tell): the outside one from before the block, or one a
        # C library installed from another thread during it. Raising the signal
        # again hands a held Ctrl-C to that one.
        self.outside = False
        self.restored = False

    def _action(self) -> Any:
        """The system's action for the signal held (see :func:`_system_action`)."""
        return _system_action() if self.signum == signal.SIGINT else _action_of(self.signum)

    def start(self) -> bool:
        """Hold ``SIGINT`` from now on; False where it cannot be held (see interrupts_deferred)."""
        if threading.current_thread() is not threading.main_thread():
            return False
        self.previous = signal.getsignal(self.signum)
        if self.previous is None:
            return False
        self.saved = self._action()  # before ours: an outside handler shows only here
        try:
            _setsignal(self.signum, self.hold)
        except ValueError:  # not the main interpreter
            return False
        action = self._action()
        if not self.restored:  # else a second Ctrl-C came first and restore() has decided
            self.ours = action
            self.outside = self.saved is not None and _handler_address(
                self.saved
            ) != _handler_address(action)
        return True

    def restore(self) -> None:
        """Put the handler (and the system's action) from before :meth:`start` back."""
        if self.restored:
            return
        self.restored = True
        if self.ours is None and signal.getsignal(self.signum) != self.hold:
            # start() was cut short (another signal's handler raised: a fork's
            # hold, see held_for_fork) before it put ours in place: nothing to undo.
            return
        now = self._action()
        intruder = False
        if self.ours is None:
            # A second Ctrl-C before the block's own action was read: ``now`` is it.
            self.outside = self.saved is not None and _handler_address(
                self.saved
            ) != _handler_address(now)
        else:
            # A C library (rclpy.init() in another thread) may have installed its
            # action during the block: signal.signal below would overwrite it too.
            intruder = now is not None and _handler_address(now) != _handler_address(self.ours)
        _put_back(self.signum, self.previous)
        if intruder:
            _set_system_action(now, self.signum)
            self.outside = True
        elif self.saved is not None:
            # Python's own action too: signal.signal sets its flags afresh, and a
            # program's signal.siginterrupt(signum, False) (SA_RESTART) was lost
            # at every hold's end (review 40, REVD).
            _set_system_action(self.saved, self.signum)

    def deliver(self, frame: FrameType | None) -> None:
        """Hand a held Ctrl-C to the handler from before :meth:`start` (after :meth:`restore`)."""
        if self.outside:
            signal.raise_signal(self.signum)  # to the outside handler, which chains on
        else:
            _deliver(self.previous, self.signum, frame)

    def hold(self, signum: int, frame: FrameType | None) -> None:
        """The handler while held."""
        if self.pending and self.insist:  # a second Ctrl-C: deliver it now
            self.restore()
            self.deliver(frame)
            return
        self.pending.append(frame)


class StepHold(_Hold):
    """``SIGINT`` held only while the main thread is inside a step that must not be cut short.

    For a span too long to hold Ctrl-C across (numba's compiler lock held by the
    main thread: a whole compile) inside which short steps must not be cut in
    two (numba letting go of that lock: a ``KeyboardInterrupt`` as its
    ``__exit__`` is entered left the lock held for good). :meth:`begin` puts
    this hold's handler in place for the span and :meth:`end` takes it away.
    A Ctrl-C meanwhile is handed at once to the handler from before (a
    ``KeyboardInterrupt`` where the interrupt lands, as without the hold)
    unless ``critical`` says the main thread's stack, from the frame the
    signal interrupted, is inside such a step: then a profile function
    (:func:`_watch`) hands it to the handler in place at the first delivery
    point after the step (a function's entry, a C call's return), here
    again, which delivers it. Made pending again at every delivery point
    instead (``_thread.interrupt_main``, as up to review 40), the signal's
    number was written to the wakeup fd each time. Nothing is done at a
    step's end, and nothing costs anything until a Ctrl-C comes.
    ``under_way`` says whether the span is under way (the lock held): a
    signal found outside it (before the lock is taken, in the wait for it)
    is delivered with the hold kept, since a handler that returns lets the
    wait, and the compile, go on; one whose handler raises ends the wait,
    with no release to end the hold, so the hold ends, and every other hold
    of its :class:`StepHolds` (:attr:`group`) with it.

    ``signum``: another signal held the same way (its handler's exception,
    a ``signal.alarm`` time-out or a ``SIGTERM`` handler's ``SystemExit``, cut
    the steps short as a ``KeyboardInterrupt`` did; :class:`StepHolds` holds
    every signal with a Python handler). Begun only in the main thread of the
    main interpreter (where Python runs signal handlers) and where the handler
    from before is a Python callable that could raise (not ``SIG_DFL``,
    ``SIG_IGN``, asyncio's, nor one installed outside Python). A handler from
    before that does not raise (a program that only notes the Ctrl-C) is
    called and the hold stays in place; one to be reached by raising the
    signal again (a system action installed outside Python behind it, see
    :class:`_Hold`) is reached after the hold ends.

    Examples
    --------
    >>> import signal
    >>> from navkit._shared.interrupts import StepHold
    >>> hold = StepHold(critical=lambda frame: False, under_way=lambda: True)
    >>> hold.begin()  # in the main thread, with Python's own handler
    True
    >>> signal.getsignal(signal.SIGINT) == hold.hold
    True
    >>> hold.end()
    >>> signal.getsignal(signal.SIGINT) is signal.default_int_handler
    True
    """

    def __init__(
        self,
        *,
        critical: Callable[[FrameType | None], bool],
        under_way: Callable[[], bool],
        signum: int = signal.SIGINT,
    ) -> None:
        super().__init__(insist=False, signum=signum)
        self.critical = critical
        self.under_way = under_way
        #: A Ctrl-C made pending again, not yet delivered.
        self.again = False
        #: :meth:`end` came while a Ctrl-C was pending: the hold ends as it is delivered.
        self.ending = False
        #: The :class:`StepHolds` this hold is one of, ended with it when its handler
        #: raises outside the span (a weak reference: the group holds its holds).
        self.group: Callable[[], StepHolds | None] = _no_group

    def begin(self) -> bool:
        """Put the hold in place; False (nothing done) where it is not needed or cannot be."""
        if threading.current_thread() is not threading.main_thread():
            return False
        previous = _getsignal(self.signum)
        if not callable(previous) or _woken_already(previous):
            return False
        return self.start()

    def end(self) -> None:
        """Take the hold away (a Ctrl-C still pending is delivered as its step is done)."""
        if self.restored:
            return
        if self.again and _getsignal(self.signum) == self.hold:
            self.ending = True  # the held Ctrl-C comes back to hold(), which ends it
            rewatch()
            return
        # (Pending again but another handler put in place, by another held signal's
        # handler run first: the signal goes to that one, never back to hold(), and
        # waiting for it left this hold and StepHolds.restored unended for good,
        # and numba's lock steps held nothing after; review 40, REVD.)
        if _getsignal(self.signum) == self.hold:
            self.restore()
        else:  # another handler put in place meanwhile (which puts this one back): left so
            self.restored = True

    def hold(self, signum: int, frame: FrameType | None) -> None:
        """The handler while held: deliver now, or hold the signal until the step is done."""
        if not self.restored and self.critical(sys._getframe(1)):
            self.again = True
            # (Already watched: a second one in the step is one, as the system delivers them.)
            profile: Any = sys.getprofile()  # (a C profiler's object too, not callable)
            tracer: Any = sys.gettrace()
            watched = profile is _watch or tracer is _watch  # (in either slot, it hands on)
            if watched and not _WATCH_GOING[0]:
                if self not in _WATCHED:
                    _WATCHED.append(self)
            elif not watched and (profile is None or callable(profile)):
                _WATCH_GOING[0] = False
                _CHAINED[0] = profile  # a program's profile function: called first
                if self not in _WATCHED:
                    _WATCHED.append(self)
                sys.setprofile(_watch)  # (for any watched before it lost its watch too)
            elif not watched and tracer is None:
                # A C profiler in use (cProfile's): watched from the trace slot, at
                # function entries only (made pending again at every point of the step,
                # a signal held at a function's entry came back there for good on
                # Python 3.11, which checks again there while profiling: review 41,
                # REVSIG's spin).
                _WATCH_GOING[0] = False
                _CHAINED[0] = None
                if self not in _WATCHED:
                    _WATCHED.append(self)
                sys.settrace(_watch)
            else:  # a C profiler and a tracer in use: pending again at every point of the step
                if self in _WATCHED:
                    _WATCHED.remove(self)
                _pend_again(signum)  # the last thing done (see _PENDING_AGAIN)
            return
        # (again is cleared by _hand_over, as the signal is delivered: cleared here, another
        # signal's exception landing at a delivery point of the restore or the tests
        # below lost this one; review 43, SIGREV2)
        if self.restored or self.ending or self.outside or not callable(self.previous):
            self._end_here()
        elif not self.under_way():
            # Before the lock is taken (numba's report of the acquire, the wait for
            # another thread): a handler that returns lets the wait go on, and the
            # compile after needs the hold (ended here, a program's second Ctrl-C as
            # numba let go of the lock left it held for good; review 41, REVSIG). One
            # that raises ends the wait with no release to follow: every hold ends
            # (this one's alone left the others in place and StepHolds.restored
            # false, and the next compile reused them with Ctrl-C unheld).
            try:
                self._hand_over(frame)
            except BaseException:
                self._end_here()
                group = self.group()
                if group is not None:
                    group.end()
                raise
            return
        self._hand_over(frame)

    def _hand_over(self, frame: FrameType | None) -> None:
        """Deliver the signal (see :meth:`_Hold.deliver`), ``again`` cleared as the last act before.

        No delivery point from the clearing to the handler's call or the raise:
        another signal's exception landing between lost this one (not handed on,
        nor made pending again by ``_Due``); one landing before leaves ``again``
        set, and the signal is made pending again, not lost; cleared after the
        call, a handler's own exception would have it handed on twice.
        """
        handler = self.previous
        if self.outside:
            self.again = False
            signal.raise_signal(self.signum)  # to the outside handler, which chains on
        elif handler is signal.default_int_handler:
            self.again = False
            raise KeyboardInterrupt  # as Python's handler would (one frame more, not three)
        elif callable(handler):
            self.again = False
            handler(self.signum, frame)
        elif handler == signal.SIG_DFL:
            self.again = False
            signal.raise_signal(self.signum)  # the default action, its handler back
        else:  # SIG_IGN: ignored, as it would have been
            self.again = False

    def _end_here(self) -> None:
        """End the hold from its own handler (and a hold begun inside it that put it back)."""
        self.restore()
        if _getsignal(self.signum) == self.hold:  # put back by a hold begun inside this one
            _put_back(self.signum, self.previous)


def _no_group() -> StepHolds | None:
    """The group of a :class:`StepHold` begun on its own: none."""
    return None


class StepHolds:
    """A :class:`StepHold` of ``SIGINT`` and one of every other signal with a Python handler.

    The handler of any signal can raise (a ``signal.alarm`` time-out, a
    service's ``SIGTERM`` handler raising ``SystemExit``), and its exception
    cut a step short as a Ctrl-C's did: at the return of the compiler lock's
    own ``acquire`` inside numba's, it left numba's compiler lock held for good
    (review 40). So each such signal is held in the steps (``critical``) and
    delivered at the next delivery point after, by its own hold, as
    :func:`held_for_fork` holds them during a fork: ``SIGINT`` first, then the
    others in signal order (the signals Python found by
    :data:`_SIGNALS`, about 4 µs to look at every one); ``SIG_IGN``,
    ``SIG_DFL``, asyncio's and handlers installed outside Python are left
    alone. Signals held together are delivered together, in signal order, as
    CPython runs pending handlers; two of one kind in a step are one, as the
    system delivers them. While the holds are in place ``signal.getsignal``
    returns a hold's ``hold`` method for each signal held (its ``__self__``'s
    ``previous`` is the program's handler), as for ``SIGINT`` alone before and
    during a fork's hooks.

    Examples
    --------
    >>> import signal
    >>> from navkit._shared.interrupts import StepHolds
    >>> def on_alarm(signum, frame):
    ...     raise TimeoutError
    >>> _ = signal.signal(signal.SIGALRM, on_alarm)
    >>> holds = StepHolds(critical=lambda frame: False, under_way=lambda: True)
    >>> holds.begin()  # in the main thread: SIGINT's and SIGALRM's handlers are Python's
    True
    >>> [hold.signum for hold in holds.holds] == [signal.SIGINT, signal.SIGALRM]
    True
    >>> signal.getsignal(signal.SIGALRM).__self__.previous is on_alarm
    True
    >>> holds.end()
    >>> signal.getsignal(signal.SIGALRM) is on_alarm
    True
    >>> _ = signal.signal(signal.SIGALRM, signal.SIG_DFL)
    """

    __slots__ = ("__weakref__", "critical", "holds", "under_way")

    def __init__(
        self, *, critical: Callable[[FrameType | None], bool], under_way: Callable[[], bool]
    ) -> None:
        self.critical = critical
        self.under_way = under_way
        #: The holds begun (or cut short as they began), ``SIGINT``'s first.
        self.holds: list[StepHold] = []

    @property
    def restored(self) -> bool:
        """Whether every hold is taken away (True where none was put in place)."""
        # A loop, not all() of a generator: a signal's handler raising as a
        # generator is closed is reported as ignored, and the exception lost.
        for hold in self.holds:  # noqa: SIM110
            if not hold.restored:
                return False
        return True

    def begin(self) -> bool:
        """Put the holds in place; False where none is (nothing done: not needed or cannot be).

        A signal landing before its own hold is in place runs the program's
        handler here; an exception it raises ends :meth:`begin` there, and
        :meth:`end` takes away what was put in place (every hold is recorded
        in :attr:`holds` before it begins).
        """
        if threading.current_thread() is not threading.main_thread():
            return False
        self._hold_new()
        return not self.restored

    def extend(self) -> None:
        """Hold too every signal whose Python handler was installed since :meth:`begin`.

        A handler run during the span (another signal's) can install one for a
        signal that had none as the holds began; not held, its exception at
        numba's release left the compiler lock held for good (review 41, REVSIG).
        About 3 µs a call (a look at every signal's handler; 2.4-2.7 µs, medians of 9).
        """
        if threading.current_thread() is threading.main_thread():
            self._hold_new(again=True)

    def _hold_new(self, *, again: bool = False) -> None:
        """Hold each signal with a Python handler (``again``: one not held by these already)."""
        # (A list: a program's handler may be a callable object that cannot be hashed.)
        held = [hold.hold for hold in self.holds if not hold.restored] if again else []
        for signum in (int(signal.SIGINT), *_SIGNALS):
            handler = _getsignal(signum)
            if not callable(handler) or handler in held:
                continue
            hold = StepHold(critical=self.critical, under_way=self.under_way, signum=signum)
            hold.group = weakref.ref(self)
            self.holds.append(hold)  # before it begins: cut short, end() undoes it
            if hold.begin():
                continue
            if again:  # nothing put in place (asyncio's): not kept, looked at again next time
                self.holds.remove(hold)
            else:
                hold.restored = True

    def end(self) -> None:
        """Take every hold away, the last begun first (see :meth:`StepHold.end`).

        Once a program's handler is back its signal can come, and the handler
        raise, while the next holds are taken away: they are taken away all
        the same (one cut short as it put its handler back too, as
        :meth:`_ForkHold.restore` does), and the first such exception is
        raised after.
        """
        error: BaseException | None = None
        done = False
        while not done:
            try:
                for hold in reversed(self.holds):
                    hold.end()  # once: again, nothing
                for hold in self.holds:
                    if hold.restored and _getsignal(hold.signum) == hold.hold:
                        _put_back(hold.signum, hold.previous)  # cut short in its restore
                done = True
            except BaseException as caught:  # a handler put back, its signal come
                if error is None:
                    error = caught
        if error is not None:
            raise error


class _ForkHold:
    """The signals :func:`held_for_fork` holds for one fork: a :class:`_Hold` each."""

    __slots__ = ("early", "fork_caller", "holds", "signums")

    def __init__(self, fork_caller: FrameType | None) -> None:
        #: The frame that called ``os.fork``.
        self.fork_caller = fork_caller
        #: SIGINT's first, then every other signal's with a Python handler.
        self.holds: list[_Hold] = []
        #: The signals but SIGINT to hold, once looked up.
        self.signums: list[int] | None = None
        #: The exception a signal's handler raised before its hold was in place.
        self.early: BaseException | None = None

    def start(self) -> None:
        """Hold ``SIGINT``, then every other signal whose handler is a Python callable.

        A handler that raises before its signal's hold is in place (its signal
        came first) does not cut this short: its exception is kept in
        :attr:`early`, raised in the parent as ``os.fork`` returns
        (:func:`release_in_parent`), and the holds go on from where they were,
        the one cut short made again if its handler is not in place. Callable
        again after an exception before its own first line: it goes on.
        """
        if threading.current_thread() is not threading.main_thread():
            return  # only the main thread runs Python's handlers
        while True:
            try:
                holds = self.holds
                last = holds[-1] if holds else None
                if last is not None and last.ours is None and _getsignal(last.signum) != last.hold:
                    # cut short before its handler was in place: made again
                    hold = _Hold(insist=False, signum=last.signum)
                    holds.append(hold)  # before it starts: cut short, restore() undoes it
                    hold.start()
                if not holds:
                    hold = _Hold(insist=False)
                    holds.append(hold)
                    hold.start()
                if self.signums is None:
                    self.signums = [s for s in _SIGNALS if callable(_getsignal(s))]
                done = {hold.signum for hold in holds}
                for signum in self.signums:
                    if signum not in done:
                        hold = _Hold(insist=False, signum=signum)
                        holds.append(hold)
                        hold.start()
                return
            except BaseException as error:  # a handler's, its signal not yet held
                if self.early is None:
                    self.early = error

    def restore(self) -> list[int]:
        """Put every handler back, last held first; the signals that came meanwhile.

        Once a handler is back, its signal can come again, and its handler
        raise, while the next ones are put back: the exception is kept in
        :attr:`early` (raised as ``os.fork`` returns, see
        :func:`release_in_parent`; raised here, in a fork hook, Python reported
        it as ignored and lost it, review 38) and the rest are put back all the
        same (only a signal within the microseconds of the ``finally`` could
        cut that short).
        """
        came: list[int] = []
        done = False
        try:
            while not done:
                try:
                    for hold in reversed(self.holds):
                        hold.restore()  # once: again, nothing
                        again = hold.pending and hold.signum not in came
                        if again and not _woken_already(hold.previous):
                            came.append(hold.signum)
                        hold.pending.clear()
                    self._put_back_cut_short()
                    done = True
                except BaseException as error:  # a handler put back, its signal come again
                    if self.early is None:
                        self.early = error
        finally:
            if not done:
                self._put_back_cut_short()
        return came

    def _put_back_cut_short(self) -> None:
        """Put back the handlers of the holds cut short as they started (their own in place)."""
        for hold in self.holds:
            if _getsignal(hold.signum) == hold.hold:
                _put_back(hold.signum, hold.previous)


def _woken_already(handler: Any) -> bool:
    """Whether a signal held from ``handler`` was handed on already, by the wakeup fd.

    asyncio's ``loop.add_signal_handler`` installs a Python handler that does
    nothing (``_sighandler_noop``) and runs the callback when the loop reads
    the signal's number from its wakeup fd (``signal.set_wakeup_fd``), which
    Python's C handler writes whatever Python handler is in place, a hold's
    included: sent again after the fork, the signal was written twice and the
    callback ran twice (review 38). A held signal for that handler is not sent
    again.
    """
    module = sys.modules.get("asyncio.unix_events")
    return module is not None and handler is getattr(module, "_sighandler_noop", None)


def held_for_fork(fork_caller: FrameType | None, record: list[Any]) -> _ForkHold:
    """Hold every signal with a Python handler until the fork under way is done (a ``before`` hook).

    For fork hooks that take locks across a fork, perhaps waiting for another
    thread's: Python ignores an exception raised in a fork hook (it prints
    "Exception ignored") and forks all the same, so a Ctrl-C raised during a
    wait was lost, and the fork made without the lock; raised between taking a
    lock and recording it, or in an after hook before its releases, it left the
    lock held. The same went for any signal whose Python handler raises (a
    program's ``SIGTERM`` handler raising ``SystemExit``, review 37). Held, the
    wait goes on to the end, and :func:`release_in_parent` hands the signals
    held on as ``os.fork`` returns in the parent; the child drops them
    (:func:`release_in_child`). A second Ctrl-C is held as well: cutting the
    wait short would fork without the lock. ``SIGINT`` is held first (its hold
    is in place before any other signal's, so a Ctrl-C landing before it finds
    nothing held yet), then every other signal whose handler is a Python
    callable (about 5 µs a fork to look, where there is none). The hold is
    appended to ``record`` before any signal is held: a handler raising while
    the hold starts leaves what it held in ``record`` for the after hooks.
    Each signal that came is handed on once, by signal number (two of one kind are
    one, as the kernel delivers signals pending together), except one whose
    handler is asyncio's, which its loop has read from its wakeup fd already
    (:func:`_woken_already`). A signal landing before its own hold is in place
    runs its handler in the hook: an exception it raises is kept (review 38:
    reported as ignored there, it was lost) and raised as ``os.fork`` returns
    (:func:`release_in_parent`). ``fork_caller`` is the frame that called
    ``os.fork`` (the hook's caller: C code adds no frame). Nothing is held
    outside the main thread of the main interpreter (see
    :func:`interrupts_deferred`).

    Examples
    --------
    >>> import sys
    >>> from navkit._shared.interrupts import held_for_fork, release_in_parent
    >>> record = []
    >>> hold = held_for_fork(sys._getframe(), record)  # a Ctrl-C from here on waits for the fork
    >>> record == [hold]
    True
    >>> release_in_parent(hold)  # no fork made: nothing held, the handlers are back
    """
    hold = _ForkHold(fork_caller)
    record.append(hold)
    hold.start()
    return hold


def release_in_parent(hold: _ForkHold | None) -> None:
    """End :func:`held_for_fork`'s hold in the parent (an ``after_in_parent`` hook).

    The handlers from before are put back, and each signal held is handed to
    its handler once ``os.fork`` has returned to its caller, not here: Python
    runs the hooks registered after this one next (logging's releases its
    lock), and an exception in a hook is ignored, its work left undone. A
    profile function sees the return and hands the signals on through a
    pending call (:func:`_hand_on_as_fork_returns`). Where it cannot (a
    profiler in use, an early exception to raise there, a handler installed
    outside Python) each is sent again (to the process, to whatever handles
    it then), a second byte on the wakeup fd: a thread of a few milliseconds
    watches the main thread's frames for the return (a Python signal handler
    cannot tell: it would run at the first point Python checks for signals,
    inside a hook).
    """
    if hold is None:
        return
    came = hold.restore()
    caller, hold.fork_caller = hold.fork_caller, None
    early, hold.early = hold.early, None  # no call here: a signal could land on it
    try:
        # The sender first: raised here (a profiler in use), the early exception took
        # the signals held with it, never sent again (review 39).
        if came and (early is not None or not _hand_on_as_fork_returns(hold, caller, came)):
            threading.Thread(
                target=_interrupt_after_fork,
                args=(caller, caller.f_lasti if caller is not None else -1, came),
                name="navkit-held-ctrl-c",
                daemon=True,
            ).start()
    finally:
        # And the early exception whatever became of the sender: a thread that
        # could not start (the fork took the last process RLIMIT_NPROC allows)
        # took it with it (review 40).
        if early is not None:
            _raise_as_fork_returns(caller, early)


def _hand_on_as_fork_returns(hold: _ForkHold, caller: FrameType | None, came: list[int]) -> bool:
    """Hand ``came`` to their handlers once ``os.fork`` has returned to ``caller`` (False: cannot).

    Sent again with ``os.kill`` (:func:`_interrupt_after_fork`), a signal held
    during the fork reached the wakeup fd a second time (review 41, WAKEUP's
    strict xfail). Where each signal's handler is a Python callable (not one
    installed outside Python behind it, which only the system's delivery
    reaches) and no profiler is in use, a profile function hands them on at
    the caller's first event after the return, through a pending call
    (:func:`_hand_on_later`): the wakeup fd keeps the one byte of the
    system's delivery.
    """
    if caller is None or sys.getprofile() is not None or _HANDING_ON[0]:
        return False
    for held in hold.holds:
        if held.signum in came and (held.outside or not callable(_getsignal(held.signum))):
            return False
    at = caller.f_lasti
    came = sorted(came)  # by signal number, as Python runs pending ones

    def profile(frame: FrameType, event: str, arg: Any) -> None:
        if frame is caller or (frame.f_back is caller and caller.f_lasti != at):
            sys.setprofile(None)
            if not _hand_on_later([], came):  # (the last act: see _hand_on_later)
                _hand_signals_on(came, frame)

    sys.setprofile(profile)
    return True


def _raise_as_fork_returns(caller: FrameType | None, error: BaseException) -> None:
    """Raise ``error`` in this thread at its first event after ``os.fork`` returns to ``caller``.

    For an exception a signal's handler raised in the before hook, before its
    signal was held (:attr:`_ForkHold.early`): raised there, Python reported it
    as ignored and lost it (review 38). A profile function (``sys.setprofile``)
    raises it at the caller's next call or return once ``os.fork`` has returned
    (its instruction moved on: the after hooks registered after this one are
    called from it before). Where a profiler is in use already, or the caller
    is unknown, it is raised here, as before.
    """
    if caller is None or sys.getprofile() is not None:
        raise error
    at = caller.f_lasti

    def profile(frame: FrameType, event: str, arg: Any) -> None:
        if frame is caller or (frame.f_back is caller and caller.f_lasti != at):
            sys.setprofile(None)
            raise error

    sys.setprofile(profile)


def _interrupt_after_fork(caller: FrameType | None, at: int, came: list[int]) -> None:
    """Send the signals ``came`` once the main thread has left ``caller``'s ``os.fork``."""
    main = threading.main_thread().ident
    while caller is not None:
        frame = sys._current_frames().get(main) if main is not None else None
        inside = frame is caller or _called_from(frame, caller)
        if not inside or caller.f_lasti != at:  # returned (its next instruction), or gone
            break
        time.sleep(0.0005)
    for signum in came:
        os.kill(os.getpid(), signum)


def _called_from(frame: FrameType | None, caller: FrameType) -> bool:
    """Whether ``caller`` is among ``frame``'s callers (not ``frame`` itself)."""
    outer = frame.f_back if frame is not None else None
    while outer is not None:
        if outer is caller:
            return True
        outer = outer.f_back
    return False


def release_in_child(hold: _ForkHold | None) -> None:
    """End :func:`held_for_fork`'s hold in a forked child: the signals held were the parent's."""
    if hold is None:
        return
    caller, hold.fork_caller = hold.fork_caller, None
    hold.early = None  # the parent's
    hold.restore()
    held: Any = hold  # (its early set again by restore)
    early, hold.early = held.early, None
    if early is not None:  # the child's own signal, come as its handler was put back
        _raise_as_fork_returns(caller, early)


def release_others_in_child() -> None:
    """End, in a forked child, the holds of the parent's main thread still in place.

    For a child forked by a thread other than the main one. Only the main
    thread holds signals (:func:`held_for_fork`, :func:`interrupts_deferred`):
    a child forked while the main thread's own fork waited in its hook (for
    the locks this fork held) copied that hold's handlers, which nothing in the
    child ends, and every Ctrl-C in the child was kept for good (review 37).
    The handlers from before are put back, the signals held dropped (the
    parent's).
    """
    _drop_watched()
    for signum in (signal.SIGINT, *_SIGNALS):
        handler = signal.getsignal(signum)
        while getattr(handler, "__func__", None) in (_Hold.hold, StepHold.hold):
            hold: _Hold = handler.__self__  # type: ignore[union-attr]
            hold.pending.clear()
            if hold.restored:  # put back already: nothing more to do
                break
            hold.restore()
            handler = signal.getsignal(signum)


#: ``signal.getsignal`` without its wrapper's conversion to ``signal.Handlers`` (0.05 µs,
#: not 0.4: a fork looks at every signal's).
_getsignal: Callable[[int], Any] = getattr(
    importlib.import_module("_signal"), "getsignal", signal.getsignal
)
#: ``signal.signal`` without its wrapper's conversions to and from ``signal.Handlers``
#: (an enum's lookups, a ValueError made and caught for a callable handler): put back
#: after a fork, in pages the parent now shares with its child, they cost about 0.15 ms
#: of page copies a fork (review 38).
_setsignal: Callable[[int, Any], Any] = getattr(
    importlib.import_module("_signal"), "signal", signal.signal
)


def _put_back(signum: int, handler: Any) -> None:
    """``signal.signal(signum, handler)`` through :data:`_setsignal` (which takes plain ints)."""
    _setsignal(signum, int(handler) if isinstance(handler, int) else handler)


#: The signals but SIGINT that can have a handler (a fork holds those with Python's).
_SIGNALS: tuple[int, ...] = tuple(
    sorted(
        int(signum)
        for signum in signal.valid_signals()
        if signum != signal.SIGINT
        and signum not in {getattr(signal, "SIGKILL", -1), getattr(signal, "SIGSTOP", -1)}
    )
)


#: Per signal, an empty dict whose lookup of a missing key makes the signal pending again
#: (``_thread.interrupt_main``, called from C). A handler that made its signal pending with
#: an ordinary call was run again at once, inside itself: CPython runs pending handlers as
#: a call of C code returns, and again at the next, without end. A subscript runs no such
#: check, nor does the handler's return, so the signal comes back at the next delivery
#: point after the handler (see :class:`StepHold`). One for every signal a handler can
#: be set for (:class:`StepHolds` holds each with a Python handler).
_PENDING_AGAIN: dict[int, collections.defaultdict[int, None]] = {
    # (typed for signal.Signals, but any signal number is taken: real-time ones too)
    signum: collections.defaultdict(functools.partial(cast(Any, _thread.interrupt_main), signum))
    for signum in (int(signal.SIGINT), *_SIGNALS)
}


def _pend_again(signum: int) -> None:
    """Make ``signum`` pending again (``_thread.interrupt_main``, see :data:`_PENDING_AGAIN`).

    Python writes the signal's number to the wakeup fd (``signal.set_wakeup_fd``)
    once more each time: only where :func:`_watch` cannot be used.
    """
    again = _PENDING_AGAIN[signum]
    again.clear()
    again[0]  # a lookup calling interrupt_main from C (see _PENDING_AGAIN)


#: The step holds whose signal came inside a step, waiting for the step's end
#: (:func:`_watch`), in the order they came; the main thread's only.
_WATCHED: list[StepHold] = []
#: Whether :func:`_watch` is going (leaving with an exception, or a profile function
#: about to be set in its place): a signal held meanwhile pends itself.
_WATCH_GOING = [False]
#: The program's profile function :func:`_watch` stands in front of (None: none).
_CHAINED: list[Any] = [None]
try:
    _posixsubprocess: Any = importlib.import_module("_posixsubprocess")
except ImportError:  # not POSIX
    _posixsubprocess = None
#: C functions that run Python code whose exceptions Python ignores (fork hooks): a signal
#: due as one is called is handed on before it (:func:`_watch`).
_FORKS = tuple(
    getattr(module, name)
    for module, name in (
        (os, "fork"),
        (os, "forkpty"),
        (_posixsubprocess, "fork_exec"),  # (a Popen's preexec_fn runs the hooks)
    )
    if hasattr(module, name)
)
#: C functions that set the thread's profile function in :func:`_watch`'s place.
_PROFILE_SETTERS = tuple(
    function
    for function in (sys.setprofile, getattr(sys, "_setprofileallthreads", None))
    if function is not None
)


def _watch(frame: FrameType, event: str, arg: Any) -> None:
    """The main thread's profile function while a signal is held: hands it on after the step.

    A signal held in a step (:meth:`StepHold.hold`) used to be made pending
    again (``_thread.interrupt_main``) at every delivery point of the step
    until it was done, and each time Python's C code wrote the signal's
    number to the wakeup fd (``signal.set_wakeup_fd``: asyncio's, trio's, Qt's
    event loops) once more: hundreds of bytes for one signal, and with
    ``warn_on_full_buffer`` a full buffer printed "Exception ignored when
    trying to write to the signal wakeup fd" at every point after (review 40,
    REVD). Nothing in Python makes a signal pending without that write. So
    the hold notes the signal and sets this function (``sys.setprofile``, the
    main thread's only) instead. At the first Python function's entry or C
    function's return outside the step (``call`` and ``c_return`` events:
    where Python would have run the pending handler) it takes itself away
    and hands the signals on through a pending call (:func:`_hand_on_later`),
    which runs at the point where Python checks for signals right after the
    event, outside this callback (run inside it up to review 41, the handlers
    were missed by trace and profile functions, and a signal held in a
    handler's own step waited for the handler's end: REVWATCH's findings):
    each to the handler in place then, in signal order, as Python runs
    pending ones (the hold's own ``hold`` method, which delivers it, or holds
    it again where that point is in a step; or another installed meanwhile;
    none for ``SIG_IGN``/``SIG_DFL``, which Python skips). The wakeup fd has
    the one byte the system's delivery wrote. Not at a C call's start
    (Python runs handlers after the call, not before) but that of ``os.fork``,
    whose hooks' Python code would get it, their exceptions ignored: there
    the signals are handed on at once, in this function, before the call.
    Not at a return (a handler's exception would be raised inside the
    returning frame's ``try`` blocks, a step's; the caller's next event comes
    at once). The one delivery point without an event is a loop's turn: a
    loop of plain operations (no call) right after a step gets the signal at
    its first call or its end, not at once. Nothing runs until a signal comes
    in a step; then a few µs an event (the step's test, a walk of the
    stack: 0.7–2.6 µs measured in a real compile, review 42) until the step
    is done. Put back by the program with nothing
    held (a profile function it saved while this one was in place), it
    takes itself away at its first event, the program's own back.

    A program's profile function in place as a signal is held (a profiler,
    a debugger's) is called first at every event, and put back after the
    step. A profiler of C code in place (cProfile's, which ``sys.getprofile``
    returns as a profiler object, not a function Python code can call) leaves
    the profile slot to it: this function is then the trace function
    (``sys.settrace``) instead, which sees function entries only (on Python
    3.11 a signal made pending again at a function's entry in a step came
    back there for good: REVSIG's spin, review 41). Where this function
    cannot stay, the signals are made pending again (a byte more each on the
    wakeup fd): a C profiler and a trace function both in place as a signal
    is held (made pending again at each point of the step, and on Python
    3.11 the spin at a function's entry in it), one about to be set (a call
    of ``sys.setprofile``, whose return would find this function gone), an
    exception leaving this function (Python takes it away, with the
    program's), a signal held in the steps of a handler run by the pending
    call (pending calls do not nest), or this function found taken away by
    other means (a C profiler's start, a tracer set in the trace slot) when
    the hold ends (:func:`rewatch`). A C profile function set without an
    object (yappi's: ``sys.getprofile`` returns None) cannot be seen: it is
    replaced, and not put back.

    While a signal is held ``sys.getprofile()`` (``sys.gettrace()`` under a C
    profiler) returns this function, not the program's: shown, not hidden
    (review 43, SIGREV2). Hiding it meant replacing ``sys.getprofile`` and
    ``sys.gettrace`` for the whole process (every debugger, coverage tool and
    profiler calls them) for the microseconds to milliseconds of a step, and
    C code reading the thread's slot would still see it; a program that saves
    what it read and sets it back later is handled (above). Told apart by
    identity: ``sys.getprofile() is interrupts._watch``.
    """
    due: list[StepHold] = []
    try:
        chained = _CHAINED[0]
        if chained is not None:
            chained(frame, event, arg)
            now: Any = sys.getprofile()  # (a C profiler's object too, not callable)
            if now is not _watch:  # it set another (or none): this one stands in front of that
                if now is not None and not callable(now):
                    _pend_watched()
                    return
                chained = _CHAINED[0] = now
                sys.setprofile(_watch)
        if not _WATCHED:
            # Put back by the program with nothing held (``p = sys.getprofile()`` while a
            # signal was held, ``sys.setprofile(p)`` after): it stayed for good, a walk
            # of the stack an event, and signals held later were made pending again at
            # every point of their steps (review 42, SIGFIX). It leaves, the program's
            # own profile function back.
            _WATCH_GOING[0] = False
            _unwatch(chained)
            return
        at_once = False
        if event == "c_call":
            if arg in _PROFILE_SETTERS:
                _pend_watched()  # the last thing done: pending as the call returns
                return
            # os.fork runs its hooks' Python code before its return: handed on there,
            # a KeyboardInterrupt was reported as ignored and lost, and navkit's own
            # fork hook skipped (review 42, REVHOLD). Handed on before the call
            # instead (an exception here: the call not made).
            if arg not in _FORKS:
                return
            at_once = True
        elif event != "call" and event != "c_return":
            return
        inside: dict[Callable[[FrameType | None], bool], bool] = {}
        for hold in _WATCHED:
            step = inside.get(hold.critical)
            if step is None:
                step = inside[hold.critical] = hold.critical(frame)
            if not step:
                due.append(hold)
        if not due:
            return
        for hold in due:
            _WATCHED.remove(hold)
        if not _WATCHED:
            _unwatch(chained)  # the program's profile function back (or none)
        due.sort(key=lambda hold: hold.signum)
        if at_once:
            _hand_on(due, frame)
            return
        if _hand_on_later(due):
            return
        if chained is not None or _HANDING_ON[0]:
            # Pending again, handed on by Python (an exception from here would take the
            # program's profile function away too; in a handler handed a signal by
            # _hand_on_later, a pending call waits for that handler's end).
            _pend_held(due)
            return
        _hand_on(due, frame)
    except BaseException:
        # Python takes this function away as the exception leaves it (the program's
        # with it): the signals held meanwhile (in a handler's own step) are made
        # pending again instead, and so are those due here but not yet handed on
        # (another signal's handler raising here first: they were lost, and their
        # holds never ended; review 41, REVWATCH), and those still watched (another
        # signal's handler, or the program's profile function, raising before the
        # hand-on: they waited for the hold's end; review 42, REVHOLD).
        _WATCHED.extend(hold for hold in due if hold.again and hold not in _WATCHED)
        _CHAINED[0] = None
        _pend_watched()
        raise


def _unwatch(chained: Any) -> None:
    """Take :func:`_watch` away: the program's profile function ``chained`` back, or no tracer."""
    if sys.gettrace() is _watch:
        sys.settrace(None)
    if sys.getprofile() is _watch:
        sys.setprofile(chained)


def _pend_watched() -> None:
    """Make the signals :func:`_watch` waits for pending again, all at once; the caller's last act.

    From C, with no delivery point from the first to the return (see
    :data:`_PENDING_AGAIN`: a loop's each turn is one, where a signal made
    pending came back, was held and made pending again, without end). One
    held from here until :func:`_watch` is set again makes itself pending.
    """
    _WATCH_GOING[0] = True
    held = list(_WATCHED)
    _WATCHED.clear()
    _pend_held(held)


def _pend_held(held: list[StepHold]) -> None:
    """Make the signals of ``held`` pending again, all at once; the caller's last act."""
    if held:
        # (typed for signal.Signals, but any signal number is taken)
        interrupt: Callable[[int], None] = cast(Any, _thread.interrupt_main)
        pend: collections.defaultdict[int, object] = collections.defaultdict(
            functools.partial(collections.deque, map(interrupt, [h.signum for h in held]), 0)
        )
        pend[0]  # a lookup calling them from C


def rewatch() -> None:
    """Make the signals held for :func:`_watch` pending again if it was taken away meanwhile.

    A profiler started from C (``PyEval_SetProfile``) in a step, or after
    it before the first event, puts its function in :func:`_watch`'s place
    unseen: the signals would wait for good, and their holds with them
    (``StepHolds.restored`` never true, so compile_gc began no hold again).
    Checked as a hold ends and as the next hold would begin; then they come
    at the next delivery point. Nothing is done while :func:`_watch` is in
    place, or where nothing is held (about 0.1 µs).

    Examples
    --------
    >>> from navkit._shared.interrupts import rewatch
    >>> rewatch()  # nothing held: nothing done
    """
    if not _DUE and not _WATCHED:
        return
    if _DUE:
        # A pending call whose hand-on was cut short before it began (another
        # signal's exception at its first line): its signals, made pending again.
        # (Cancelled, kept until its call has begun: freed, a call still queued
        # would be handed a freed object.)
        held = [hold for item in _DUE if not item.done for hold in item.holds if hold.again]
        for item in _DUE:
            item.done = True
        _DUE[:] = [item for item in _DUE if not item.ran]
        held = [hold for hold in held if hold not in _WATCHED]
    else:
        held = []
    if _WATCHED and sys.getprofile() is not _watch and sys.gettrace() is not _watch:
        _WATCH_GOING[0] = True  # (as _pend_watched)
        held.extend(_WATCHED)
        _WATCHED.clear()
    if held:
        _pend_held(held)


class _Due:
    """Held signals due, handed on by a pending call (see :func:`_hand_on_later`).

    ``signums``: signals held during a fork instead, for the handlers in place
    (:func:`release_in_parent`).
    """

    __slots__ = ("done", "holds", "pid", "ran", "signums")

    def __init__(self, holds: list[StepHold], signums: list[int] | None = None) -> None:
        self.holds = holds
        self.signums = signums
        #: The process whose pending call this is (CPython keeps pending calls across
        #: a fork: the child runs the parent's, review 42, REVHOLD).
        self.pid = os.getpid()
        #: Whether its call has begun; whether it is done (or cancelled: nothing to do).
        self.ran = False
        self.done = False

    def __bool__(self) -> bool:
        """Hand the signals on (the pending call is ``PyObject_IsTrue`` of this object)."""
        # Kept in _DUE until here: the pending call holds only its address.
        self.ran = True
        if self.done:  # cancelled (a forked child's, or found cut short)
            if self in _DUE:
                _DUE.remove(self)
            return False
        self.done = True
        # (No delivery point from here to the try, nor from its end to the decrement:
        # another signal's exception landing at the list's remove, outside the try,
        # lost these signals and left the count up for good; review 42, REVHOLD.)
        _HANDING_ON[0] += 1
        try:
            _DUE.remove(self)
            if self.pid != os.getpid():
                pass  # the parent's, run in a forked child: its signals are the parent's
            elif self.signums is not None:
                _hand_signals_on(self.signums, sys._getframe(1))
            else:
                _hand_on(self.holds, sys._getframe(1))  # the frame Python was running
        except BaseException:
            _HANDING_ON[0] -= 1
            # Those not handed on (another signal's exception first): pending again.
            _pend_held([hold for hold in self.holds if hold.again and hold not in _WATCHED])
            raise
        _HANDING_ON[0] -= 1
        return False


#: The :class:`_Due` whose pending call has not yet run (kept alive until then).
_DUE: list[_Due] = []
#: How many :class:`_Due` are handing signals on (nested: a handler's own step).
_HANDING_ON = [0]
#: ``Py_AddPendingCall`` and the address of ``PyObject_IsTrue``, once looked up (empty
#: where ctypes or the C API cannot be had).
_PENDING_CALL: list[Any] = []


def _hand_on_later(due: list[StepHold], signums: list[int] | None = None) -> bool:
    """Hand ``due`` on where Python runs its pending calls (False: cannot, nothing done).

    Handed on inside :func:`_watch`, the handlers ran in the profile callback,
    where CPython makes no trace or profile events (a debugger's breakpoint, a
    coverage tool, a profiler missed them) and a signal held in a handler's
    own step waited for the handler's end (review 41, REVWATCH). A pending call
    (``Py_AddPendingCall``) runs in the main thread's evaluation loop at the
    next point it checks for signals (right after the event here), as Python's
    own signal handlers do, with no byte on the wakeup fd. Its function is
    ``PyObject_IsTrue`` of a :class:`_Due`, whose ``__bool__`` hands the
    signals on: its -1 on an exception makes Python raise it there, as it
    raises a handler's. Pending calls do not nest: inside a handler run so
    this returns False. True: the caller's last act is to return (a call in
    between would run the pending call there, in the profile callback).
    """
    if _HANDING_ON[0]:
        return False
    if not _PENDING_CALL:
        add = address = None
        try:
            import ctypes

            add = ctypes.pythonapi.Py_AddPendingCall
            add.argtypes = [ctypes.c_void_p, ctypes.c_void_p]
            add.restype = ctypes.c_int
            address = ctypes.cast(ctypes.pythonapi.PyObject_IsTrue, ctypes.c_void_p).value
        except (ImportError, AttributeError, OSError):
            add = None
        _PENDING_CALL.extend((add, address))
    add, address = _PENDING_CALL
    if add is None:
        return False
    item = _Due(due, signums)
    _DUE.append(item)
    pend: collections.defaultdict[int, int] = collections.defaultdict(
        functools.partial(add, address, id(item))
    )
    # A lookup calling it from C, and no call after: Python runs pending calls as a
    # call returns, and one run here ran inside the profile callback.
    if pend[0] == 0:
        return True
    _DUE.remove(item)  # the queue full (32 calls): nothing pending
    return False


def _hand_signals_on(signums: list[int], frame: FrameType) -> None:
    """Hand each of ``signums`` to the Python handler in place, the next whatever it raises."""
    try:
        handler = _getsignal(signums[0])
        if callable(handler):
            handler(signums[0], frame)
    finally:
        if len(signums) > 1:
            _hand_signals_on(signums[1:], frame)


def _hand_on(due: list[StepHold], frame: FrameType) -> None:
    """Hand each held signal of ``due`` to the handler in place, the next whatever it raises.

    A hold's ``again`` stays set until its signal is handed on (the hold's own
    ``hold`` clears it as it delivers the signal, :meth:`StepHold._hand_over`):
    another signal's exception landing before leaves it to be made pending
    again (cleared first, it was lost for good; review 42, REVHOLD). Handed to
    another handler (put in place meanwhile), it is cleared here with no
    delivery point from there to the call: cleared before the C call
    ``callable(handler)``, another signal's exception landing as that returned
    lost it (review 43, SIGREV2). What remains is a Python
    handler's own entry, a delivery point before its first line, as for the
    handlers CPython runs itself (it clears a signal's flag before its call).
    """
    hold = due[0]
    try:
        handler = _getsignal(hold.signum)
        if getattr(handler, "__self__", None) is hold:
            handler(hold.signum, frame)  # (the hold's own: it clears again itself)
        elif callable(handler):
            hold.again = False  # the last act before the call (no delivery point between)
            handler(hold.signum, frame)
        else:
            hold.again = False  # none put in place meanwhile (SIG_IGN, SIG_DFL)
    finally:
        if len(due) > 1:
            _hand_on(due[1:], frame)


def _drop_watched() -> None:
    """In a forked child, forget the parent's held signals (as Python drops its pending ones)."""
    for hold in [*_WATCHED, *(hold for item in _DUE for hold in item.holds)]:
        hold.again = False
    _WATCHED.clear()
    for item in _DUE:  # cancelled, kept until their calls (copied too) have begun
        item.done = True
    _WATCH_GOING[0] = False
    if sys.getprofile() is _watch:
        sys.setprofile(_CHAINED[0])
    if sys.gettrace() is _watch:
        sys.settrace(None)
    _CHAINED[0] = None


if hasattr(os, "register_at_fork"):
    os.register_at_fork(after_in_child=_drop_watched)


#: The C library's ``sigaction``, once looked up (None where there is none), then the
#: ``ctypes`` types of an action's buffer and of its first field (the handler).
_SIGACTION: list[Any] = []


def _sigaction() -> Any:
    """The C library's ``sigaction`` (POSIX), or None."""
    if not _SIGACTION:
        function = buffer = address = None
        if os.name == "posix":
            try:
                import ctypes

                function = ctypes.CDLL(None, use_errno=True).sigaction
                buffer = ctypes.c_char * 512  # larger than any system's struct sigaction
                address = ctypes.c_void_p
            except (ImportError, OSError, AttributeError):
                function = None
        _SIGACTION.extend((function, buffer, address))
    return _SIGACTION[0]


def _system_action() -> Any:
    """``SIGINT``'s ``struct sigaction`` as the system holds it (an opaque buffer), or None."""
    return _action_of(signal.SIGINT)


def _action_of(signum: int) -> Any:
    """``signum``'s ``struct sigaction`` as the system holds it (an opaque buffer), or None.

    The types made once (not ``ctypes.create_string_buffer`` and an ``import`` a
    call): read after a fork, in pages the parent now shares with its child,
    fewer objects touched are fewer pages copied (review 38).
    """
    sigaction = _sigaction()
    if sigaction is None:
        return None
    action = _SIGACTION[1]()
    return action if sigaction(signum, None, action) == 0 else None


def _handler_address(action: Any) -> int | None:
    """The handler of an action from :func:`_system_action` (its first field on POSIX systems)."""
    if action is None:
        return None
    address: int | None = _SIGACTION[2].from_buffer(action).value
    return address or 0


def _set_system_action(action: Any, signum: int = signal.SIGINT) -> None:
    """Make ``action`` (from :func:`_system_action`) ``signum``'s action again."""
    _sigaction()(signum, action, None)


def _deliver(handler: Any, signum: int, frame: FrameType | None) -> None:
    """Hand ``signum`` to ``handler`` as the interpreter would have."""
    if callable(handler):
        handler(signum, frame)
    elif handler == signal.SIG_DFL:
        # The default action (ending the process) is the operating system's: raise
        # the signal again now that its default handler is back.
        signal.raise_signal(signum)
    # SIG_IGN: ignored, as it would have been.
