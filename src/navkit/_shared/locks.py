"""Process-wide locks that forked children get afresh; one caller at a time (private).

A module-level lock held by some thread when the process forks stays held in
the child, where that thread does not exist: the child's first ``with`` on it
would wait for ever. :class:`ForkSafeLock` makes itself anew in the child
(``os.register_at_fork``; Windows cannot fork).

:func:`one_caller` guards the methods of a stateful object documented as
used by one thread at a time: a call made while another is under way (from
another thread, or a signal handler's in the same thread) raises a clear
``RuntimeError`` instead of corrupting the object's state.
"""

from __future__ import annotations

import functools
import os
import sys
import threading
from _thread import get_ident as _get_ident
from collections.abc import Callable
from types import FrameType, TracebackType
from typing import Any, Concatenate, ParamSpec, Protocol, TypeVar

__all__ = ["ForkSafeLock", "one_caller"]

_P = ParamSpec("_P")
_R = TypeVar("_R")


class _Guarded(Protocol):
    """An object with the callers list :func:`one_caller` keeps (a ``_callers`` slot).

    Its tokens are ``(thread ident, method name, object)`` tuples (``Any``: a
    class may declare the list as it likes; only :func:`one_caller` fills it).
    """

    _callers: list[Any]


_G = TypeVar("_G", bound=_Guarded)


def one_caller(
    method: Callable[Concatenate[_G, _P], _R],
) -> Callable[Concatenate[_G, _P], _R]:
    """Make ``method`` refuse to run while another guarded method of the object runs.

    The object keeps a list ``_callers``, empty at rest (give a copy or an
    unpickled object an empty one: a copy made while another thread calls the
    original is not in use). Each call appends a token (its thread, its
    method, an object of its own) and runs only if its token is the first; it
    takes that token out as it returns or raises, whatever the point (a
    ``KeyboardInterrupt`` included: the append, a C call, is done or not before
    one can land, and the ``finally`` takes out only that token: no other
    token equals it, so a signal handler's call of the same method, refused,
    takes out its own and not the runner's; with (thread, method) tokens it
    took the runner's, and the runner, at its check, was refused too).
    Appending is atomic, so of two
    threads calling at once exactly one runs and the other gets
    ``RuntimeError``, which says whether the call under way is another
    thread's or the same thread's (a signal handler's), or, in a forked
    child, was a thread's of the parent when it forked: that call never ends
    here, and the object, perhaps half-updated, refuses every call (review
    37; worked out on the refusal only). The cost is about half a
    microsecond a call: for methods of milliseconds.

    Examples
    --------
    >>> class Counter:
    ...     __slots__ = ("_callers", "n")
    ...     def __init__(self) -> None:
    ...         self._callers, self.n = [], 0
    ...     @one_caller
    ...     def bump(self, inner: bool = False) -> None:
    ...         self.n += 1
    ...         if inner:
    ...             self.bump()  # as a signal handler's call would
    >>> counter = Counter()
    >>> counter.bump()
    >>> try:
    ...     counter.bump(inner=True)
    ... except RuntimeError as error:
    ...     print(str(error)[:55])
    Counter.bump was called during this Counter's own bump,
    >>> counter.n, counter._callers
    (2, [])
    """
    name = method.__name__

    @functools.wraps(method)
    def guarded(self: _G, /, *args: _P.args, **kwargs: _P.kwargs) -> _R:
        callers = self._callers
        # Equal to no other token (its object): list.remove takes out the first equal
        # one, which for (thread, method) alone was the runner's when a signal
        # handler's call of the same method was refused.
        token = (_get_ident(), name, object())
        try:
            callers.append(token)
            if callers[0] is not token:
                raise RuntimeError(_in_use(type(self).__name__, name, callers[0], callers))
            return method(self, *args, **kwargs)
        finally:
            callers.remove(token)

    return guarded


#: This process's id when this module was imported: another one is a forked child's.
_PID = os.getpid()


