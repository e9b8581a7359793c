"""Process-wide locks that forked children get afresh (private).

A module-level lock held by some thread when the process forks stays held in
the child, where that thread does not exist: the child's first ``with`` on it
would wait for ever. :class:`ForkSafeLock` makes itself anew in the child
(``os.register_at_fork``; Windows cannot fork).
"""

from __future__ import annotations

import os
import threading
from collections.abc import Callable
from types import TracebackType

__all__ = ["ForkSafeLock"]


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
