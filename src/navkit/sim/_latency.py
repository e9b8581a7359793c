"""Late delivery of sensor streams: a first-in, first-out delay line per stream."""

from __future__ import annotations

from collections import deque
from typing import Generic, TypeVar

from navkit._shared.frozen import restore_slots

__all__ = ["DelayLine"]

_T = TypeVar("_T")


class DelayLine(Generic[_T]):
    """Holds the items of one stream until their delivery time.

    The caller queues each item with its due time (:meth:`push_at`; the
    simulator computes the due times of a whole batch of readings at once, in
    steps of its clock), never before an item already queued, so items leave
    in the order they came in. Times are compared with a tolerance of 1e-9 s,
    so that an item due at ``t`` is delivered at step ``k`` when
    ``k / rate ≈ t``.

    An ordinary class with ``__slots__``: it changes as items pass. Copies
    (:func:`copy.copy` too), deep copies and pickles hold their own queue.

    Parameters
    ----------
    delay : float
        The stream's delivery delay, s, >= 0 (validated by the caller; kept as
        :attr:`delay`, the due times given to :meth:`push_at` include it).

    Examples
    --------
    >>> line = DelayLine(0.5)
    >>> line.push_at(0.5, "a"); line.push_at(0.6, "b")
    >>> line.pop_due(0.5), line.pop_due(0.55), line.pop_due(0.6)
    ([(0.5, 'a')], [], [(0.6, 'b')])
    """

    __slots__ = ("_delay", "_items")

    _EPS = 1e-9

    def __init__(self, delay: float) -> None:
        self._delay = float(delay)
        self._items: deque[tuple[float, _T]] = deque()

    def __copy__(self) -> DelayLine[_T]:
        """A shallow copy with its own queue (the queued items themselves shared)."""
        # Python's default state of a slotted object, a subclass's __dict__ and slots
        # included (what copy.deepcopy copies), so subclasses copy whole.
        reduced = self.__reduce_ex__(4)
        assert isinstance(reduced, tuple)
        cls = type(self)
        twin = cls.__new__(cls)
        restore_slots(twin, reduced[2])
        # Shared, a push or pop on one would change what the other delivers.
        twin._items = deque(self._items)
        return twin

    @property
    def delay(self) -> float:
        """The delivery delay, s."""
        return self._delay

    def push_at(self, due: float, item: _T) -> None:
        """Queue ``item`` due at ``due`` (not before any item already queued)."""
        self._items.append((due, item))

    def pop_due(self, now: float) -> list[tuple[float, _T]]:
        """Remove and return ``(due time, item)`` of every item due by ``now``, in order."""
        items = self._items
        if not items or items[0][0] > now + self._EPS:
            return []
        out = []
        while items and items[0][0] <= now + self._EPS:
            out.append(items.popleft())
        return out

    def __len__(self) -> int:
        return len(self._items)
