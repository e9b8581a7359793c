"""``with`` on navkit's process-wide locks, interrupted anywhere, leaves them free.

:class:`~navkit._shared.locks.ForkSafeLock` wrapped its lock in Python
``__enter__``/``__exit__`` methods: a ``KeyboardInterrupt`` delivered as the
lock's own ``__enter__`` returned inside them, or on entering the Python
``__exit__``, left the lock held, so the next ``with`` on a plain lock waited for
ever and other threads waited on a re-entrant one (found by review 26).
``with`` now calls the lock's own C methods, between which CPython runs no
Python code.
"""

from __future__ import annotations

import threading

import pytest

from interrupt_points import delivery_points, interrupted_at
from navkit._shared import files
from navkit._shared.locks import ForkSafeLock
from navkit.mapping import _grid
from navkit.mapping.io import _map_files
from navkit.sim import _world


def _free_elsewhere(lock: ForkSafeLock) -> bool:
    """Whether another thread can take ``lock`` now (and gives it back)."""
    took: list[bool] = []

    def take() -> None:
        got = lock._lock.acquire(timeout=2.0)
        took.append(got)
        if got:
            lock._lock.release()

    worker = threading.Thread(target=take)
    worker.start()
    worker.join(10.0)
    return took == [True]


LOCKS = {
    "plain": ForkSafeLock(),
    "reentrant": ForkSafeLock(reentrant=True),
    "renames": files.RENAME_LOCK,
    "warnings": _map_files._WARNINGS_LOCK,
    "geos": _world._GEOS_LOCK,
    "grid-locks": _grid._LOCK_MAKING,
}


@pytest.mark.parametrize("name", LOCKS)
def test_an_interrupted_with_leaves_the_lock_free(name: str) -> None:
    lock = LOCKS[name]

    def body() -> None:
        with lock:
            len(())  # a C call inside the block: an interrupt may land there too

    points = delivery_points(body)
    assert points >= 1  # the call inside the block at least
    for k in range(1, points + 2):
        interrupted_at(k, body)
        free = _free_elsewhere(lock)
        if not free:  # let go here (this thread took it), or later tests would wait
            lock._lock.release()
        assert free, f"held after an interrupt at point {k} of {points}"


def test_the_lock_still_excludes_and_reenters() -> None:
    plain, again = ForkSafeLock(), ForkSafeLock(reentrant=True)
    with plain:
        assert not _free_elsewhere(plain)
    assert _free_elsewhere(plain)
    with again, again:
        assert not _free_elsewhere(again)
    assert _free_elsewhere(again)
    assert plain.__enter__() is True  # the lock's own return value
    plain.__exit__(None, None, None)
    assert _free_elsewhere(plain)