def _in_use(cls: str, name: str, other: tuple[Any, ...], callers: list[Any] | None = None) -> str:
    """The message of a call ``name`` refused because ``other`` (a token) is under way.

    ``other`` starts with the thread ident and the method name of the call
    under way; its call holds it in a local variable named ``token`` (see
    :func:`_running_here`). ``callers``, the list it was read from, if given,
    is read again (a call that ended meanwhile is not listed). Worked out on
    the refusal only: in a forked child, whether the call is under way in this
    process at all, and then in which thread.
    """
    ident, running = other[0], other[1]
    if (
        os.getpid() != _PID
        and not _running_here(other)
        and (callers is None or any(listed is other for listed in callers))
    ):
        # A forked child, and no thread of it is in the call: its thread was
        # another of the parent's, which the child does not have (a token is
        # taken out only by its own call's ``finally``).
        return (
            f"{cls}.{name} was called while a call of this {cls}'s {running} was under "
            "way in a thread of the parent process when this process was forked: "
            f"the {cls} may be half-updated, and takes no more calls here (make a new one)"
        )
    if ident == threading.get_ident():
        return (
            f"{cls}.{name} was called during this {cls}'s own {running}, in the same "
            f"thread (from a signal handler?): a {cls} takes one call at a time"
        )
    return (
        f"{cls}.{name} was called while another thread was in this {cls}'s {running}: "
        f"a {cls} is used by one thread at a time (one per thread, or a lock of your "
        "own around its calls)"
    )


def _running_here(wanted: tuple[Any, ...]) -> bool:
    """Whether some thread of this process is inside the guarded call that made ``wanted``.

    A thread in a call has a frame holding the token in its local ``token``
    (``one_caller``'s ``guarded``, or a class's own guard written the same
    way; this function's parameter and :func:`_in_use`'s are named
    otherwise), among the frames ``sys._current_frames`` gives (a thread made
    outside Python too, while it runs Python code). In a forked child, only
    the forking thread's frames are there. The thread ident alone cannot
    tell: a thread started in the child may get the ident of one of the
    parent's (glibc reuses the stacks of the threads the child lacks).
    """
    for top in sys._current_frames().values():
        frame: FrameType | None = top
        while frame is not None:
            if "token" in frame.f_code.co_varnames and frame.f_locals.get("token") is wanted:
                return True
            frame = frame.f_back
    return False


class ForkSafeLock:
    """A ``threading.Lock`` (or ``RLock``) used with ``with``, renewed in forked children.

    Parameters
    ----------
    reentrant : bool, default False
        An ``RLock``: the thread holding it may take it again.

    Examples
    --------
    >>> lock = ForkSafeLock()
    >>> with lock:
    ...     pass
    """

    __slots__ = ("__weakref__", "_lock", "_reentrant")

    def __init__(self, *, reentrant: bool = False) -> None:
        self._reentrant = reentrant
        self._lock: threading.Lock | threading.RLock = self._new()
        if hasattr(os, "register_at_fork"):
            os.register_at_fork(after_in_child=self._renew)

    def _new(self) -> threading.Lock | threading.RLock:
        return threading.RLock() if self._reentrant else threading.Lock()

    def _renew(self) -> None:
        self._lock = self._new()

    # ``with`` takes the lock's own (C) __enter__ and __exit__ through these
    # properties, and CPython runs no Python code between acquiring and the block,
    # or between the block and releasing. As Python methods calling them, a
    # KeyboardInterrupt delivered as the lock's __enter__ returned into ours, or on
    # entering our __exit__, left the lock held: the next ``with`` on a plain lock
    # waited for ever (review 26).
    @property
    def __enter__(self) -> Callable[[], bool]:
        return self._lock.__enter__

    @property
    def __exit__(
        self,
    ) -> Callable[
        [type[BaseException] | None, BaseException | None, TracebackType | None], None
    ]:
        return self._lock.__exit__
