"""Restoring frozen dataclasses that hold read-only arrays (private).

``pickle`` and :func:`copy.deepcopy` rebuild a slotted dataclass from its field
values without running ``__post_init__``, and the arrays they copy come back
writable: a "frozen" record whose arrays can be changed in place. The records'
``__setstate__`` use :func:`restore_read_only` to set their arrays read-only
again; ordinary classes with ``__slots__`` use :func:`restore_slots`.
"""

from __future__ import annotations

from collections.abc import Collection, Mapping, Sequence
from dataclasses import fields
from typing import Any

import numpy as np

__all__ = ["restore_read_only", "restore_slots"]


def restore_read_only(record: Any, state: Sequence[Any], arrays: Sequence[str]) -> None:
    """Set ``record``'s fields from ``state`` (their values, in order); freeze ``arrays``.

    Parameters
    ----------
    record : dataclass instance
        The record being restored (its ``__setstate__``'s ``self``).
    state : sequence
        The field values, in field order (what a slotted dataclass pickles).
    arrays : sequence of str
        Names of the fields holding arrays to make read-only (None values skipped).

    Examples
    --------
    >>> import copy
    >>> from dataclasses import dataclass
    >>> @dataclass(frozen=True, slots=True)
    ... class Record:
    ...     values: np.ndarray
    ...     def __setstate__(self, state: list[Any]) -> None:
    ...         restore_read_only(self, state, ("values",))
    >>> copy.deepcopy(Record(np.zeros(2))).values.flags.writeable
    False
    """
    for field, value in zip(fields(record), state, strict=True):
        object.__setattr__(record, field.name, value)
    for name in arrays:
        array = getattr(record, name)
        if isinstance(array, np.ndarray):
            array.flags.writeable = False


def restore_slots(
    obj: Any,
    state: Any,
    *,
    read_only: Collection[str] = (),
    renamed: Mapping[str, str] | None = None,
) -> None:
    """Restore a slotted object from its default pickle state; freeze the arrays named.

    Parameters
    ----------
    obj : object
        The object being restored (its ``__setstate__``'s ``self``).
    state : tuple or dict
        Python's default state of a class with ``__slots__``: ``(instance
        __dict__ or None, {slot: value})``, so that subclasses (with a
        ``__dict__`` or slots of their own) copy whole; a bare ``{slot: value}``
        also loads.
    read_only : collection of str
        Slots holding arrays to make read-only (pickle and deepcopy hand back
        writable copies).
    renamed : mapping of str to str, optional
        Old slot names and the slots they are stored in now, for pickles made
        before a rename (an attribute that became a read-only property).

    Examples
    --------
    >>> import copy
    >>> class Holder:
    ...     __slots__ = ("values",)
    ...     def __init__(self) -> None:
    ...         self.values = np.zeros(2)
    ...         self.values.flags.writeable = False
    ...     def __setstate__(self, state: Any) -> None:
    ...         restore_slots(self, state, read_only=("values",))
    >>> copy.deepcopy(Holder()).values.flags.writeable
    False
    """
    instance, slots = state if isinstance(state, tuple) else (None, state)
    if instance:
        obj.__dict__.update(instance)
    for name, value in slots.items():
        if renamed is not None:
            name = renamed.get(name, name)
        if name in read_only and isinstance(value, np.ndarray):
            value.flags.writeable = False
        object.__setattr__(obj, name, value)
