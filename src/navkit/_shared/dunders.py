"""Shared special methods for copying, comparing and printing navkit's objects (private).

* :func:`slot_state`: the ``__getstate__`` of an ordinary class with
  ``__slots__``, so that pickle protocols 0 and 1 take it as 2 to 5 do.
* :func:`record_eq` and :func:`record_hash`: ``__eq__`` and ``__hash__`` of a
  frozen dataclass whose fields may hold NaN ("does not apply"), equal to NaN.
* :func:`bounded_repr`: the ``__repr__`` of a frozen dataclass holding long
  tuples (a scan per line of a log), shortened as NumPy shortens long arrays.
"""

from __future__ import annotations

import math
from dataclasses import fields
from typing import Any

import numpy as np

__all__ = ["bounded_repr", "record_eq", "record_hash", "slot_state"]

#: Tuples longer than this show their first two items and their last.
_SHOWN = 3


def slot_state(obj: object) -> object:
    """``__getstate__`` of a class with ``__slots__``: Python's default state, under its own name.

    Pickle protocols 0 and 1 refuse an object whose class has ``__slots__``
    but inherits :meth:`object.__getstate__` ("a class that defines __slots__
    without defining __getstate__ cannot be pickled"), although that method
    returns the state every other protocol, :func:`copy.copy` and
    :func:`copy.deepcopy` use: ``(instance __dict__ or None, {slot: value})``.
    Assigned as ``__getstate__ = slot_state``, it returns that same state, so
    copies and pickles of protocols 2 to 5 are unchanged and older pickles load
    as before.

    Examples
    --------
    >>> import pickle
    >>> class Holder:
    ...     __slots__ = ("value",)
    ...     __getstate__ = slot_state
    ...     def __init__(self, value: int) -> None:
    ...         self.value = value
    >>> Holder(3).__reduce_ex__(0)[2]  # what protocol 0 pickles; refused without slot_state
    (None, {'value': 3})
    """
    return object.__getstate__(obj)


def _same(a: object, b: object) -> bool:
    """``a == b`` for field values, NaN equal to NaN, inside tuples too."""
    if isinstance(a, tuple) and isinstance(b, tuple):
        return len(a) == len(b) and all(_same(x, y) for x, y in zip(a, b, strict=True))
    if isinstance(a, (float, np.floating)) and isinstance(b, (float, np.floating)):
        return bool(a == b) or (math.isnan(a) and math.isnan(b))
    return bool(a == b)


def _hashable(value: object) -> object:
    """``value`` with every NaN replaced by one sentinel (``hash(nan)`` is per object)."""
    if isinstance(value, tuple):
        return tuple(_hashable(item) for item in value)
    if isinstance(value, (float, np.floating)) and math.isnan(value):
        return _NaN
    return value


class _NaNKey:
    """The stand-in of every NaN in :func:`record_hash`."""

    __slots__ = ()

    def __hash__(self) -> int:
        return 0x6E616E  # "nan"


_NaN = _NaNKey()


def record_eq(self: Any, other: Any) -> bool:
    """``__eq__`` of a frozen dataclass: the compared fields equal, NaN equal to NaN.

    The dataclass's own ``__eq__`` compares tuples of fields, which treats a
    NaN as equal only to the same float object: two runs giving the same
    figures, or a record and its pickle, compared unequal wherever a figure
    was NaN. Records of different classes compare as the dataclass's do
    (``NotImplemented``).

    Examples
    --------
    >>> from dataclasses import dataclass
    >>> @dataclass(frozen=True)
    ... class Figure:
    ...     value: float
    ...     __eq__ = record_eq
    ...     __hash__ = record_hash
    >>> Figure(float("nan")) == Figure(float("nan")), Figure(float("nan")) == Figure(1.0)
    (True, False)
    """
    if other.__class__ is not self.__class__:
        # The dataclass's own answer to another class; typeshed types it Any.
        return NotImplemented  # type: ignore[no-any-return]
    return all(
        _same(getattr(self, field.name), getattr(other, field.name))
        for field in fields(self)
        if field.compare
    )


def record_hash(self: Any) -> int:
    """``__hash__`` to go with :func:`record_eq`: every NaN hashes alike.

    Examples
    --------
    >>> from dataclasses import dataclass
    >>> @dataclass(frozen=True)
    ... class Figure:
    ...     value: float
    ...     __eq__ = record_eq
    ...     __hash__ = record_hash
    >>> hash(Figure(float("nan"))) == hash(Figure(float("nan")))
    True
    """
    return hash(tuple(_hashable(getattr(self, f.name)) for f in fields(self) if f.compare))


def _short(value: object) -> str:
    if not isinstance(value, tuple) or len(value) <= _SHOWN:
        return repr(value)
    head = ", ".join(repr(item) for item in value[:2])
    return f"({head}, ... {len(value) - 3} more ..., {value[-1]!r})"


def bounded_repr(self: Any) -> str:
    """``__repr__`` of a frozen dataclass: long tuples shown by their ends and length.

    The dataclass's own ``__repr__`` prints every item of a tuple field: a
    trace recording 600 scans, or a log of 2000, printed megabytes (in a
    notebook, a debugger or a failing test's report). Arrays are already
    shortened by NumPy; tuples of more than three items now show the first
    two, how many are left out, and the last.

    Examples
    --------
    >>> from dataclasses import dataclass
    >>> @dataclass(frozen=True)
    ... class Log:
    ...     name: str
    ...     items: tuple[int, ...]
    ...     __repr__ = bounded_repr
    >>> Log("a", (1, 2, 3)), Log("b", tuple(range(1000)))
    (Log(name='a', items=(1, 2, 3)), Log(name='b', items=(0, 1, ... 997 more ..., 999)))
    """
    parts = ", ".join(
        f"{field.name}={_short(getattr(self, field.name))}" for field in fields(self) if field.repr
    )
    return f"{type(self).__qualname__}({parts})"
